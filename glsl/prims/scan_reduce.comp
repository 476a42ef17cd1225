#version 450
#extension GL_GOOGLE_include_directive : require
// First pass of the scan (and of compaction): the sum of each tile, or the number of its
// nonzero flags, to the tile sums in scratch.
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_scan_push p; };

void main()
{
    uint n = read_count(p.count.xy, p.count.z);
    uint tile = flat_group_index();
    uint first = tile * TB_PRIMS_SCAN_TILE;
    if (first >= n) return; // the whole workgroup: no barrier is skipped by half of it
    uint m = min(n - first, TB_PRIMS_SCAN_TILE);
    Uints data = Uints(p.data.xy);
    bool flags = p.count.w == TB_PRIMS_SCAN_MODE_FLAGS;
    uint sum = 0u;
    for (uint j = 0u; j < SCAN_ITEMS; j++) {
        uint e = tile_index(j, SCAN_ITEMS);
        if (e < m) {
            uint v = data.v[first + e];
            sum += flags ? (v != 0u ? 1u : 0u) : v;
        }
    }
    uint total;
    subgroups_exclusive(subgroupAdd(sum), total);
    if (thread_rank() == 0u) Uints(p.aux.xy).v[tile] = total;
}
