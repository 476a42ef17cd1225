#version 450
#extension GL_GOOGLE_include_directive : require
// First stage of a step: zero the counts only the GPU knows. The abort flags (state.x) and
// the steps completed (state.y) carry across steps; an abandoned step leaves everything,
// its counts included, for the host to read.
#include "world.glsl"

void main()
{
    if (step_aborted()) return;
    uint t = gl_LocalInvocationID.x;
    if (t == 0u) {
        counters.pair_dispatch = uvec4(0u, 1u, 1u, 0u);
        counters.wide_pair_dispatch = uvec4(0u, 1u, 1u, 0u);
        counters.state.zw = uvec2(0u);
        counters.grid = uvec4(0u, 0u, params.counts.x, 0u);
        counters.solver = uvec4(0u);
        counters.hull_sat = uvec4(0u);
        counters.colouring.w = 0u;
        counters.events.x = counters.events.y;   // no event of an abandoned attempt stays
    }
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x)
        counters.round_kinds[k] = uvec4(0u);
    for (uint c = t; c < TB_MAX_COLOURS; c += gl_WorkGroupSize.x) {
        counters.colour[c] = uvec4(0u);
        counters.colour_dispatch[c] = uvec4(0u, 1u, 1u, 0u);
    }
}
