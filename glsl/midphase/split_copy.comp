#version 450
#extension GL_GOOGLE_include_directive : require
// The midphase split (split.glsl), last pass: the split pairs copied into this step's half
// of the pair array, where the narrowphase reads them. One thread a pair, dispatched over
// counters.pair_dispatch (now the split pairs').
#include "world.glsl"
#include "split.glsl"

void main()
{
    if (step_aborted()) return;
    uint p = pair_thread_index();
    if (p < counters.state.z) pairs[pair_half_base() + p] = split_pairs[p];
}
