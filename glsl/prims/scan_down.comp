#version 450
#extension GL_GOOGLE_include_directive : require
// Last pass of the scan: each tile scanned, plus the scanned sum of the tiles before it.
// In place works: each element is read and written by the same invocation.
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_scan_push p; };

void main()
{
    uint n = read_count(p.count.xy, p.count.z);
    uint tile = flat_group_index();
    uint first = tile * TB_PRIMS_SCAN_TILE;
    if (first >= n) return; // the whole workgroup
    uint carry = Uints(p.aux.xy).v[tile];
    scan_tile(Uints(p.data.xy), Uints(p.data.zw), first, min(n - first, TB_PRIMS_SCAN_TILE),
              carry);
}
