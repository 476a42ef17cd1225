#version 450
#extension GL_GOOGLE_include_directive : require
// First pass of a sort: its plan from the count. Blocks: as many as there are tiles, up to
// the most the host allows (p.plan.w, within the device's workgroup count limit); then
// several tiles each. Spine: one workgroup per digit, or, when its rows (one count per
// block) are short, one subgroup per digit (see sort_spine).
#include "radix.glsl"

void main()
{
    if (gl_LocalInvocationIndex != 0u) return;
    uint tiles = ceil_div(read_count(p.count.xy, p.count.z), TB_PRIMS_SORT_TILE);
    uint tiles_per_block = max(ceil_div(tiles, p.plan.w), 1u);
    uint blocks = ceil_div(tiles, tiles_per_block);
    Uints plan = Uints(p.plan.xy);
    plan.v[0] = blocks;
    plan.v[1] = 1u;
    plan.v[2] = 1u;
    plan.v[4] = short_spine_rows(blocks) ? ceil_div(TB_PRIMS_RADIX, p.plan.z) : TB_PRIMS_RADIX;
    plan.v[5] = 1u;
    plan.v[6] = 1u;
    plan.v[PLAN_TILES_PER_BLOCK] = tiles_per_block;
    plan.v[PLAN_BLOCKS] = blocks;
}
