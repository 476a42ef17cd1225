#version 450
#extension GL_GOOGLE_include_directive : require
// After the scan of the per-body counts: abandon the step when the pairs do not fit (the
// host grows the buffer and runs the step again), else size the per-pair dispatches.
#include "world.glsl"

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    uint total = counters.state.z;
    if (total > params.capacity.x) {
        counters.state.w = total;
        counters.state.x |= TB_ABORT_PAIRS;
        return;
    }
    counters.pair_dispatch = dispatch_covering(total, TB_WORKGROUP_SIZE);
    counters.wide_pair_dispatch = dispatch_covering(total, TB_WIDE_WORKGROUP_SIZE);
}
