#version 450
#extension GL_GOOGLE_include_directive : require
#include "tumble_plugin.glsl"

void main() { tb_plugin_begin() }
