#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The block solver's sweep over the tail, a workgroup's invocations a body (block/solve.glsl).
#define TB_BLOCK_TAIL
#include "solve.glsl"
