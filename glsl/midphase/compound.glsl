// Compounds as the GPU reads them: the image (layout.h, tb_gpu_compound_child) reached
// through the device address in the shape's tb_gpu_shape.hull.xy, one child at a time.
#ifndef TB_MIDPHASE_COMPOUND_GLSL
#define TB_MIDPHASE_COMPOUND_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "layout.h"
#include "quat.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer CompoundImage {
    uvec4 header;
    tb_gpu_compound_child child[];
};

CompoundImage compound_of_shape(uint shape)
{
    return CompoundImage(shapes[shape].hull.xy);
}

bool body_is_compound(uint i)
{
    return (body_info[i].y & TB_BODY_FLAG_COMPOUND) != 0u;
}

// How many children body i has as a pair sees them: a compound's count, else 1 (itself).
uint compound_parts(uint i)
{
    return body_is_compound(i) ? shapes[body_info[i].x].info.y : 1u;
}

// Child c's box in world space, swept over the step's motion as the body's own box is
// (world_aabb.comp) and grown by `grow` (body i a compound).
void compound_child_box(uint i, uint c, float grow, out vec3 lo, out vec3 hi)
{
    uint shape = body_info[i].x;
    tb_gpu_compound_child child = compound_of_shape(shape).child[c];
    mat3 r = quat_to_mat3(body_rot[i]);
    vec3 centre = body_pos[i].xyz + r * child.box_center.xyz;
    mat3 spread = mat3(abs(r[0]), abs(r[1]), abs(r[2]));
    vec3 half_size = spread * child.box_half.xyz + grow +
                     body_step_turn(i) * length(shapes[shape].aabb_half.xyz);
    vec3 sweep = body_step_motion(i);
    lo = min(centre - half_size, centre - half_size + sweep);
    hi = max(centre + half_size, centre + half_size + sweep);
}

// Part c of body i's box: a compound's child's, or the body's own.
void part_box(uint i, uint c, float grow, out vec3 lo, out vec3 hi)
{
    if (body_is_compound(i)) {
        compound_child_box(i, c, grow, lo, hi);
    } else {
        lo = body_aabb_min[i].xyz - grow;
        hi = body_aabb_max[i].xyz + grow;
    }
}

bool boxes_touch(vec3 lo_a, vec3 hi_a, vec3 lo_b, vec3 hi_b)
{
    return all(lessThanEqual(lo_a, hi_b)) && all(lessThanEqual(lo_b, hi_a));
}

#endif
