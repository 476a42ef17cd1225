#version 450
#extension GL_GOOGLE_include_directive : require
// The midphase split (split.glsl), second pass: each record's pairs written at its offset in
// the split pairs, in the record's order, so every finder's run stays whole and in order.
// One thread a record, dispatched over counters.pair_dispatch (still the records').
#include "world.glsl"
#include "split.glsl"

void main()
{
    if (step_aborted()) return;
    uint p = pair_thread_index();
    if (p >= counters.grid.w) return;
    split_record(pairs[pair_half_base() + p], true, split_counts[p]);
}
