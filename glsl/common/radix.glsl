// What the radix sort passes (glsl/prims/sort_*) share: the plan of tiles and blocks, the
// digit of a key, and the peers of an element (the lanes of its subgroup with its digit).
//
// A pass works on tiles of TB_PRIMS_SORT_TILE keys. A workgroup takes a block of
// consecutive tiles: one tile per block up to TB_PRIMS_SORT_MAX_BLOCKS tiles, more beyond,
// so that the digit counts per block (written, scanned and read by every pass) stay few.
#ifndef TB_RADIX_GLSL
#define TB_RADIX_GLSL

#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_sort_push p; };

// Elements per invocation in a sort tile.
const uint SORT_ITEMS = TB_PRIMS_SORT_TILE / WORKGROUP_SIZE;

// Where sort_args keeps the plan (see tb_gpu_sort_push.plan).
const uint PLAN_TILES_PER_BLOCK = 8u;
const uint PLAN_BLOCKS = 9u;

uint plan_word(uint i)
{
    return Uints(p.plan.xy).v[i];
}

// A spine row (one digit's counts over the blocks) this short is scanned by one subgroup.
bool short_spine_rows(uint blocks)
{
    return blocks <= 4u * gl_SubgroupSize;
}

uint digit_shift() { return p.count.w & 0xffu; }
uint digit_bits() { return p.count.w >> 8; }
uint radix() { return 1u << digit_bits(); }

uint digit_of(uint key)
{
    return (key >> digit_shift()) & (radix() - 1u);
}

// Lanes of the subgroup whose element is valid and has digit d: one ballot per digit bit
// instead of a shared-memory histogram round trip. Uniform control flow only.
uvec4 digit_peers(uint d, bool valid)
{
    uvec4 peers = subgroupBallot(valid);
    for (uint b = 0u; b < digit_bits(); b++) {
        bool one = ((d >> b) & 1u) != 0u;
        uvec4 ones = subgroupBallot(one);
        peers &= one ? ones : ~ones;
    }
    return peers;
}

#endif
