#version 450
#extension GL_GOOGLE_include_directive : require
// The boxes in sorted order, so the sweeps read neighbours from neighbouring addresses:
// min with the body's slot in w, max with its TB_SAP_BOX_* flags in w (as uints), their
// axes turned so that the sweep axis comes first (x): the sweep then needs no axis index,
// and the overlap test, the same on every axis, gives the same answers. The first large
// body and the first dead slot in the order (the sort put them last) say where the swept
// boxes and the large ones end. Each workgroup also leaves the spread of its swept
// centres, from which the next step's axis is chosen (sap_axis.glsl).
#include "world.glsl"
#include "sap.glsl"
#include "sap_axis.glsl"

// 0 swept, 1 large, 2 dead.
uint class_of(uint key)
{
    return key == TB_SAP_KEY_DEAD ? 2u : key == TB_SAP_KEY_LARGE ? 1u : 0u;
}

// The axes of v, the sweep axis first (cyclic, so the test is the same).
vec3 sweep_axis_first(vec3 v, uint axis)
{
    return axis == 0u ? v : axis == 1u ? v.yzx : v.zxy;
}

// Sorted position s: its boxes, the ends of the runs it starts; whether it is swept.
bool gather(uint s, out vec3 centre)
{
    SapUints keys = sap_uints(TB_SAP_KEYS);
    uint here = class_of(keys.v[s]);
    uint before = s == 0u ? 0u : class_of(keys.v[s - 1u]);
    if (here >= 1u && (s == 0u || before < 1u)) sap_header().h.state.y = s;
    if (here == 2u && (s == 0u || before < 2u)) sap_header().h.state.z = s;
    uint i = sap_uints(TB_SAP_ORDER).v[s];
    uint flags = (body_is(i, TB_BODY_FLAG_DYNAMIC) ? TB_SAP_BOX_DYNAMIC : 0u) |
                 (body_is(i, TB_BODY_FLAG_COMPOUND) ? TB_SAP_BOX_SPLIT : 0u) |
                 (here != 0u ? TB_SAP_BOX_OUT : 0u);
    uint axis = sap_axis();
    vec3 lo = body_aabb_min[i].xyz, hi = body_aabb_max[i].xyz;
    centre = 0.5 * (lo + hi);
    sap_boxes(TB_SAP_BOX_MIN).v[s] = uvec4(floatBitsToUint(sweep_axis_first(lo, axis)), i);
    sap_boxes(TB_SAP_BOX_MAX).v[s] = uvec4(floatBitsToUint(sweep_axis_first(hi, axis)), flags);
    return here == 0u;
}

void main()
{
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint slots = counters.grid.z;
    // The whole workgroup returns together: past the last row's end (dispatches in rows
    // have a few spare workgroups), or from an abandoned step.
    if (group * gl_WorkGroupSize.x >= slots || step_aborted()) return;
    uint s = body_thread_index();
    vec3 centre = vec3(0.0);
    bool swept = s < slots && gather(s, centre);
    sap_axis_partial(group, swept, centre);
}
