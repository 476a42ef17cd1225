#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_normal;
layout(location = 1) flat in vec3 in_color;

layout(location = 0) out vec4 out_color;

void main()
{
    out_color = vec4(shade(in_color, normalize(in_normal)), 1.0);
}
