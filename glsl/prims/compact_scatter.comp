#version 450
#extension GL_GOOGLE_include_directive : require
// Last pass of compaction: the index of every nonzero flag goes to its rank among the
// nonzero flags, the scanned count of the tiles before plus the rank within the tile
// (ballots within a subgroup, subgroup totals across the workgroup).
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_scan_push p; };

const uint NONE = 0xffffffffu;

void main()
{
    uint n = read_count(p.count.xy, p.count.z);
    uint tile = flat_group_index();
    uint first = tile * TB_PRIMS_SCAN_TILE;
    if (first >= n) return; // the whole workgroup
    uint m = min(n - first, TB_PRIMS_SCAN_TILE);
    Uints flags = Uints(p.data.xy);
    uint rank[SCAN_ITEMS];
    uint run = 0u;
    for (uint j = 0u; j < SCAN_ITEMS; j++) {
        uint e = tile_index(j, SCAN_ITEMS);
        bool set = false;
        if (e < m) set = flags.v[first + e] != 0u;
        uvec4 ballot = subgroupBallot(set);
        rank[j] = set ? run + subgroupBallotExclusiveBitCount(ballot) : NONE;
        run += subgroupBallotBitCount(ballot);
    }
    uint total;
    uint base = Uints(p.aux.xy).v[tile] + subgroups_exclusive(run, total);
    Uints out_indices = Uints(p.data.zw);
    for (uint j = 0u; j < SCAN_ITEMS; j++)
        if (rank[j] != NONE) out_indices.v[base + rank[j]] = first + tile_index(j, SCAN_ITEMS);
}
