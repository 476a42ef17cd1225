// The stackless walk of a mesh's BVH (src/geom/bvh.h builds it; tb_gpu_bvh_node in
// layout.h): nodes depth first, an inner node's first child next to it and its skip index
// past its subtree. A walk tests a node's quantized box against the query's; a hit on an
// inner node steps into it (i + 1), a leaf is reported and stepped past (i + 1), a miss on
// an inner node jumps past its subtree (skip).
#ifndef TB_MIDPHASE_BVH_GLSL
#define TB_MIDPHASE_BVH_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "layout.h"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BvhNodes { uvec4 v[]; };

// A query box in the mesh's quantized coordinates: rounded outward, then widened by one
// more step so float rounding here can never make it miss what the host's double
// quantization of the nodes put at its edge; clamped to the mesh's box (the caller rejects
// a query beside the mesh first).
void bvh_quantize(vec3 mesh_lo, vec3 scale, vec3 lo, vec3 hi, out uvec3 qlo, out uvec3 qhi)
{
    qlo = uvec3(clamp(floor((lo - mesh_lo) * scale) - 1.0, 0.0, 65535.0));
    qhi = uvec3(clamp(ceil((hi - mesh_lo) * scale) + 1.0, 0.0, 65535.0));
}

bool bvh_node_overlaps(uvec4 node, uvec3 qlo, uvec3 qhi)
{
    uvec3 lo = uvec3(node.x & 0xffffu, node.x >> 16, node.y & 0xffffu);
    uvec3 hi = uvec3(node.y >> 16, node.z & 0xffffu, node.z >> 16);
    return all(lessThanEqual(lo, qhi)) && all(lessThanEqual(qlo, hi));
}

bool bvh_is_leaf(uvec4 node)
{
    return (node.w & TB_BVH_LEAF) != 0u;
}

// The node the walk goes to after node i, given whether i's box overlapped the query.
uint bvh_next(uint i, uvec4 node, bool hit)
{
    return hit || bvh_is_leaf(node) ? i + 1u : node.w;
}

#endif
