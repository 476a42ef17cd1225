#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase of mesh pairs: the pair of a convex body (or a compound's child) and one
// triangle of a mesh body (the broadphase split the body pair by triangle) gets its manifold
// here (triangle.glsl); contacts.comp leaves it alone. One thread per pair; other pairs
// return at once. Recorded after contacts (and hull_points) while the world has mesh shapes;
// mesh_reduce then keeps at most four points per body pair. Dispatched indirectly over
// counters.pair_dispatch.
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

uint mesh_points(uint p)
{
    np_pair q = np_pair_load(p);
    // A capsule, cylinder or cone against a triangle: round_points.comp's.
    if (np_is_round(q.second.type)) return 0u;
    np_pair_start(q);
    vec3 normal = vec3(0.0);
    uint count = 0u;
    np_body shape = q.first, mesh = q.second;   // the mesh comes after the other convex shapes
    uint triangle = q.triangle;
    if (shape.type == TB_GPU_SHAPE_SPHERE) {
        np_triangle tri = np_load_triangle(mesh, triangle, mesh.rot, mesh.pos);
        count = np_sphere_triangle(q.t, shape, tri, q.margin, normal);
    } else if (shape.type == TB_GPU_SHAPE_BOX || shape.type == TB_GPU_SHAPE_HULL) {
        np_frame in_hull = np_frame_between(shape, mesh);
        np_triangle tri = np_load_triangle(mesh, triangle, in_hull.rot, in_hull.pos);
        count = np_hull_triangle(q.t, shape, tri, q.margin, normal);
    }
    np_pair_finish(q, count, normal);
    return count;
}

void main()
{
    if (counters.state.x != 0u) return;
    uint p = pair_thread_index();
    bool mesh = p < counters.state.z && pair_has_mesh(pairs[pair_half_base() + p]);
    np_count_points(mesh ? mesh_points(p) : 0u);
}
