#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The round pairs round_cull left for round_points, grouped by kind into colour_work's first
// list (free until the solver colours), so that
// a warp of round_points runs pairs of one kind: its threads then take the same support
// functions and features together instead of one kind after another (a pile whose kinds lay
// in layers ran the kernel a quarter faster than a shuffled one). Each workgroup ranks its
// pairs of a kind in shared memory and claims a run of the kind's range with one atomic;
// the order within a kind follows the claims (round_points' results do not depend on it).
// One thread per pair, dispatched indirectly over counters.pair_dispatch, after round_count
// (round_cull left each pair's kind in colour_work's second list).
#include "world.glsl"

shared uint kind_count[TB_ROUND_KINDS];
shared uint kind_start[TB_ROUND_KINDS];

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x) kind_count[k] = 0u;
    barrier();
    uint p = pair_thread_index();
    bool live = !step_aborted() && p < counters.state.z;
    uint kind = live ? colour_work[params.capacity.x + p] : TB_ROUND_KINDS;   // round_cull's
    uint rank = kind < TB_ROUND_KINDS ? atomicAdd(kind_count[kind], 1u) : 0u;
    barrier();
    for (uint k = t; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x) {
        // The kind's range starts after every smaller kind's pairs.
        uint before = 0u;
        for (uint j = 0u; j < k; j++) before += counters.round_kinds[j].x;
        uint mine = kind_count[k];
        kind_start[k] = before + (mine != 0u ? atomicAdd(counters.round_kinds[k].y, mine) : 0u);
        if (k == TB_ROUND_KINDS - 1u && gl_WorkGroupID.x == 0u && gl_WorkGroupID.y == 0u)
            counters.round_kinds[0].w = before + counters.round_kinds[k].x;
    }
    barrier();
    if (kind < TB_ROUND_KINDS) colour_work[kind_start[kind] + rank] = p;
}
