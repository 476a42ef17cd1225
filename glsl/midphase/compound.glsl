// Compounds as the GPU reads them: the image (layout.h, tb_gpu_compound_child) reached
// through the device address in the shape's tb_gpu_shape.hull.xy, one child at a time;
// and the boxes of a pair's parts, which the broadphase's pair output splits pairs by.
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

bool boxes_touch(vec3 lo_a, vec3 hi_a, vec3 lo_b, vec3 hi_b)
{
    return all(lessThanEqual(lo_a, hi_b)) && all(lessThanEqual(lo_b, hi_a));
}

// ---- oriented boxes: the tighter test between the parts of a compound pair ----------------

// A body as its parts' boxes need it: its pose, its parts (a compound's children, else the
// body itself), and how far any of its points may move within the step (its sweep and the
// reach of its turn, as world_aabb.comp grows its box).
struct part_frame {
    uint body;
    vec3 pos;
    mat3 rot;
    vec3 motion;      // the step's sweep
    float turn;       // how far the turn carries a point of the shape's box
    float reach;      // |motion| + turn
    uint shape, parts;
    bool compound;
};

part_frame part_frame_of(uint i)
{
    part_frame f;
    f.body = i;
    f.pos = body_pos[i].xyz;
    f.rot = quat_to_mat3(body_rot[i]);
    f.shape = body_info[i].x;
    f.compound = body_is(i, TB_BODY_FLAG_COMPOUND);
    f.parts = f.compound ? shapes[f.shape].info.y : 1u;
    f.motion = body_step_motion(i);
    f.turn = body_step_turn(i) * length(shapes[f.shape].aabb_half.xyz);
    f.reach = length(f.motion) + f.turn;
    return f;
}

// Part c's world box, grown by `grow`: the body's own box, or a compound child's box in the
// body swept over the step's motion and grown by the turn's reach as the body's own is.
void frame_part_box(part_frame f, uint c, float grow, out vec3 lo, out vec3 hi)
{
    if (!f.compound) {
        lo = body_aabb_min[f.body].xyz - grow;
        hi = body_aabb_max[f.body].xyz + grow;
        return;
    }
    tb_gpu_compound_child child = compound_of_shape(f.shape).child[c];
    vec3 centre = f.pos + f.rot * child.box_center.xyz;
    mat3 spread = mat3(abs(f.rot[0]), abs(f.rot[1]), abs(f.rot[2]));
    vec3 half_size = spread * child.box_half.xyz + grow + f.turn;
    lo = min(centre - half_size, centre - half_size + f.motion);
    hi = max(centre + half_size, centre + half_size + f.motion);
}

// A box of any orientation: centre, axes (columns), half extents.
struct oriented_box {
    vec3 centre;
    mat3 axes;
    vec3 half_size;
};

// Part c of the body: a compound's child's own box (its shape's box in its frame) placed by
// the child's pose, or the body's shape's box; grown by the body's reach and `grow`.
oriented_box part_oriented_box(part_frame f, uint c, float grow)
{
    uint s = f.shape;
    vec3 centre = f.pos;
    mat3 axes = f.rot;
    if (f.compound) {
        tb_gpu_compound_child child = compound_of_shape(s).child[c];
        s = floatBitsToUint(child.position.w);
        centre += f.rot * child.position.xyz;
        axes = f.rot * quat_to_mat3(child.rotation);
    }
    oriented_box o;
    o.centre = centre + axes * shapes[s].aabb_center.xyz;
    o.axes = axes;
    o.half_size = shapes[s].aabb_half.xyz + f.reach + grow;
    return o;
}

// Whether the boxes are apart along one of a's axes.
bool apart_along_axes_of(oriented_box a, oriented_box b)
{
    vec3 d = b.centre - a.centre;
    for (uint k = 0u; k < 3u; k++) {
        vec3 axis = a.axes[k];
        float reach_b = dot(b.half_size, abs(axis * b.axes));
        if (abs(dot(d, axis)) > a.half_size[k] + reach_b) return true;
    }
    return false;
}

// Oriented boxes overlap unless one's face axes separate them (the nine edge axes of the
// full test are left out: they rarely separate what the six do not, and this is a cull).
bool oriented_boxes_touch(oriented_box a, oriented_box b)
{
    return !apart_along_axes_of(a, b) && !apart_along_axes_of(b, a);
}

#endif
