#version 450
#extension GL_GOOGLE_include_directive : require
// Last pass of a radix sort pass: every key and value of the block to its place, stably,
// one tile after the other.
//
// Ranking: each subgroup walks its run of the tile round by round; the lanes sharing a
// digit (digit_peers) take consecutive ranks after that digit's running count in the
// subgroup, which its lowest lane reads and advances (counters private to the subgroup,
// so no atomics and no contention). Prefix sums over the subgroups and over the digits
// turn these into the key's slot in the tile sorted by digit. The tile is staged in that
// order in shared memory and written out slot by slot, so consecutive invocations write
// consecutive addresses of a digit's run instead of scattering single words.
#include "radix.glsl"

const uint NONE = 0xffffffffu;
const uint DIGITS_PER_INVOCATION = TB_PRIMS_RADIX / WORKGROUP_SIZE;

shared uint s_rank[MAX_SUBGROUPS * TB_PRIMS_RADIX]; // [subgroup * radix + digit]
shared uint s_tile_start[TB_PRIMS_RADIX];  // first slot of each digit in the sorted tile
shared uint s_dest[TB_PRIMS_RADIX];        // destination of slot 0 for each digit's slots
shared uint s_stage[TB_PRIMS_SORT_TILE];   // the tile in sorted order, keys then values

// Each invocation owns a run of digits: their destinations live in its registers.
uint first_digit()
{
    return thread_rank() * DIGITS_PER_INVOCATION;
}

// Where the block's first key of each owned digit goes: the digit's start (the exclusive
// scan of the totals) plus the block's start within the digit (the scanned spine).
void block_starts(uint block, uint blocks, out uint next[DIGITS_PER_INVOCATION])
{
    Uints totals = Uints(p.spine.zw), spine = Uints(p.spine.xy);
    uint total[DIGITS_PER_INVOCATION];
    uint sum = 0u;
    for (uint i = 0u; i < DIGITS_PER_INVOCATION; i++) {
        total[i] = 0u;
        if (first_digit() + i < radix()) total[i] = totals.v[first_digit() + i];
        sum += total[i];
    }
    uint unused;
    uint start = workgroup_exclusive_scan(sum, unused);
    for (uint i = 0u; i < DIGITS_PER_INVOCATION; i++) {
        uint d = first_digit() + i;
        next[i] = start;
        if (d < radix()) next[i] += spine.v[d * blocks + block];
        start += total[i];
    }
}

// Per digit: the counts of the subgroups become their exclusive prefix; returns the
// digit's count in the tile.
uint subgroup_prefix(uint d)
{
    uint run = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; s++) {
        uint c = s_rank[s * TB_PRIMS_RADIX + d];
        s_rank[s * TB_PRIMS_RADIX + d] = run;
        run += c;
    }
    return run;
}

// s_tile_start and s_dest of this tile; next[] moves past the tile's keys.
void tile_starts(inout uint next[DIGITS_PER_INVOCATION])
{
    uint count[DIGITS_PER_INVOCATION];
    uint sum = 0u;
    for (uint i = 0u; i < DIGITS_PER_INVOCATION; i++) {
        count[i] = subgroup_prefix(first_digit() + i);
        sum += count[i];
    }
    uint unused;
    uint start = workgroup_exclusive_scan(sum, unused);
    for (uint i = 0u; i < DIGITS_PER_INVOCATION; i++) {
        uint d = first_digit() + i;
        s_tile_start[d] = start;
        s_dest[d] = next[i] - start; // unsigned wrap cancels in s_dest + slot
        next[i] += count[i];
        start += count[i];
    }
}

void scatter_tile(uint first, uint m, inout uint next[DIGITS_PER_INVOCATION])
{
    for (uint i = thread_rank(); i < gl_NumSubgroups * TB_PRIMS_RADIX; i += WORKGROUP_SIZE)
        s_rank[i] = 0u;
    Uints keys_in = Uints(p.keys.xy), values_in = Uints(p.values.xy);
    uint key[SORT_ITEMS], value[SORT_ITEMS], slot[SORT_ITEMS], dest[SORT_ITEMS];
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) { // all loads in flight at once
        uint e = tile_index(j, SORT_ITEMS);
        key[j] = 0u;
        value[j] = 0u;
        if (e < m) {
            key[j] = keys_in.v[first + e];
            value[j] = values_in.v[first + e];
        }
    }
    barrier(); // s_rank is zero

    uint row = gl_SubgroupID * TB_PRIMS_RADIX;
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) {
        bool valid = tile_index(j, SORT_ITEMS) < m;
        uint d = digit_of(key[j]);
        uvec4 peers = digit_peers(d, valid);
        uint leader = valid ? subgroupBallotFindLSB(peers) : gl_SubgroupInvocationID;
        uint before = 0u;
        if (valid && gl_SubgroupInvocationID == leader) {
            before = s_rank[row + d];
            s_rank[row + d] = before + subgroupBallotBitCount(peers);
        }
        before = subgroupShuffle(before, leader);
        slot[j] = valid ? before + subgroupBallotExclusiveBitCount(peers) : NONE;
        subgroupBarrier(); // the next round's leader may read what this one wrote
    }
    barrier();
    tile_starts(next);
    barrier();

    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) {
        if (slot[j] != NONE) {
            uint d = digit_of(key[j]);
            slot[j] += s_tile_start[d] + s_rank[row + d];
            s_stage[slot[j]] = key[j];
        }
    }
    barrier();
    Uints keys_out = Uints(p.keys.zw);
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) {
        uint s = j * WORKGROUP_SIZE + thread_rank();
        dest[j] = NONE;
        if (s < m) {
            uint k = s_stage[s];
            dest[j] = s_dest[digit_of(k)] + s;
            keys_out.v[dest[j]] = k;
        }
    }
    barrier();
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++)
        if (slot[j] != NONE) s_stage[slot[j]] = value[j];
    barrier();
    Uints values_out = Uints(p.values.zw);
    [[unroll]] for (uint j = 0u; j < SORT_ITEMS; j++) {
        uint s = j * WORKGROUP_SIZE + thread_rank();
        if (s < m) values_out.v[dest[j]] = s_stage[s];
    }
    barrier(); // s_stage and s_rank are free for the next tile
}

void main()
{
    uint block = flat_group_index(), blocks = plan_word(PLAN_BLOCKS);
    if (block >= blocks) return; // the whole workgroup
    uint n = read_count(p.count.xy, p.count.z);
    uint tiles = ceil_div(n, TB_PRIMS_SORT_TILE), per_block = plan_word(PLAN_TILES_PER_BLOCK);
    uint next[DIGITS_PER_INVOCATION];
    block_starts(block, blocks, next);
    uint end = min(tiles, (block + 1u) * per_block);
    for (uint t = block * per_block; t < end; t++) {
        uint first = t * TB_PRIMS_SORT_TILE;
        scatter_tile(first, min(n - first, TB_PRIMS_SORT_TILE), next);
    }
}
