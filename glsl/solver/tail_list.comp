#version 450
#extension GL_GOOGLE_include_directive : require
// After a colouring that ran all TB_MAX_COLOURS rounds: flags each constraint it left
// uncoloured (it has points and no colour) for the stable compaction that lists them in
// pair order for solve_tail. The flags go to the second colour work list, the list to the
// first: colouring is done with both. Per pair, counters.pair_dispatch.
#include "world.glsl"

void main()
{
    uint p = pair_thread_index();
    if (step_aborted() || p >= counters.state.z) return;
    bool left = pairs[pair_half_base() + p].z == TB_NO_COLOUR && manifolds[p].info.x > 0u;
    colour_work[params.capacity.x + p] = left ? 1u : 0u;
}
