#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The block solver's sweeps of a small world's step in one workgroup, 8 lanes a body, with
// joints (block/solve.glsl, TB_BLOCK_FUSED and TB_BLOCK_JOINTS).
#define TB_BLOCK_FUSED
#define TB_BLOCK_JOINTS
#include "solve.glsl"
