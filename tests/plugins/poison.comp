#version 450
#extension GL_GOOGLE_include_directive : require
// The poison plugin's stage (after the broadphase, a thread per body): while param 0's x is 1, the body
// in slot y gets a NaN velocity.
#include "tumble_plugin.glsl"

void main()
{
    if (!tb_plugin_begin()) return;
    uint i = tb_plugin_thread_index();
    vec4 p = tb_plugin_param(0u);
    if (i >= tb_plugin_body_count() || p.x != 1.0 || i != uint(p.y)) return;
    // z 1: infinite instead of NaN.
    body_linvel[i].xyz = vec3(uintBitsToFloat(p.z == 1.0 ? 0x7f800000u : 0x7fc00000u));
}
