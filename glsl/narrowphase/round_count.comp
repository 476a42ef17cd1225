#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The round pairs round_cull left for round_points, of each kind (round_cull wrote each
// pair's kind in colour_work's second list), counted into counters.round_kinds[].x for
// round_order: a histogram per workgroup in shared memory, then one atomic per kind a
// workgroup met. One thread per pair, dispatched indirectly over counters.pair_dispatch.
#include "world.glsl"

shared uint kind_count[TB_ROUND_KINDS];

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x) kind_count[k] = 0u;
    barrier();
    uint p = pair_thread_index();
    bool live = !step_aborted() && p < counters.state.z;
    uint kind = live ? colour_work[params.capacity.x + p] : TB_ROUND_KINDS;
    if (kind < TB_ROUND_KINDS) atomicAdd(kind_count[kind], 1u);
    barrier();
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x)
        if (kind_count[k] != 0u) atomicAdd(counters.round_kinds[k].x, kind_count[k]);
}
