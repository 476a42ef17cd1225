// What the parallel primitives (glsl/prims) share: operands as device addresses, GPU-side
// counts, tiles laid out in subgroup order, and workgroup scans built from subgroup
// operations. No descriptor set: every operand comes through the push constants, so a
// primitive works on any buffer.
//
// Subgroup order: subgroup s of a workgroup owns the contiguous run of a tile starting at
// s * items * gl_SubgroupSize; round j of lane l is element (s * items + j) * gl_SubgroupSize
// + l. Loads and stores of a round are contiguous (coalesced), and a subgroup scan or ballot
// ranks elements in tile order, which is what keeps the sort stable.
#ifndef TB_PRIMS_GLSL
#define TB_PRIMS_GLSL

#extension GL_EXT_control_flow_attributes : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require

#include "layout.h"

layout(local_size_x_id = TB_SPEC_WORKGROUP_SIZE) in;
layout(constant_id = TB_SPEC_SUBGROUP_SIZE) const uint SUBGROUP_SIZE = 32;

const uint WORKGROUP_SIZE = gl_WorkGroupSize.x;
// Shared arrays indexed by subgroup are sized from the specialization constants.
const uint MAX_SUBGROUPS = WORKGROUP_SIZE / SUBGROUP_SIZE;
// Elements per invocation in a scan tile.
const uint SCAN_ITEMS = TB_PRIMS_SCAN_TILE / WORKGROUP_SIZE;

// Any array of uint, only 4-byte aligned (operands may start at any uint of a buffer).
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Uints { uint v[]; };

bool is_null(uvec2 address)
{
    return address == uvec2(0);
}

// The element count at `address`, never more than the scratch memory was sized for.
uint read_count(uvec2 address, uint largest)
{
    return min(Uints(address).v[0], largest);
}

uint ceil_div(uint n, uint d)
{
    return n / d + (n % d != 0u ? 1u : 0u);
}

// Dispatches may come in rows of workgroups (x is limited by the device).
uint flat_group_index()
{
    return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}

// This invocation's place in subgroup order (equal to gl_LocalInvocationIndex wherever
// subgroups are laid out linearly, which is not promised).
uint thread_rank()
{
    return gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
}

// Tile element of round j of this invocation, with `items` rounds per subgroup.
uint tile_index(uint j, uint items)
{
    return (gl_SubgroupID * items + j) * gl_SubgroupSize + gl_SubgroupInvocationID;
}

shared uint s_subgroup_total[MAX_SUBGROUPS];

// Every invocation passes the total of its subgroup; returns the sum of the totals of the
// subgroups before it and sets `total` to the workgroup's. Uniform control flow only.
uint subgroups_exclusive(uint subgroup_total, out uint total)
{
    if (subgroupElect()) s_subgroup_total[gl_SubgroupID] = subgroup_total;
    barrier();
    uint before = 0u;
    total = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; s++) {
        uint t = s_subgroup_total[s];
        before += s < gl_SubgroupID ? t : 0u;
        total += t;
    }
    barrier(); // s_subgroup_total may be written again after this
    return before;
}

// Exclusive prefix sum of one value per invocation, in thread_rank order.
uint workgroup_exclusive_scan(uint x, out uint total)
{
    uint inclusive = subgroupInclusiveAdd(x);
    uint before = subgroups_exclusive(subgroupShuffle(inclusive, gl_SubgroupSize - 1u), total);
    return before + inclusive - x;
}

// Exclusive prefix sum of src.v[first + e] for e < n (n <= TB_PRIMS_SCAN_TILE), plus
// `carry`, into dst.v[first + e]; returns the sum of the n elements. dst may be src: each
// element is read and written by the same invocation. Uniform control flow only.
uint scan_tile(Uints src, Uints dst, uint first, uint n, uint carry)
{
    uint x[SCAN_ITEMS];
    [[unroll]] for (uint j = 0u; j < SCAN_ITEMS; j++) { // all loads in flight at once
        uint e = tile_index(j, SCAN_ITEMS);
        x[j] = 0u;
        if (e < n) x[j] = src.v[first + e]; // never a load beyond n, even a speculated one
    }
    uint run = 0u;
    [[unroll]] for (uint j = 0u; j < SCAN_ITEMS; j++) {
        uint inclusive = subgroupInclusiveAdd(x[j]);
        x[j] = run + inclusive - x[j];
        run += subgroupShuffle(inclusive, gl_SubgroupSize - 1u);
    }
    uint total;
    uint base = carry + subgroups_exclusive(run, total);
    [[unroll]] for (uint j = 0u; j < SCAN_ITEMS; j++) {
        uint e = tile_index(j, SCAN_ITEMS);
        if (e < n) dst.v[first + e] = base + x[j];
    }
    return total;
}

#endif
