// What every contact routine shares: the two bodies as the narrowphase sees them, and the
// manifold being written, with the warm start from last step's manifold of the same pair.
//
// Points are written to the manifold as they are found (a store with a point index is
// cheap; a private array of points indexed at run time would not be), each with the
// impulses last step's point of the same feature key ended with.
#ifndef TB_NP_MANIFOLD_GLSL
#define TB_NP_MANIFOLD_GLSL

#include "../midphase/compound.glsl"

#define NP_NONE 0xffffffffu

// A body's pose and shape.
struct np_body {
    vec3 pos;
    mat3 rot;       // columns: the body's axes in world space
    vec4 params;    // sphere: x radius; box: xyz half extents; plane: xyz normal, w offset
    vec2 material;  // x friction, y restitution
    uint type;      // TB_GPU_SHAPE_*
    uint shape;     // index into shapes: hull routines find the hull data through it
};

// Shape s placed at pos, turned by rot.
np_body np_posed_shape(uint s, vec3 pos, mat3 rot)
{
    np_body b;
    b.pos = pos;
    b.rot = rot;
    b.params = shapes[s].params;
    b.material = shapes[s].material.xy;
    b.type = shapes[s].info.x;
    b.shape = s;
    return b;
}

np_body np_load_body(uint i)
{
    return np_posed_shape(body_info[i].x, body_pos[i].xyz, quat_to_mat3(body_rot[i]));
}

// Part c of body i as a pair sees it: a compound's child c, placed by the child's pose in
// the body, with the child's own shape and material; any other body is itself.
np_body np_load_part(uint i, uint c)
{
    np_body b = np_load_body(i);
    if (b.type != TB_GPU_SHAPE_COMPOUND) return b;
    tb_gpu_compound_child child = compound_of_shape(b.shape).child[c];
    return np_posed_shape(floatBitsToUint(child.position.w), b.pos + b.rot * child.position.xyz,
                          b.rot * quat_to_mat3(child.rotation));
}

// Capsules, cylinders and cones: their pairs are narrowphase/round_points' (round.glsl).
bool np_is_round(uint type)
{
    return type == TB_GPU_SHAPE_CAPSULE || type == TB_GPU_SHAPE_CYLINDER ||
           type == TB_GPU_SHAPE_CONE;
}

// Column i of m and component i of v for a run-time i, without a private array.
vec3 np_col(mat3 m, uint i)
{
    return i == 0u ? m[0] : (i == 1u ? m[1] : m[2]);
}

float np_comp(vec3 v, uint i)
{
    return i == 0u ? v.x : (i == 1u ? v.y : v.z);
}

// +1 where v >= 0, else -1 (sign() would give 0 on a tie and lose a corner).
vec3 np_signs(vec3 v)
{
    return mix(vec3(-1.0), vec3(1.0), greaterThanEqual(v, vec3(0.0)));
}

// The manifold being written, and last step's manifold of the same pair.
struct np_target {
    uint slot;            // index of this step's manifold (its pair's index within the half)
    uint prev;            // index of last step's manifold of the pair, NP_NONE if it had none
    uint prev_count;
    uvec4 prev_features;
};

// Last step's pair (a, b) in the run of pairs its finder found (the finder is a or b;
// src/broadphase/broadphase.h), which body_pairs[finder] locates (x, y for even halves,
// z, w for odd ones; counts are 0 before the first step). `sub` tells the pairs of one
// body pair apart: the triangle + 1 of a mesh pair, else 0.
uint np_find_in_run(uint finder, uint a, uint b, uint sub, uint prev_half)
{
    uvec4 owned = body_pairs[finder];
    uvec2 run = prev_half == 0u ? owned.xy : owned.zw;
    uint first = prev_half * params.capacity.x + run.x;
    for (uint i = 0u; i < run.y; i++)
        if (pairs[first + i].xyw == uvec3(a, b, sub)) return run.x + i;
    return NP_NONE;
}

uint np_find_previous(uint a, uint b, uint sub, uint prev_half)
{
    uint found = np_find_in_run(a, a, b, sub, prev_half);
    return found != NP_NONE ? found : np_find_in_run(b, a, b, sub, prev_half);
}

