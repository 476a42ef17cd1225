#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair: its points go into the lists of its dynamic bodies, side by side (block_sort
// then puts each list in entry order, whatever order the atomics gave).
#include "block.glsl"

void put(uint body, uint other, uint p, uint count, bool is_b)
{
    uint at = block_start[body] + atomicAdd(block_fill[body], count);
    for (uint k = 0u; k < count; k++) block_entries[at + k] = uvec2(block_entry(p, k, is_b), other);
}

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted()) return;
    uint count = block_points(p);
    if (count == 0u) return;
    uvec2 ab = pairs[pair_half_base() + p].xy;
    if (block_dynamic(ab.x)) put(ab.x, ab.y, p, count, false);
    if (block_dynamic(ab.y)) put(ab.y, ab.x, p, count, true);
}
