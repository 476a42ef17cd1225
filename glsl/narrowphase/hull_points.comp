#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase, second pass: the points of the hull pairs the first pass (contacts.comp)
// found touching and marked (manifolds[p].axis.z, the axis of largest separation, never 0),
// from the axis it cached there: clipping and reduction for a face axis, the closest edge
// points for an edge axis (hull_hull.glsl step 4). One thread per pair (while round shapes
// live, per pair with a hull that round_order listed: push.args.x set); unmarked pairs
// return at once. Dispatched indirectly over counters.pair_dispatch.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "box_box.glsl"
#include "hull.glsl"
#include "hull_sat.glsl"
#include "hull_clip.glsl"
#include "hull_hull.glsl"
#include "pair.glsl"
#include "reuse.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

uint hull_points(uint p)
{
    np_pair q = np_pair_load(p);
    vec3 normal;
    uvec4 axis = manifolds[p].axis;
    uint count = np_hull_hull_points(q.t, q.first, q.second, axis.x, axis.z, q.margin, normal);
    manifolds[p].axis.z = 0u;
    np_pair_finish(q, count, normal);
    np_keep_measured(q.a, q.b, q.sub, p, count);
    return count;
}

void main()
{
    if (counters.state.x != 0u) return;
    uint t = pair_thread_index(), p = t;
    bool marked;
    if (push.args.x != 0u) {
        // While round shapes live, round_order listed the pairs with a hull (np_kind_run).
        p = np_listed_pair(t, np_kind_run(TB_PAIR_KIND_HULL, TB_PAIR_KIND_HULL));
        marked = p != NP_NONE && manifolds[p].axis.z != 0u;
    } else {
        // A mesh triangle's pair is never contacts.comp's, so its manifold may hold a mark
        // of a step abandoned before this pass: not ours.
        marked = p < counters.state.z && manifolds[p].axis.z != 0u &&
                 !pair_has_mesh(pairs[pair_half_base() + p]);
    }
    np_count_points(marked ? hull_points(p) : 0u);
}
