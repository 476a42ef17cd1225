#version 450
#extension GL_GOOGLE_include_directive : require
// One thread per query box: the triangles of a mesh's BVH whose leaf boxes overlap it
// (bvh.glsl's walk), as the mesh midphase will find them for a body's box. Operands come by
// address (tb_gpu_bvh_query_push): the nodes, the queries (low and high corner, a vec4
// each), and per query a count followed by up to results.z triangles (a query that finds more
// counts them all and keeps the first out.z).
#include "bvh.glsl"

layout(local_size_x_id = TB_SPEC_WORKGROUP_SIZE) in;
layout(push_constant) uniform Push { tb_gpu_bvh_query_push p; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Boxes { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Results { uint v[]; };

void main()
{
    uint q = gl_GlobalInvocationID.x;
    if (q >= p.results.w) return;
    vec3 lo = Boxes(p.arrays.zw).v[2u * q].xyz, hi = Boxes(p.arrays.zw).v[2u * q + 1u].xyz;
    Results found_at = Results(p.results.xy);
    uint keep = p.results.z, base = q * (keep + 2u), found = 0u, looked = 0u;
    vec3 mesh_lo = p.mesh_lo.xyz, mesh_hi = p.mesh_hi.xyz;
    if (all(lessThanEqual(lo, mesh_hi)) && all(lessThanEqual(mesh_lo, hi))) {
        uvec3 qlo, qhi;
        bvh_quantize(mesh_lo, p.scale.xyz, lo, hi, qlo, qhi);
        BvhNodes nodes = BvhNodes(p.arrays.xy);
        uint count = floatBitsToUint(p.mesh_lo.w);
        for (uint i = 0u; i < count;) {
            uvec4 node = nodes.v[i];
            looked++;
            bool hit = bvh_node_overlaps(node, qlo, qhi);
            if (hit && bvh_is_leaf(node)) {
                if (found < keep) found_at.v[base + 2u + found] = node.w & ~TB_BVH_LEAF;
                found++;
            }
            i = bvh_next(i, node, hit);
        }
    }
    found_at.v[base] = found;
    found_at.v[base + 1u] = looked;
}
