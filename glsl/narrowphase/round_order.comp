#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The pairs round_cull left for round_points and contacts.comp, grouped by kind into
// colour_work's first list (free until the solver colours), so that a warp runs pairs of
// one kind: its threads then take the same support functions and features together instead
// of one kind after another (a pile whose kinds lay in layers ran round_points a quarter
// faster than a shuffled one), and contacts.comp's threads are not spread one in sixteen
// over the round pairs' warps. round_cull left each pair's kind in colour_work's second
// list and counted every kind in counters.round_kinds[].x. Each workgroup ranks its pairs
// of a kind (round_kinds.glsl) and claims a run of the kind's range with one atomic; the
// order within a kind follows the claims (round_points' and contacts' results do not
// depend on it). A round pair's kind includes the bucket of its last GJK supports
// (layout.h), so a warp of round_points also gets pairs of about as many supports: in four
// buckets that took round_points from 1.21 to 1.05 ms in the 100k shapes pile on an H100
// (its warps' GJK lanes were busy 59 % of the loops' rounds), in eight 4 % less again
// (H200). A thread per pair, dispatched indirectly over counters.wide_pair_dispatch, in
// workgroups of TB_WIDE_WORKGROUP_SIZE.
#include "world.glsl"
#include "round_kinds.glsl"

shared uint kind_start[TB_ROUND_KINDS];   // where this workgroup's run of a kind starts
shared uint subgroup_total[TB_WIDE_WORKGROUP_SIZE];   // of the subgroups' counts, inclusive

// The pairs of every kind before this invocation's (its rank in subgroup order), each kind's
// `total` passed by its invocation: a workgroup scan.
uint kinds_before(uint total)
{
    uint inclusive = subgroupInclusiveAdd(total);
    if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) subgroup_total[gl_SubgroupID] = inclusive;
    barrier();
    uint before = 0u;
    for (uint s = 0u; s < gl_SubgroupID; s++) before += subgroup_total[s];
    return before + inclusive - total;
}

// Where each kind's run of the workgroup starts: the kind's range starts after every
// smaller kind's pairs.
void claim_runs()
{
    uint k = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    uint before = kinds_before(k < TB_ROUND_KINDS ? counters.round_kinds[k].x : 0u);
    if (k < TB_ROUND_KINDS) {
        uint mine = np_kind_count[k];
        kind_start[k] = before + (mine != 0u ? atomicAdd(counters.round_kinds[k].y, mine) : 0u);
        if (gl_WorkGroupID.x == 0u && gl_WorkGroupID.y == 0u) counters.round_kinds[k].z = before;
    }
    barrier();
}

void main()
{
    np_kind_clear();
    uint p = pair_thread_index();
    bool live = !step_aborted() && p < counters.state.z;
    uint kind = live ? colour_work[params.capacity.x + p] : TB_ROUND_KINDS;   // round_cull's
    uint rank = np_kind_add(kind);
    barrier();
    claim_runs();
    if (kind < TB_ROUND_KINDS) colour_work[kind_start[kind] + rank] = p;
}
