#version 450
#extension GL_GOOGLE_include_directive : require
// The midphase split (split.glsl), first pass: how many pairs each of the broadphase's
// records becomes. One thread a record, dispatched over counters.pair_dispatch; a scan
// then turns the counts into offsets and their sum into counters.grid.w.
#include "world.glsl"
#include "split.glsl"

void main()
{
    if (step_aborted()) return;
    uint p = pair_thread_index();
    if (p >= counters.state.z) return;
    uvec4 pair = pairs[pair_half_base() + p];
    split_counts[p] = split_record(pair, false, 0u);
}
