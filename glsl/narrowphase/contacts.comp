#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase: one thread per pair of this step turns the pair into a contact manifold of
// up to four points sharing one normal, with the impulses of last step's points of the same
// features (warm start). Dispatched indirectly over counters.pair_dispatch.
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

// Shape types in canonical order: sphere < box < plane < hull, so each routine knows which
// shape comes first. Plane against plane never arrives (planes are static); it gets no
// points. A box meets a hull through its hull data; box against box keeps its own path.
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
        if (hull) return np_hull_hull(t, first, second, margin, normal);
        return np_box_plane(t, first, second, margin, normal);
    }
    if (first.type == TB_GPU_SHAPE_PLANE) return hull ? np_plane_hull(t, first, second, margin, normal) : 0u;
    return np_hull_hull(t, first, second, margin, normal);
}

// How far body i may carry any of its points within the step: its motion (velocity with
// this step's gravity) plus the reach of its turn.
vec3 step_motion(uint i)
{
    if (!body_is(i, TB_BODY_FLAG_DYNAMIC)) return vec3(0.0);
    float dt = params.gravity.w;
    return (body_linvel[i].xyz + params.gravity.xyz * (body_inv_inertia[i].w * dt)) * dt;
}

float step_turn_reach(uint i)
{
    if (!body_is(i, TB_BODY_FLAG_DYNAMIC)) return 0.0;
    float angle = min(length(body_angvel[i].xyz) * params.gravity.w, params.limits.x);
    return angle * length(shapes[body_info[i].x].aabb_half.xyz);
}

// Speculative reach of a pair: the contact margin plus how far the two may close in within
// the step. Points up to that far apart are kept (speculative, separation > 0); the solver
// lets a gap close no faster than it would within a substep, so a fast body lands on a
// surface instead of passing through it (while its path within the step is straight).
float pair_margin(uint a, uint b)
{
    return params.contact.x + length(step_motion(a) - step_motion(b)) + step_turn_reach(a) +
           step_turn_reach(b);
}

// Writes the manifold of pair p; returns its point count.
uint pair_contacts(uint p)
{
    uvec2 pair = pairs[pair_half_base() + p].xy;
    uint a = pair.x, b = pair.y;
    np_body body_a = np_load_body(a), body_b = np_load_body(b);
    bool swapped = body_a.type > body_b.type || (body_a.type == body_b.type && a > b);
    np_target t = np_target_make(p, a, b, current_half() ^ 1u);
    // One call on selected operands (not one call per order): both orders run the very
    // same instructions, so their points agree to the bit.
    np_body first = swapped ? body_b : body_a, second = swapped ? body_a : body_b;
    vec3 normal;
    // The separating axis a hull pair caches for the next step; other pairs have none.
    manifolds[p].axis = uvec4(0u);
    uint count = np_collide(t, first, second, pair_margin(a, b), normal);
    np_finish(t, count, swapped ? -normal : normal, a, b,
              sqrt(body_a.material.x * body_b.material.x), max(body_a.material.y, body_b.material.y));
    return count;
}

void main()
{
    // An abandoned step (overflow upstream) leaves last step's results alone.
    if (counters.state.x != 0u) return;
    uint p = pair_thread_index();
    uint count = p < counters.state.z ? pair_contacts(p) : 0u;
    // Contact points for the stats: one atomic per subgroup.
    uint total = subgroupAdd(count);
    if (subgroupElect() && total != 0u) atomicAdd(counters.solver.w, total);
}
