#version 450
#extension GL_GOOGLE_include_directive : require
// One sort entry per body slot: its AABB's minimum on the sweep axis as an ordered uint;
// large bodies and dead slots get keys after every real one, so the sort lists them too,
// at its end. The axis is the one the previous step chose (sap_axis.glsl).
#include "world.glsl"
#include "sap.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    bool alive = body_is(i, TB_BODY_FLAG_ALIVE);
    bool large = alive && sap_is_large(i);
    uint axis = sap_axis();
    // Where the large bodies and the dead slots begin in the order, until sap_gather
    // finds them (when there are none, nothing is past the last entry).
    if (i == 0u) sap_header().h.state.yz = uvec2(params.counts.x);
    uint key = TB_SAP_KEY_DEAD;
    if (large) key = TB_SAP_KEY_LARGE;
    else if (alive) key = ordered_bits(body_aabb_min[i][axis]);
    sap_uints(TB_SAP_KEYS).v[i] = key;
    sap_uints(TB_SAP_ORDER).v[i] = i;
}
