#version 450
#extension GL_GOOGLE_include_directive : require
// After the count of the bodies of each colour, one workgroup: colour[c].y = first index of
// colour c in block_list, colour[c].w = 0 (the fill's cursor), colour_dispatch[c] covering
// colour[c].x bodies, BLOCK_LANES_OF(push.args.x) threads each (push.args.x: the lanes of
// the sweep the host recorded), in workgroups of TB_SOLVER_WORKGROUP_SIZE; solver.x = the
// colours in use (the highest + 1). A body coloured beyond the colours the
// host recorded sweeps for (params.capacity.z) abandons the step (TB_ABORT_COLOURS), and
// so does one left uncoloured by the recorded colouring rounds while the host recorded
// fewer than TB_MAX_COLOURS (TB_ABORT_ROUNDS): the host records more and runs it again.
// With all TB_MAX_COLOURS recorded, the bodies left uncoloured go to the tail (list.comp),
// solved one at a time after the colours.
#include "block.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void main()
{
    bool aborted = step_aborted();
    barrier();
    if (aborted) return;
    uint lanes = BLOCK_LANES_OF(push.args.x);
    for (uint c = gl_LocalInvocationID.x; c < TB_MAX_COLOURS; c += gl_WorkGroupSize.x) {
        uint first = 0u;
        for (uint k = 0u; k < c; k++) first += counters.colour[k].x;
        counters.colour[c].y = first;
        counters.colour[c].w = 0u;
        counters.colour_dispatch[c] = dispatch_covering(counters.colour[c].x * lanes,
                                                        TB_SOLVER_WORKGROUP_SIZE);
    }
    if (gl_LocalInvocationID.x != 0u) return;
    uint used = 0u;
    for (uint c = 0u; c < TB_MAX_COLOURS; c++)
        if (counters.colour[c].x > 0u) used = c + 1u;
    counters.solver.x = used;
    bool short_of_colours = params.capacity.z < uint(TB_MAX_COLOURS);
    if (used > params.capacity.z) atomicOr(counters.state.x, TB_ABORT_COLOURS);
    if (short_of_colours && counters.solver.y > 0u) atomicOr(counters.state.x, TB_ABORT_ROUNDS);
}
