// The midphase's split (src/broadphase/pair_split.h): the broadphase reports a pair
// with a mesh or compound body once, as (a, b, TB_NO_COLOUR, TB_PAIR_UNSPLIT); these passes,
// one thread a pair, turn each such record into convex pairs and copy every other record as
// it is:
// - against a mesh or heightfield, one pair per triangle whose BVH leaf box (or cell) the
//   other body's box touches, grown by the contact margin, or each of its children's boxes
//   when it is a compound: (a, b, TB_NO_COLOUR, triangle + 1 | child << TB_PAIR_TRIANGLE_BITS);
// - otherwise one pair per pair of parts (children, or the body itself) that may touch
//   within the step: (a, b, TB_NO_COLOUR, a's child | b's child << 16).
// A body pair none of whose parts touch is dropped, unless the broadphase starts from last
// step's pairs (isap, push.args.x = 1) and neither body is a mesh (isap finds those again
// each step): then it keeps its record, unsplit, so a pair whose boxes still overlap stays
// in that list (the narrowphase gives it an empty manifold at once).
//
// The split's arrays, by device address in the push constants (tb_gpu_broadphase_push):
// address[0].xy the split pairs (uvec4 per pair of the capacity), address[0].zw each
// record's count, scanned into offsets in place.
#ifndef TB_MIDPHASE_SPLIT_GLSL
#define TB_MIDPHASE_SPLIT_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "mesh.glsl"
#include "compound.glsl"

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer SplitPairs { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer SplitCounts { uint v[]; };

#define split_pairs (SplitPairs(push.address[0].xy).v)
#define split_counts (SplitCounts(push.address[0].zw).v)

// A pair of the split: written at `at` + found when `write`; returns found + 1.
uint split_put(uint a, uint b, uint sub, bool write, uint at, uint found)
{
    if (write) split_pairs[at + found] = uvec4(a, b, TB_NO_COLOUR, sub);
    return found + 1u;
}

// A heightfield's triangles under the box [lo, hi] (its frame): both of every cell in the
// box's range of rows and columns whose corners reach the box's height range. `part` (the
// other body's child, shifted into place) joins each triangle + 1.
uint split_cells(uint a, uint b, uint shape, vec3 lo, vec3 hi, uint part, bool write, uint at,
                 uint found)
{
    field_view field = field_of_shape(shape);
    uvec4 range = field_cells(field, lo, hi);
    for (uint k = range.y; k < range.w; k++) {
        for (uint i = range.x; i < range.z; i++) {
            float h0 = field_height(field, i, k), h1 = field_height(field, i + 1u, k);
            float h2 = field_height(field, i, k + 1u), h3 = field_height(field, i + 1u, k + 1u);
            if (min(min(h0, h1), min(h2, h3)) > hi.y || max(max(h0, h1), max(h2, h3)) < lo.y)
                continue;
            uint n = k * (field.count.x - 1u) + i;
            if ((field_flags(field, 2u * n) & TB_MESH_DEGENERATE) != 0u) continue;   // a hole
            found = split_put(a, b, (2u * n + 1u) | part, write, at, found);
            found = split_put(a, b, (2u * n + 2u) | part, write, at, found);
        }
    }
    return found;
}

// A mesh's triangles whose BVH leaf boxes touch the box [lo, hi] (its frame).
uint split_leaves(uint a, uint b, uint shape, vec3 lo, vec3 hi, uint part, bool write, uint at,
                  uint found)
{
    mesh_view mesh = mesh_of_shape(shape);
    uvec3 qlo, qhi;
    if (!mesh_query(mesh, lo, hi, qlo, qhi)) return found;
    for (uint i = 0u; i < mesh.nodes;) {
        uvec4 node = mesh.image.v[mesh.sections.x + i];
        bool hit = bvh_node_overlaps(node, qlo, qhi);
        if (hit && bvh_is_leaf(node))
            found = split_put(a, b, ((node.w & ~TB_BVH_LEAF) + 1u) | part, write, at, found);
        i = bvh_next(i, node, hit);
    }
    return found;
}

// The pairs of (a, b), one of them a mesh or heightfield body: one per triangle near the
// other's box, or near each of its children's boxes when it is a compound.
uint split_triangles(uint a, uint b, bool write, uint at)
{
    uint m = body_is(a, TB_BODY_FLAG_MESH) ? a : b, other = m == a ? b : a;
    uint shape = body_info[m].x;
    bool field = shapes[shape].info.x == TB_GPU_SHAPE_HEIGHTFIELD;
    part_frame f = part_frame_of(other);
    uint found = 0u;
    for (uint c = 0u; c < f.parts; c++) {
        vec3 lo, hi;
        frame_part_box(f, c, params.contact.x, lo, hi);
        mesh_local_box(body_pos[m].xyz, body_rot[m], lo, hi, lo, hi);
        uint part = c << TB_PAIR_TRIANGLE_BITS;
        if (field) found = split_cells(a, b, shape, lo, hi, part, write, at, found);
        else found = split_leaves(a, b, shape, lo, hi, part, write, at, found);
    }
    return found;
}

// The second body's parts whose boxes touch the first body's box: bits of a 64-bit mask.
uvec2 split_near_parts(part_frame f2, uint first)
{
    uvec2 near = uvec2(0u);
    for (uint j = 0u; j < f2.parts; j++) {
        vec3 lo, hi;
        frame_part_box(f2, j, params.contact.x, lo, hi);
        if (boxes_touch(lo, hi, body_aabb_min[first].xyz, body_aabb_max[first].xyz))
            near[j >> 5] |= 1u << (j & 31u);
    }
    return near;
}

// The pairs of parts of (a, b), one of them a compound: counted, or also written from `at`
// in the split pairs when `write`. The tests run in one order of the two bodies (lower
// index first), whichever the record holds first, so the split depends on the two bodies
// only. A child of the first whose box misses the second's is skipped whole; the rest meet
// the second's near parts as oriented boxes (a turned thin child's axis-aligned box is
// several times its size).
uint split_parts(uint a, uint b, bool write, uint at)
{
    bool flip = a > b;
    uint first = flip ? b : a, second = flip ? a : b;
    part_frame f1 = part_frame_of(first), f2 = part_frame_of(second);
    float half_margin = 0.5 * params.contact.x;
    uvec2 near = split_near_parts(f2, first);
    uint found = 0u;
    for (uint i = 0u; i < f1.parts && near != uvec2(0u); i++) {
        vec3 lo, hi;
        frame_part_box(f1, i, params.contact.x, lo, hi);
        if (!boxes_touch(lo, hi, body_aabb_min[second].xyz, body_aabb_max[second].xyz)) continue;
        oriented_box box1 = part_oriented_box(f1, i, half_margin);
        for (uvec2 left = near; left != uvec2(0u);) {
            uint word = left.x != 0u ? 0u : 1u;
            uint j = 32u * word + uint(findLSB(left[word]));
            left[word] &= left[word] - 1u;
            if (!oriented_boxes_touch(box1, part_oriented_box(f2, j, half_margin))) continue;
            if (write) split_pairs[at + found] = uvec4(a, b, TB_NO_COLOUR, flip ? j | (i << 16) : i | (j << 16));
            found++;
        }
    }
    bool keep_apart = push.args.x != 0u;
    if (found == 0u && keep_apart && write) split_pairs[at] = uvec4(a, b, TB_NO_COLOUR, TB_PAIR_UNSPLIT);
    return keep_apart ? max(found, 1u) : found;
}

// How many pairs record `pair` becomes (written from `at` when `write`).
uint split_record(uvec4 pair, bool write, uint at)
{
    if (pair.w != TB_PAIR_UNSPLIT) {
        if (write) split_pairs[at] = pair;
        return 1u;
    }
    if (pair_has_mesh(pair)) return split_triangles(pair.x, pair.y, write, at);
    return split_parts(pair.x, pair.y, write, at);
}

#endif
