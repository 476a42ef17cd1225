#version 450
#extension GL_GOOGLE_include_directive : require
// Middle pass of a radix sort pass: exclusive scan of each digit's row of counts (one per
// block), in place, and the digit's total. The scatter turns the totals into each digit's
// start. Long rows get a workgroup per digit; short rows (small sorts) a subgroup per
// digit, without barriers and with few workgroups (sort_args decides).
#include "radix.glsl"

uint scan_short_row(Uints spine, uint first, uint n)
{
    uint total = 0u;
    for (uint at = 0u; at < n; at += gl_SubgroupSize) {
        uint i = at + gl_SubgroupInvocationID;
        uint v = 0u;
        if (i < n) v = spine.v[first + i];
        uint before = subgroupExclusiveAdd(v);
        if (i < n) spine.v[first + i] = total + before;
        total += subgroupAdd(v);
    }
    return total;
}

void main()
{
    uint blocks = plan_word(PLAN_BLOCKS);
    Uints spine = Uints(p.spine.xy), totals = Uints(p.spine.zw);
    if (short_spine_rows(blocks)) {
        uint d = flat_group_index() * gl_NumSubgroups + gl_SubgroupID;
        if (d >= radix()) return;
        uint total = scan_short_row(spine, d * blocks, blocks);
        if (subgroupElect()) totals.v[d] = total;
        return;
    }
    uint d = flat_group_index();
    if (d >= radix()) return; // the whole workgroup
    uint total = 0u;
    for (uint first = 0u; first < blocks; first += TB_PRIMS_SCAN_TILE)
        total += scan_tile(spine, spine, d * blocks + first,
                           min(blocks - first, TB_PRIMS_SCAN_TILE), total);
    if (thread_rank() == 0u) totals.v[d] = total;
}
