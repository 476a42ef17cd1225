#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair, before the block solver's iterations: each point starts from the share
// params.block.w of the force it ended last step with (the narrowphase carried it over as an
// impulse) and from the larger of the starting stiffness params.block.x and the share
// params.block_more.w of the pair's stiffness last step (both in units of its effective mass
// over dt^2; the narrowphase carries the pair's in axis.w, which the sweeps then raise to the
// stiffest point's, block_dual). The stiffness goes into the impulse's w, where the sweeps
// keep it until the last one writes the step's normal impulse there.
#include "block.glsl"

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted()) return;
    uint count = block_points(p);
    float carried = uintBitsToFloat(manifolds[p].axis.w) * params.block_more.w;
    float stiffness = max(params.block.x, carried);
    manifolds[p].axis.w = 0u;
    for (uint k = 0u; k < count; k++) {
        vec4 impulse = manifolds[p].impulse[k];
        manifolds[p].impulse[k] = vec4(impulse.xyz * params.block.w,
                                       stiffness * block_stiffness_unit(p, k));
    }
}
