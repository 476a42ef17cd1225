#version 450
#extension GL_GOOGLE_include_directive : require
// The midphase split (split.glsl), after the scan: abandon the step when the split pairs do
// not fit (the host grows the pair buffers and runs the step again); else the split's
// total becomes the step's pair count, and the broadphase's record count moves to
// counters.grid.w for the passes that still read the records.
#include "world.glsl"

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    uint total = counters.grid.w, records = counters.state.z;
    if (total > params.capacity.x) {
        counters.state.w = total;
        counters.state.x |= TB_ABORT_PAIRS;
        return;
    }
    counters.grid.w = records;
    counters.state.z = total;
}
