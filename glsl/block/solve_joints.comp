#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The block solver's sweep over one colour, 8 lanes a body, with joints (block/solve.glsl):
// a world with joints sweeps with this one (and solve_tail_joints) only.
#define TB_BLOCK_JOINTS
#include "solve.glsl"
