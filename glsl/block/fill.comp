#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair: the contact goes into the lists of its dynamic bodies (block_sort then puts
// each list in pair order, whatever order the atomics gave).
#include "block.glsl"

void put(uint body, uint entry)
{
    uint at = atomicAdd(block_fill[body], 1u);
    block_entries[block_start[body] + at] = entry;
}

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted() || manifolds[p].info.x == 0u) return;
    uvec2 ab = pairs[pair_half_base() + p].xy;
    if (block_dynamic(ab.x)) put(ab.x, p);
    if (block_dynamic(ab.y)) put(ab.y, p | TB_BLOCK_SIDE_B);
}
