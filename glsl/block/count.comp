#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair: each dynamic body counts the contact points it has in the pair, at either end;
// the counts are then scanned in place into the starts of the lists.
#include "block.glsl"

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted()) return;
    uint count = block_points(p);
    if (count == 0u) return;
    uvec2 ab = pairs[pair_half_base() + p].xy;
    if (block_dynamic(ab.x)) atomicAdd(block_start[ab.x], count);
    if (block_dynamic(ab.y)) atomicAdd(block_start[ab.y], count);
}
