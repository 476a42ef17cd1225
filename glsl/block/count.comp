#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair: each dynamic body counts the contacts (pairs with points) it is in, at either
// end; the counts are then scanned in place into the starts of the lists.
#include "block.glsl"

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted() || manifolds[p].info.x == 0u) return;
    uvec2 ab = pairs[pair_half_base() + p].xy;
    if (block_dynamic(ab.x)) atomicAdd(block_start[ab.x], 1u);
    if (block_dynamic(ab.y)) atomicAdd(block_start[ab.y], 1u);
}
