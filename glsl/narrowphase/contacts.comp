#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Narrowphase: one thread per pair of this step turns the pair into a contact manifold of
// up to four points sharing one normal, with the impulses of last step's points of the same
// features (warm start). Dispatched indirectly over counters.pair_dispatch. While round
// shapes live (push.args.x set) the pairs are those round_order listed of the kinds
// TB_PAIR_KIND_HULL and TB_PAIR_KIND_CONVEX, grouped so, rather than every pair.
//
// Hull pairs get only last step's separating axis tried here (hull_hull.glsl, steps 1 and
// 1b); the pairs it does not decide are listed for narrowphase/hull_sat, the separating
// axis test, and hull_points.comp clips and reduces the touching pairs' points. The
// clipper's polygons (128 vec4 per thread) and the SAT's loops then do not share one
// kernel's registers with each other and with the other shapes' routines.
//
// Pair p of this step is pairs[half * capacity + p] = (a, b, colour, -), half = the step
// parity; its manifold goes to manifolds[p], normal from a to b; last step's manifolds are
// in prev_manifolds, indexed like last step's pairs. Every
// contact routine sees the pair in one canonical order (by shape type, then body index),
// so the points and feature keys depend only on the unordered pair; swapping a and b only
// negates the normal.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "sphere.glsl"
#include "box_plane.glsl"
#include "box_box.glsl"
#include "hull.glsl"
#include "hull_sat.glsl"
#include "hull_clip.glsl"
#include "hull_hull.glsl"
#include "hull_plane.glsl"
#include "hull_sphere.glsl"
#include "pair.glsl"
#include "reuse.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

// Shape types in canonical order: sphere < box < plane < hull < mesh < capsule, cylinder,
// cone, so each routine knows which shape comes first. Mesh pairs never come here
// (mesh_points.comp), nor do pairs with a capsule, cylinder or cone (round_points.comp).
// Plane against plane never arrives (planes are static); it gets no points. A box meets a hull through its hull data; box against box keeps its own path.
uint np_collide(np_target t, np_body first, np_body second, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    bool hull = second.type == TB_GPU_SHAPE_HULL;
    if (first.type == TB_GPU_SHAPE_SPHERE) {
        if (second.type == TB_GPU_SHAPE_SPHERE) return np_sphere_sphere(t, first, second, margin, normal);
        if (second.type == TB_GPU_SHAPE_BOX) return np_sphere_box(t, first, second, margin, normal);
        if (hull) return np_sphere_hull(t, first, second, margin, normal);
        return np_sphere_plane(t, first, second, margin, normal);
    }
    if (first.type == TB_GPU_SHAPE_BOX) {
        if (second.type == TB_GPU_SHAPE_BOX) return np_box_box(t, first, second, margin, normal);
        if (hull) return np_hull_hull_deferred(t, first, second, margin);
        return np_box_plane(t, first, second, margin, normal);
    }
    if (first.type == TB_GPU_SHAPE_PLANE) return hull ? np_plane_hull(t, first, second, margin, normal) : 0u;
    return np_hull_hull_deferred(t, first, second, margin);
}

// A compound pair whose parts are all apart (the split kept it whole, TB_PAIR_UNSPLIT):
// an empty manifold.
void apart_parts(uint p, uvec4 pair)
{
    np_target t = np_target(p, NP_NONE, 0u, uvec4(0u));
    manifolds[p].axis = uvec4(0u);
    np_finish(t, 0u, vec3(0.0), pair.x, pair.y, 0.0, 0.0);
}

// Writes the manifold of pair p; returns its point count.
uint pair_contacts(uint p)
{
    uvec4 pair = pairs[pair_half_base() + p];
    if (pair.w == TB_PAIR_UNSPLIT) {
        apart_parts(p, pair);
        return 0u;
    }
    np_pair q = np_pair_load(p);
    // A box's or hull's pair that has hardly moved since its manifold was found (reuse.glsl).
    bool reused = params.contact.w >= 0.0 && np_flat_pair_reused(q);
    if (reused && np_may_remeasure(q, q.t.prev)) return np_remeasure(q, p, q.t.prev);
    vec3 normal;
    // The separating axis a hull pair caches for the next step; other pairs have none.
    np_pair_start(q);
    uint count = np_collide(q.t, q.first, q.second, q.margin, normal);
    np_pair_finish(q, count, normal);
    if (reused) np_keep_measured(q.a, q.b, q.sub, p, count);
    return count;
}

// The hull pair this thread left to narrowphase/hull_sat (np_hull_sat_pending), if any, into
// colour_work's second list (free until the solver): one atomic per subgroup. From uniform
// control flow.
void list_for_sat(uint p)
{
    uvec4 ballot = subgroupBallot(p != NP_NONE);
    uint n = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (subgroupElect() && n != 0u) base = atomicAdd(counters.hull_sat.x, n);
    base = subgroupBroadcastFirst(base);
    if (p != NP_NONE)
        colour_work[params.capacity.x + base + subgroupBallotExclusiveBitCount(ballot)] = p;
}

void main()
{
    // An abandoned step (overflow upstream) leaves last step's results alone.
    if (counters.state.x != 0u) return;
    uint t = pair_thread_index(), p = t;
    bool mine;
    if (push.args.x != 0u) {
        // While round shapes live, round_order listed this pass's pairs (np_kind_run).
        p = np_listed_pair(t, np_kind_run(TB_PAIR_KIND_HULL, TB_PAIR_KIND_CONVEX));
        mine = p != NP_NONE;
    } else {
        // Otherwise a thread per pair; a mesh triangle's pair is mesh_points.comp's, whole.
        mine = p < counters.state.z && !pair_has_mesh(pairs[pair_half_base() + p]);
    }
    uint count = mine ? pair_contacts(p) : 0u;
    list_for_sat(np_hull_sat_pending);
    np_count_points(count);
}
