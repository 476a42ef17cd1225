#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The block solver's sweep over the tail with joints (block/solve.glsl, solve_joints.comp).
#define TB_BLOCK_TAIL
#define TB_BLOCK_JOINTS
#include "solve.glsl"
