#version 450
#extension GL_GOOGLE_include_directive : require
// The midphase split (split.glsl), third pass: each finder's run of this half moved to
// where its records' pairs now start, and as long as they are; the per-pair dispatches
// sized for the split pairs. One thread a body slot.
#include "world.glsl"
#include "split.glsl"

// Where record r's pairs start (the end of the last record's: the total).
uint split_offset(uint r)
{
    return r < counters.grid.w ? split_counts[r] : counters.state.z;
}

void main()
{
    if (step_aborted()) return;
    uint i = body_thread_index();
    if (i == 0u) {
        counters.pair_dispatch = dispatch_covering(counters.state.z, TB_WORKGROUP_SIZE);
        counters.wide_pair_dispatch = dispatch_covering(counters.state.z, TB_WIDE_WORKGROUP_SIZE);
    }
    if (i >= counters.grid.z) return;
    bool even = current_half() == 0u;
    uvec2 run = even ? body_pairs[i].xy : body_pairs[i].zw;
    uint start = split_offset(run.x);
    run = uvec2(start, split_offset(run.x + run.y) - start);
    if (even) body_pairs[i].xy = run;
    else body_pairs[i].zw = run;
}
