#version 450
#extension GL_GOOGLE_include_directive : require
// Middle pass of the scan (and of compaction), one workgroup: exclusive scan of the tile
// sums in place, a tile of them at a time, and the grand total where one is wanted.
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_scan_push p; };

void main()
{
    uint tiles = ceil_div(read_count(p.count.xy, p.count.z), TB_PRIMS_SCAN_TILE);
    Uints sums = Uints(p.aux.xy);
    uint carry = 0u;
    for (uint first = 0u; first < tiles; first += TB_PRIMS_SCAN_TILE)
        carry += scan_tile(sums, sums, first, min(tiles - first, TB_PRIMS_SCAN_TILE), carry);
    if (thread_rank() == 0u && !is_null(p.aux.zw)) Uints(p.aux.zw).v[0] = carry;
}
