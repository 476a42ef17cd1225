#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The round pairs of each kind (pair.glsl's np_round_kind), counted into
// counters.round_kinds[].x for round_order: a histogram per workgroup in shared memory, then
// one atomic per kind a workgroup met. Each pair's kind (TB_ROUND_KINDS: none) goes to the
// second list of colour_work, free until round_cull, for round_order. One thread per pair,
// dispatched indirectly over counters.pair_dispatch.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "pair.glsl"

shared uint kind_count[TB_ROUND_KINDS];

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x) kind_count[k] = 0u;
    barrier();
    uint p = pair_thread_index();
    bool live = !step_aborted() && p < counters.state.z;
    uint kind = live ? np_round_kind(p) : TB_ROUND_KINDS;
    if (live) colour_work[params.capacity.x + p] = kind;
    if (kind < TB_ROUND_KINDS) atomicAdd(kind_count[kind], 1u);
    barrier();
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x)
        if (kind_count[k] != 0u) atomicAdd(counters.round_kinds[k].x, kind_count[k]);
}
