#version 450
#extension GL_GOOGLE_include_directive : require
// The boxes in sorted order, so the sweeps read neighbours from neighbouring addresses:
// min with the body's slot in w, max with its TB_SAP_BOX_* flags in w. Boxes that stay out
// of the sweep (the sort put them last) get an infinite minimum, which ends every sweep.
#include "world.glsl"
#include "sap.glsl"

void main()
{
    uint s = body_thread_index();
    if (s >= counters.grid.z || step_aborted()) return;
    uint i = sap_uints(TB_SAP_ORDER).v[s];
    bool out_of_sweep = sap_uints(TB_SAP_KEYS).v[s] == TB_SAP_KEY_OUT;
    uint flags = (body_is(i, TB_BODY_FLAG_DYNAMIC) ? TB_SAP_BOX_DYNAMIC : 0u) |
                 (out_of_sweep ? TB_SAP_BOX_OUT : 0u);
    vec3 lo = out_of_sweep ? vec3(uintBitsToFloat(0x7f800000u)) : body_aabb_min[i].xyz;
    sap_vec4s(TB_SAP_BOX_MIN).v[s] = vec4(lo, uintBitsToFloat(i));
    sap_vec4s(TB_SAP_BOX_MAX).v[s] = vec4(body_aabb_max[i].xyz, uintBitsToFloat(flags));
}
