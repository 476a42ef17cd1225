// Triangle meshes and heightfields as the GPU reads them: their images (layout.h,
// tb_gpu_mesh_header, tb_gpu_heightfield_header), reached through the device address in
// their shape's tb_gpu_shape.hull.xy; a mesh's BVH (bvh.glsl) finds the triangles near a
// box, a heightfield's cells under it are a range of rows and columns.
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

// ---- heightfields ---------------------------------------------------------------------------

struct field_view {
    MeshImage image;
    vec3 lo, hi;              // the first and last samples' places, the lowest and highest heights
    vec2 cell;                // spacing along x and z
    uvec2 count;              // samples along x and z
    uvec2 sections;           // first height, first cell's flags
};

field_view field_of_shape(uint shape)
{
    field_view f;
    f.image = MeshImage(shapes[shape].hull.xy);
    vec4 lo = uintBitsToFloat(f.image.v[0]), hi = uintBitsToFloat(f.image.v[1]);
    uvec4 counts = f.image.v[2];
    f.lo = lo.xyz;
    f.hi = hi.xyz;
    f.cell = vec2(lo.w, hi.w);
    f.count = counts.xy;
    f.sections = counts.zw;
    return f;
}

float field_height(field_view f, uint i, uint k)
{
    uint n = k * f.count.x + i;
    return uintBitsToFloat(f.image.v[f.sections.x + n / 4u][n % 4u]);
}

// The flags of triangle t (2n or 2n + 1 of cell n).
uint field_flags(field_view f, uint t)
{
    uint n = t >> 1u;
    return (f.image.v[f.sections.y + n / 4u][n % 4u] >> (4u * (t & 1u))) & 15u;
}

vec3 field_sample(field_view f, uint i, uint k)
{
    return vec3(f.lo.x + float(i) * f.cell.x, field_height(f, i, k), f.lo.z + float(k) * f.cell.y);
}

// Triangle t's corners (counter-clockwise from above) and flags.
void field_triangle(field_view f, uint t, out vec3 p0, out vec3 p1, out vec3 p2, out uint flags)
{
    uint n = t >> 1u, cells_x = f.count.x - 1u, i = n % cells_x, k = n / cells_x;
    vec3 b = field_sample(f, i + 1u, k), c = field_sample(f, i, k + 1u);
    bool second = (t & 1u) != 0u;
    p0 = second ? b : field_sample(f, i, k);
    p1 = c;
    p2 = second ? field_sample(f, i + 1u, k + 1u) : b;
    flags = field_flags(f, t);
}

// The cells a box [lo, hi] of the field's frame lies over: x y the first column and row,
// z w one past the last; empty (z <= x or w <= y) when it misses the field.
uvec4 field_cells(field_view f, vec3 lo, vec3 hi)
{
    if (lo.y > f.hi.y || hi.y < f.lo.y) return uvec4(0u);
    vec2 first = floor((lo.xz - f.lo.xz) / f.cell), last = floor((hi.xz - f.lo.xz) / f.cell);
    vec2 cells = vec2(f.count - 1u);
    if (any(lessThan(last, vec2(0.0))) || any(greaterThanEqual(first, cells))) return uvec4(0u);
    uvec2 from = uvec2(max(first, vec2(0.0))), to = uvec2(min(last, cells - 1.0)) + 1u;
    return uvec4(from, to);
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
