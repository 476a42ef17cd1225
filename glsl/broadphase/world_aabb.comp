#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// World AABB of every body from its shape's local AABB: the centre is carried by the pose,
// the half extents by |R| (the sum of |column k| * h_k), which bounds the rotated box
// exactly; a hull's box bounds its turned vertices and a round shape's its axis and rims. A
// sphere's box does not turn with it: its half extent stays the radius.
// A dynamic body's box is swept over the step's motion (its velocity with this step's
// gravity, and the reach of its turn), so the broadphase pairs it with whatever it could hit
// within the step and the narrowphase can give that a speculative point.
// Dead slots get an empty (inverted) box so nothing can overlap them.
// The largest side of any dynamic body's box goes to counters.grid.x: it sizes the grid.
#include "world.glsl"
#include "quat.glsl"

// A hull's own box: its turned vertices' bounds, tighter than the turned local box (which
// for a hull turned 45 degrees is up to 1.4 times wider on each axis, and ten times the
// pairs in a pile). At most TB_HULL_MAX_VERTICES reads.
void hull_bounds(tb_gpu_shape shape, mat3 r, vec3 pos, out vec3 centre, out vec3 extent)
{
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint k = 0u; k < shape.info.y; k++) {
        vec3 v = r * hull_vectors[shape.hull.x + k].xyz;
        lo = min(lo, v);
        hi = max(hi, v);
    }
    centre = pos + 0.5 * (lo + hi);
    extent = 0.5 * (hi - lo);
}

// A capsule's, cylinder's or cone's own box: the ends of its axis (the body's y), each
// widened by its ball (a capsule) or its rim, a disc square to the axis, whose half extent
// along world axis k is the radius times sin(axis, k). The turned local box is up to 1.4
// times wider on each axis: the 100k shapes pile had 39 % fewer pairs with these.
void round_bounds(tb_gpu_shape shape, mat3 r, vec3 pos, out vec3 centre, out vec3 extent)
{
    vec3 axis = r[1];
    float radius = shape.params.x, h = shape.params.y;
    vec3 rim = radius * sqrt(max(vec3(1.0) - axis * axis, vec3(0.0)));
    centre = pos + r * shape.aabb_center.xyz;
    if (shape.info.x == TB_GPU_SHAPE_CAPSULE) {
        extent = abs(axis) * h + vec3(radius);
    } else if (shape.info.x == TB_GPU_SHAPE_CYLINDER) {
        extent = abs(axis) * h + rim;
    } else {   // a cone: its base's rim h below the box's centre, its apex h above
        vec3 base = centre - h * axis, apex = centre + h * axis;
        vec3 lo = min(base - rim, apex), hi = max(base + rim, apex);
        centre = 0.5 * (lo + hi);
        extent = 0.5 * (hi - lo);
    }
}

void main()
{
    uint i = body_thread_index();
    if (step_aborted()) return;
    float side = 0.0;
    if (i < params.counts.x) {
        if (!body_is(i, TB_BODY_FLAG_ALIVE)) {
            body_aabb_min[i] = vec4(3.0e38);
            body_aabb_max[i] = vec4(-3.0e38);
        } else {
            tb_gpu_shape shape = shapes[body_info[i].x];
            mat3 r = quat_to_mat3(body_rot[i]);
            vec3 h = shape.aabb_half.xyz;
            vec3 centre = body_pos[i].xyz + r * shape.aabb_center.xyz;
            vec3 extent = shape.info.x == TB_GPU_SHAPE_SPHERE
                              ? vec3(shape.params.x)
                              : abs(r[0]) * h.x + abs(r[1]) * h.y + abs(r[2]) * h.z;
            if (shape.info.x == TB_GPU_SHAPE_HULL)
                hull_bounds(shape, r, body_pos[i].xyz, centre, extent);
            if (shape.info.x >= TB_GPU_SHAPE_CAPSULE && shape.info.x <= TB_GPU_SHAPE_CONE)
                round_bounds(shape, r, body_pos[i].xyz, centre, extent);
            vec3 sweep = body_step_motion(i);
            extent += vec3(body_step_turn(i) * length(h));
            body_aabb_min[i] = vec4(min(centre - extent, centre - extent + sweep), 0.0);
            body_aabb_max[i] = vec4(max(centre + extent, centre + extent + sweep), 0.0);
            if (body_is(i, TB_BODY_FLAG_DYNAMIC))
                side = 2.0 * max(extent.x, max(extent.y, extent.z));
        }
    }
    // Positive floats order like their bits: one atomic per subgroup.
    float largest = subgroupMax(side);
    if (subgroupElect() && largest > 0.0) atomicMax(counters.grid.x, floatBitsToUint(largest));
}
