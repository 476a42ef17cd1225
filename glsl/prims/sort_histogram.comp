#version 450
#extension GL_GOOGLE_include_directive : require
// First pass of a radix sort pass: how many keys of each digit every block holds, stored
// digit-major (spine[digit * blocks + block]) so that one exclusive scan of a digit's row
// gives each block its start among that digit's keys.
#include "radix.glsl"

shared uint s_count[TB_PRIMS_RADIX];

void count_tile(uint first, uint m)
{
    Uints keys = Uints(p.keys.xy);
    uint key[SORT_ITEMS];
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) { // all loads in flight at once
        uint e = tile_index(j, SORT_ITEMS);
        key[j] = 0u;
        if (e < m) key[j] = keys.v[first + e];
    }
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) {
        bool valid = tile_index(j, SORT_ITEMS) < m;
        uint d = digit_of(key[j]);
        // A shared atomic per key: cheaper than matching digits with ballots (measured),
        // and counts are the same in any order. A run of equal digits (sorted input, few
        // distinct keys) would serialize on one counter: it takes one atomic instead.
        if (subgroupAll(valid) && subgroupAllEqual(d)) {
            if (subgroupElect()) atomicAdd(s_count[d], gl_SubgroupSize);
        } else if (valid) {
            atomicAdd(s_count[d], 1u);
        }
    }
}

void main()
{
    uint block = flat_group_index(), blocks = plan_word(PLAN_BLOCKS);
    if (block >= blocks) return; // the whole workgroup
    uint n = read_count(p.count.xy, p.count.z);
    uint tiles = ceil_div(n, TB_PRIMS_SORT_TILE), per_block = plan_word(PLAN_TILES_PER_BLOCK);
    for (uint d = thread_rank(); d < TB_PRIMS_RADIX; d += WORKGROUP_SIZE) s_count[d] = 0u;
    barrier();
    uint end = min(tiles, (block + 1u) * per_block);
    for (uint t = block * per_block; t < end; t++) {
        uint first = t * TB_PRIMS_SORT_TILE;
        count_tile(first, min(n - first, TB_PRIMS_SORT_TILE));
    }
    barrier();
    Uints spine = Uints(p.spine.xy);
    for (uint d = thread_rank(); d < radix(); d += WORKGROUP_SIZE)
        spine.v[d * blocks + block] = s_count[d];
}
