// The incremental 3-axis sort and sweep (src/broadphase/isap.c): what its kernels share.
//
// Each step sorts the begin and end points of every body on the three axes, keeps the
// order and each endpoint's place in it, and keeps the boxes, in the half of the step's
// parity; last step's half is only read. An endpoint id is the body slot for a begin and
// n + slot for an end (n = params.counts.x). A begin's key is min - margin and an end's is
// max, exactly the terms aabbs_touch compares, and equal keys sort begins first (the sort
// is stable and begins come first in its input), so "the begin of a lies before the end of
// b" in an order says the same as aabbs_touch on that axis: a pair's overlap can only start
// or end where such endpoints change places between the orders.
#ifndef TB_ISAP_GLSL
#define TB_ISAP_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "pairs.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer IsapUints { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer IsapVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer IsapControl {
    tb_gpu_isap_control c;
};

uint isap_capacity() { return push.args.y; }
uint isap_slots() { return params.counts.x; }
uint isap_new_half() { return current_half(); }
uint isap_old_half() { return current_half() ^ 1u; }

uvec2 isap_pick(uint slot, uint h) { return h == 0u ? push.address[slot].xy : push.address[slot].zw; }
IsapUints isap_order(uint h) { return IsapUints(isap_pick(0u, h)); }
IsapUints isap_place(uint h) { return IsapUints(isap_pick(1u, h)); }
IsapVec4s isap_boxes(uint h) { return IsapVec4s(isap_pick(2u, h)); }
IsapUints isap_keys() { return IsapUints(push.address[3].xy); }
IsapControl isap_control() { return IsapControl(push.address[3].zw); }

// Element e of axis k in a per-axis array (2 * capacity entries per axis).
uint isap_at(uint k, uint e) { return k * 2u * isap_capacity() + e; }
// The sorted endpoints follow the keys in the same buffer.
uint isap_sorted_at(uint k, uint p) { return 6u * isap_capacity() + isap_at(k, p); }

vec4 isap_min(uint h, uint body) { return isap_boxes(h).v[body]; }
vec4 isap_max(uint h, uint body) { return isap_boxes(h).v[isap_capacity() + body]; }

// This step's box says the body is large (w of the stored minimum corner).
bool isap_large(uint body) { return isap_min(isap_new_half(), body).w != 0.0; }

// Last step left its half for exactly this set of bodies.
bool isap_old_valid()
{
    uvec4 set = isap_control().c.header[isap_old_half()].set;
    return set.x == 1u && set.y == params.counts.w && set.z == params.counts.x;
}

// A 64-bit count kept as two words, read approximately (it only steers a choice).
float isap_wide(uint lo, uint hi) { return float(hi) * 4294967296.0 + float(lo); }

// Search from scratch this step (isap_decide chose it).
bool isap_from_scratch()
{
    return isap_control().c.search.x == 0u;
}

// Add each invocation's value to a count kept in two words (a carry goes to the high word):
// one atomic per subgroup. Uniform control flow only.
#define ISAP_ADD_WIDE(value, lo, hi)                                  \
    {                                                                 \
        uint sum_ = subgroupAdd(value);                               \
        if (subgroupElect() && sum_ != 0u) {                          \
            uint before_ = atomicAdd(lo, sum_);                       \
            if (before_ + sum_ < before_) atomicAdd(hi, 1u);          \
        }                                                             \
    }

#endif
