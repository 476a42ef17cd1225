#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase, second pass: the points of the hull pairs the first pass (contacts.comp)
// found touching and marked (manifolds[p].axis.z, the axis of largest separation, never 0),
// from the axis it cached there: clipping and reduction for a face axis, the closest edge
// points for an edge axis (hull_hull.glsl step 4). One thread per pair; unmarked pairs
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

uint hull_points(uint p)
{
    np_pair q = np_pair_load(p);
    vec3 normal;
    uvec4 axis = manifolds[p].axis;
    uint count = np_hull_hull_points(q.t, q.first, q.second, axis.x, axis.z, q.margin, normal);
    manifolds[p].axis.z = 0u;
    np_pair_finish(q, count, normal);
    return count;
}

void main()
{
    if (counters.state.x != 0u) return;
    uint p = pair_thread_index();
    // A mesh triangle's pair is never contacts.comp's, so its manifold may hold a mark of a
    // step abandoned before this pass: not ours.
    bool marked = p < counters.state.z && manifolds[p].axis.z != 0u &&
                  !pair_has_mesh(pairs[pair_half_base() + p]);
    np_count_points(marked ? hull_points(p) : 0u);
}
