#version 450
#extension GL_GOOGLE_include_directive : require
// One sort entry per body slot: its AABB's minimum on the sweep axis as an ordered uint,
// or TB_SAP_KEY_OUT (after every real key) for dead and large bodies; large ones are
// flagged for the compaction that lists them.
#include "world.glsl"
#include "sap.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    bool alive = body_is(i, TB_BODY_FLAG_ALIVE);
    bool large = alive && sap_is_large(i);
    uint axis = sap_header().h.state.x;
    sap_uints(TB_SAP_KEYS).v[i] = alive && !large ? sap_ordered_bits(body_aabb_min[i][axis])
                                                  : TB_SAP_KEY_OUT;
    sap_uints(TB_SAP_ORDER).v[i] = i;
    sap_uints(TB_SAP_LARGE_FLAGS).v[i] = large ? 1u : 0u;
}
