// A triangle mesh as the GPU reads it: its image (layout.h, tb_gpu_mesh_header), reached
// through the device address in its shape's tb_gpu_shape.hull.xy, and the walk of its BVH
// (bvh.glsl) that finds the triangles near a box.
#ifndef TB_MIDPHASE_MESH_GLSL
#define TB_MIDPHASE_MESH_GLSL

#include "bvh.glsl"
#include "quat.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MeshImage { uvec4 v[]; };

struct mesh_view {
    MeshImage image;
    vec3 lo, hi, scale;       // the box the BVH is quantized over, and its steps per metre
    uint nodes;               // node count
    uvec3 sections;           // first node, triangle and vertex, in uvec4 of the image
};

mesh_view mesh_of_shape(uint shape)
{
    mesh_view m;
    m.image = MeshImage(shapes[shape].hull.xy);
    uvec4 lo = m.image.v[0], scale = m.image.v[1], hi = m.image.v[2];
    m.lo = uintBitsToFloat(lo.xyz);
    m.scale = uintBitsToFloat(scale.xyz);
    m.hi = uintBitsToFloat(hi.xyz);
    m.nodes = lo.w;
    m.sections = m.image.v[3].xyz;
    return m;
}

// Triangle t: x y z its vertex indices, w its TB_MESH_* flags.
uvec4 mesh_triangle(mesh_view m, uint t)
{
    return m.image.v[m.sections.y + t];
}

vec3 mesh_vertex(mesh_view m, uint i)
{
    return uintBitsToFloat(m.image.v[m.sections.z + i].xyz);
}

// A world box [lo, hi] as a box of the mesh's frame (the mesh body at pos, turned by rot)
// that holds it.
void mesh_local_box(vec3 pos, vec4 rot, vec3 lo, vec3 hi, out vec3 local_lo, out vec3 local_hi)
{
    mat3 back = transpose(quat_to_mat3(rot));
    vec3 centre = back * (0.5 * (lo + hi) - pos);
    mat3 spread = mat3(abs(back[0]), abs(back[1]), abs(back[2]));
    vec3 half_size = spread * (0.5 * (hi - lo));
    local_lo = centre - half_size;
    local_hi = centre + half_size;
}

// Whether the box [lo, hi] (mesh frame) can touch the mesh at all; if so, its quantized
// corners for the walk.
bool mesh_query(mesh_view m, vec3 lo, vec3 hi, out uvec3 qlo, out uvec3 qhi)
{
    qlo = uvec3(0u);
    qhi = uvec3(0u);
    if (any(greaterThan(lo, m.hi)) || any(greaterThan(m.lo, hi))) return false;
    bvh_quantize(m.lo, m.scale, lo, hi, qlo, qhi);
    return true;
}

#endif
