#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase of the pairs with a capsule, cylinder or cone (round.glsl): against any convex
// shape (GJK, EPA), a plane, or a mesh triangle (contacts.comp and mesh_points.comp leave
// these pairs alone). Recorded after hull_points and before mesh_points while the world has
// such shapes, so mesh_reduce sees the triangle pairs' points. A thread per round pair that
// round_cull did not find apart, as round_order listed them (grouped by kind); dispatched
// indirectly over counters.wide_pair_dispatch (enough for every pair), in workgroups of
// TB_WIDE_WORKGROUP_SIZE.
//
// The round shapes come after every other convex shape and the plane in the canonical order
// (by shape type), and after meshes too: the second shape of a listed pair is a round one.
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
#include "reuse.glsl"
#include "apart.glsl"

uint round_points(uint p)
{
    // round_cull found last step's manifold of the pair (round_cull.comp).
    np_pair q = np_pair_bodies(p);
    q.t = np_target_after(p, manifolds[p].axis.x);
    np_pair_start(q);
    vec3 normal;
    uint first = q.first.type;
    bool on_mesh = first == TB_GPU_SHAPE_MESH || first == TB_GPU_SHAPE_HEIGHTFIELD;
    np_triangle tri;
    if (on_mesh) tri = np_load_triangle(q.first, q.triangle, q.first.rot, q.first.pos);
    uint count = np_round_contacts(q.t, q.first, q.second, on_mesh, tri, q.margin, normal);
    np_pair_finish(q, count, normal);
    manifolds[q.t.slot].axis.y = np_round_supports;
    np_keep_measured(q.a, q.b, q.sub, q.t.slot, count);
    if (count == 0u) np_keep_apart(q, q.t.slot, np_round_apart_along);
    return count;
}

void main()
{
    if (counters.state.x != 0u) return;
    // The round pairs round_cull left, grouped by kind (round_order).
    uint t = pair_thread_index();
    // The round kinds come first: the first kind after them starts where they end.
    bool mine = t < counters.round_kinds[TB_PAIR_KIND_HULL].z;
    np_count_points(mine ? round_points(colour_work[t]) : 0u);
}
