#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair, before the block solver's iterations: each point starts from the share
// params.block.w of the force it ended last step with (the narrowphase carried it over as an
// impulse) and from the larger of the starting stiffness params.block.x and the share
// params.block_more.w of the pair's stiffness last step (both in units of its effective mass
// over dt^2; the narrowphase carries the pair's in axis.w, which the sweeps then raise to the
// stiffest point's, block_dual). The stiffness goes into the impulse's w, where the sweeps
// keep it until the last one writes the step's normal impulse there. With anchored friction
// (params.block_more.y, the share of its slip since it stuck that a point's friction rows
// count) the friction multipliers start from the rest of that share: the slip alone asks
// for the force that holds the point where it stuck, and the multiplier carried as well
// asked for it twice, so a settled pile trembled at 1-5 cm/s and the base-100 pyramid
// leaned 22 cm (H200; with the multiplier from nothing it holds the pile's creep to
// 0.016 mm in 30,000 steps, against 3.66 mm without anchoring, docs/performance.md).
#include "block.glsl"

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted()) return;
    uint count = block_points(p);
    float carried = uintBitsToFloat(manifolds[p].axis.w) * params.block_more.w;
    float stiffness = max(params.block.x, carried);
    manifolds[p].axis.w = 0u;
    vec3 share = params.block.w * vec3(1.0, vec2(1.0 - params.block_more.y));
    for (uint k = 0u; k < count; k++) {
        vec4 impulse = manifolds[p].impulse[k];
        manifolds[p].impulse[k] = vec4(impulse.xyz * share,
                                       stiffness * block_stiffness_unit(p, k));
    }
}