// The manifold `slot` continuing last step's manifold `prev` (NP_NONE: none).
np_target np_target_after(uint slot, uint prev)
{
    np_target t;
    t.slot = slot;
    t.prev = prev;
    t.prev_count = 0u;
    t.prev_features = uvec4(0u);
    if (t.prev != NP_NONE) {
        t.prev_count = min(prev_manifolds[t.prev].info.x, uint(TB_MAX_MANIFOLD_POINTS));
        t.prev_features = prev_manifolds[t.prev].feature;
    }
    return t;
}

np_target np_target_make(uint slot, uint a, uint b, uint sub, uint prev_half)
{
    return np_target_after(slot, np_find_previous(a, b, sub, prev_half));
}

// Last step's point this one continues (NP_NONE: none): the one of the same feature key.
// Its normal and friction impulses (per substep) and its static friction slip carry over;
// the step's total normal impulse (w) starts from 0.
// Features can be ambiguous where corners of the two shapes coincide (equal boxes stacked
// exactly): a tiny turn relabels the same point. A point no key matches therefore continues
// last step's nearest point within the contact margin, so a resting stack keeps its
// impulses.
uint np_warm_match(np_target t, uint feature, vec3 point)
{
    uint nearest = NP_NONE;
    float best = params.contact.x * params.contact.x;
    for (uint j = 0u; j < t.prev_count; j++) {
        if (t.prev_features[j] == feature) return j;
        vec3 d = prev_manifolds[t.prev].point[j].xyz - point;
        if (dot(d, d) <= best) { best = dot(d, d); nearest = j; }
    }
    return nearest;
}

vec2 np_prev_slip(uint prev, uint j)
{
    return slip_of_point(prev_manifolds[prev].slip[j >> 1], j);
}

// Point k: world point midway between the surfaces, separation along the normal.
void np_emit(np_target t, uint k, vec3 point, float separation, uint feature)
{
    manifolds[t.slot].point[k] = vec4(point, separation);
    uint j = np_warm_match(t, feature, point);
    manifolds[t.slot].impulse[k] = j == NP_NONE ? vec4(0.0)
                                                : vec4(prev_manifolds[t.prev].impulse[j].xyz, 0.0);
    bool same = j != NP_NONE && t.prev_features[j] == feature;
    set_manifold_slip(t.slot, k, same ? np_prev_slip(t.prev, j) : vec2(0.0));
    manifolds[t.slot].feature[k] = feature;
}

// A manifold without points as round_cull writes it for the many round pairs it finds apart:
// the count and bodies (all that is read of an empty manifold: every reader of points,
// impulses, slip and features stops at the count), the axis a pair caches cleared, nothing
// kept for reuse. Its point slots keep what they held; zeroing them, as np_finish does,
// took 0.05 of round_cull's 0.46 ms in the 100k shapes pile on an H200.
void np_finish_empty(uint slot, uint a, uint b)
{
    manifolds[slot].axis = uvec4(0u);
    manifolds[slot].normal = vec4(0.0, 1.0, 0.0, 0.0);
    manifolds[slot].info = uvec4(0u, a, b, 0u);
    manifolds[slot].measured_normal.w = 0.0;
}

// Normal, materials and count; unused points are zeroed so a step's output depends on
// nothing but its input.
void np_finish(np_target t, uint count, vec3 normal, uint a, uint b, float friction,
               float restitution)
{
    for (uint k = count; k < uint(TB_MAX_MANIFOLD_POINTS); k++) {
        manifolds[t.slot].point[k] = vec4(0.0);
        manifolds[t.slot].impulse[k] = vec4(0.0);
        set_manifold_slip(t.slot, k, vec2(0.0));
        manifolds[t.slot].feature[k] = 0u;
    }
    manifolds[t.slot].normal = vec4(normal, friction);
    manifolds[t.slot].info = uvec4(count, a, b, floatBitsToUint(restitution));
    manifolds[t.slot].measured_normal.w = 0.0;   // nothing kept (reuse.glsl), unless set after
}

#endif
