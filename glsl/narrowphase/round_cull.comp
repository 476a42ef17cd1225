#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The round pairs (round_order's list, grouped by kind) that are surely apart get their
// empty manifold here (np_round_apart: bounding balls, the capsules' closed form, GJK's
// first supports); the others are listed again after the first list in colour_work
// (counters.round_kinds[0].z of them) for round_points, a subgroup's together, so the list
// stays mostly grouped by kind (its order varies from run to run; no result depends on it). Most of a pile's
// round pairs are apart, and one GJK support or two tell; in round_points their threads would
// idle beside those that build a manifold. A thread per round pair, dispatched indirectly over
// counters.wide_pair_dispatch, in workgroups of TB_WIDE_WORKGROUP_SIZE.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "sphere.glsl"
#include "box_box.glsl"
#include "hull.glsl"
#include "hull_sat.glsl"
#include "hull_clip.glsl"
#include "../midphase/mesh.glsl"
#include "triangle.glsl"
#include "pair.glsl"
#include "convex.glsl"
#include "gjk.glsl"
#include "epa.glsl"
#include "round.glsl"

// Whether pair p is apart (then its empty manifold is written).
bool cull(uint p)
{
    np_pair q = np_pair_load(p);
    if (!np_round_apart(q.first, q.second, q.margin)) return false;
    // As round_points with no points.
    uint stiffness = q.t.prev != NP_NONE ? prev_manifolds[q.t.prev].axis.w : 0u;
    manifolds[p].axis = uvec4(0u, 0u, 0u, stiffness);
    np_pair_finish(q, 0u, vec3(0.0, 1.0, 0.0));
    return true;
}

void main()
{
    if (counters.state.x != 0u) return;
    uint t = pair_thread_index();
    bool mine = t < counters.round_kinds[0].w;
    uint p = mine ? colour_work[t] : 0u;
    bool listed = mine && !cull(p);
    uvec4 ballot = subgroupBallot(listed);
    uint count = subgroupBallotBitCount(ballot), base = 0u;
    if (subgroupElect() && count != 0u) base = atomicAdd(counters.round_kinds[0].z, count);
    base = subgroupBroadcastFirst(base);
    if (listed) colour_work[params.capacity.x + base + subgroupBallotExclusiveBitCount(ballot)] = p;
}
