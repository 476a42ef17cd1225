// The linear BVH as its kernels see it (layout.h describes the nodes and the links): node
// references, boxes, and the stackless walk along escapes. Arrays are device addresses, so
// the same tree serves the broadphase, a mesh's triangles or ray queries.
#ifndef TB_LBVH_GLSL
#define TB_LBVH_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "layout.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer LbvhNodes {
    tb_gpu_lbvh_node node[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LbvhUints { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer LbvhVec4s { vec4 v[]; };

bool lbvh_is_leaf(uint ref)
{
    return (ref & TB_LBVH_LEAF) != 0u;
}

// Where a referenced node lives in the node array (leaves after `capacity` internal nodes).
uint lbvh_slot(uint ref, uint capacity)
{
    return lbvh_is_leaf(ref) ? capacity + (ref & ~TB_LBVH_LEAF) : ref;
}

// Index into a links section.
uint lbvh_link(uint section, uint index, uint capacity)
{
    return section * capacity + index;
}

uint lbvh_leaf_count_index(uint capacity)
{
    return TB_LBVH_LINK_SECTIONS * capacity;
}

vec3 lbvh_min(tb_gpu_lbvh_node n)
{
    return uintBitsToFloat(n.lo.xyz);
}

vec3 lbvh_max(tb_gpu_lbvh_node n)
{
    return uintBitsToFloat(n.hi.xyz);
}

// Does the box [lo, hi] grown by `margin` on its lower side touch the node's box? Grown by
// the margin once, as two boxes each grown by half of it (touching counts).
bool lbvh_touches(vec3 lo, vec3 hi, float margin, tb_gpu_lbvh_node n)
{
    return !any(greaterThan(lo - margin, lbvh_max(n))) &&
           !any(greaterThan(lbvh_min(n) - margin, hi));
}

// The thread's index in a dispatch laid out in rows of workgroups (layout.h).
uint lbvh_thread_index()
{
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    return group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

#endif
