#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The block solver's sweep over one colour, 16 lanes a body (block/solve.glsl).
#define TB_BLOCK_LANES 16
#include "solve.glsl"
