// The compound split (src/broadphase/compound_split.h): the broadphase reports a pair with a
// compound body once, as (a, b, TB_NO_COLOUR, TB_PAIR_UNSPLIT); these passes, one thread a
// pair, turn each such record into one pair per pair of parts (children, or the body
// itself) that may touch within the step, as (a, b, TB_NO_COLOUR, a's child | b's child
// << 16), and copy every other record as it is. A body pair none of whose parts touch is
// dropped, unless the broadphase starts from last step's pairs (isap, push.args.x = 1):
// then it keeps its record, unsplit, so a pair whose boxes still overlap stays in that list
// (the narrowphase gives it an empty manifold at once).
//
// The split's arrays, by device address in the push constants (tb_gpu_broadphase_push):
// address[0].xy the split pairs (uvec4 per pair of the capacity), address[0].zw each
// record's count, scanned into offsets in place.
#ifndef TB_MIDPHASE_SPLIT_GLSL
#define TB_MIDPHASE_SPLIT_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "compound.glsl"

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer SplitPairs { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer SplitCounts { uint v[]; };

#define split_pairs (SplitPairs(push.address[0].xy).v)
#define split_counts (SplitCounts(push.address[0].zw).v)

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

#endif
