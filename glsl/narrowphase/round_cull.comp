#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The first pass of the narrowphase while round shapes live: every pair's kind (pair.glsl's
// np_pair_kind). The round pairs surely apart get their empty manifold here
// (np_round_apart: bounding balls, the capsules' closed form, GJK's first support), and
// those whose bodies have hardly moved since their manifold was measured get it measured
// again (reuse.glsl). The
// kind of each pair left for round_points (with the bucket of the supports its GJK took
// last step) or contacts.comp (TB_ROUND_KINDS for none: a mesh triangle's pair, or apart)
// goes to colour_work's second list, free until the solver, and is counted in
// counters.round_kinds[].x, for round_order, which lists those pairs grouped by kind. Most
// of a pile's round pairs are apart, and one GJK support tells; in round_points their
// threads would idle beside those that build a manifold. The pairs are taken in their own
// order, not grouped: neighbouring pairs share bodies, and the loads of a warp then meet in
// the caches (grouped by kind first, this pass took a third longer). A thread per pair,
// dispatched indirectly over counters.wide_pair_dispatch, in workgroups of
// TB_WIDE_WORKGROUP_SIZE.
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
#include "round_kinds.glsl"
#include "reuse.glsl"
#include "apart.glsl"

// The bucket of the GJK supports pair q (p) took last step (round_points keeps them in its
// manifold's axis.y; they change for about one pair in ten from step to step): up to 3,
// each of 4 to 8 (a pair new or without GJK last step as 6), 9 and 10, more. Grouped by it
// too, a warp's GJK loops run about as long (with four buckets, up to 4, 5-6, 7-8 and more,
// round_points took 4 % longer on an H200). Last step's manifold, found by round_kind, is
// left for round_points (this step's manifold's axis.x) so that it does not look again.
uint supports_bucket(uint p, uint prev)
{
    manifolds[p].axis.x = prev;
    uint supports = prev != NP_NONE ? prev_manifolds[prev].axis.y : 0u;
    if (supports == 0u) supports = 6u;
    return supports <= 3u ? 0u : (supports <= 8u ? supports - 3u : (supports <= 10u ? 6u : 7u));
}

// Round pair p of `kind` (its first bucket) with its bucket, or TB_ROUND_KINDS when it is
// apart or its manifold was measured again (reuse.glsl): then its manifold is written here,
// and `points` counts them.
uint round_kind(uint p, uint kind, inout uint points)
{
    // Last step's manifold is looked for only where the bounding balls meet: the search is
    // a loop over last step's pairs, and a manifold without points takes nothing from it
    // (its stiffness carry-over, axis.w, is read for points only and zeroed by the block
    // solver's start, block/start.comp). A pair still posed as when its manifold was
    // measured touches as it did then: measured again before GJK's supports of the cull.
    np_pair q = np_pair_bodies(p);
    uint first = q.first.type;
    bool unbounded = first == TB_GPU_SHAPE_PLANE || first == TB_GPU_SHAPE_MESH ||
                     first == TB_GPU_SHAPE_HEIGHTFIELD;   // never culled (np_round_apart)
    bool near = unbounded || np_balls_near(q.first, q.second, q.margin);
    bool reuse = params.contact.w >= 0.0;   // tb_world_set_contact_reuse
    uint prev = NP_NONE;
    if (near && reuse) {
        prev = np_find_previous(q.a, q.b, q.sub, current_half() ^ 1u);
        if (np_may_remeasure(q, prev)) {
            points = np_remeasure(q, p, prev);
            return TB_ROUND_KINDS;
        }
        // A pair GJK found apart last step is tried along the direction it found first.
        if (np_still_apart(q, prev)) {
            np_stay_apart(q, prev);
            return TB_ROUND_KINDS;
        }
    }
    if (near && !np_round_apart(q.first, q.second, q.margin)) {
        if (!reuse) prev = np_find_previous(q.a, q.b, q.sub, current_half() ^ 1u);
        return kind + supports_bucket(p, prev);
    }
    np_finish_empty(p, q.a, q.b);
    return TB_ROUND_KINDS;
}

void main()
{
    np_kind_clear();
    uint p = pair_thread_index();
    bool live = !step_aborted() && p < counters.state.z;
    uint kind = live ? np_pair_kind(p) : TB_ROUND_KINDS;
    uint points = 0u;
    if (kind < TB_PAIR_KIND_HULL) kind = round_kind(p, kind, points);
    np_count_points(points);
    if (live) colour_work[params.capacity.x + p] = kind;
    // The pairs left of each kind, counted for round_order.
    np_kind_add(kind);
    barrier();
    uint k = gl_LocalInvocationID.x;
    if (k < TB_ROUND_KINDS && np_kind_count[k] != 0u)
        atomicAdd(counters.round_kinds[k].x, np_kind_count[k]);
}
