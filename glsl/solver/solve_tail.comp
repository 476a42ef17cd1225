#version 450
#extension GL_GOOGLE_include_directive : require
// The constraints the colouring left over when all TB_MAX_COLOURS rounds ran (a body
// touching more than 64 others), solved by one thread in pair order after each iteration's
// colours: serial, so still Gauss-Seidel and deterministic. push.args.y = substep,
// push.args.z = the sweep (TB_SOLVE_*). They are listed once per step (tail_list and a
// compaction: colour_work[0 .. counters.colouring.z)): reading every pair of the step in
// every sweep instead cost 310 ms a step for 100k bodies of mixed sizes on an H100.
// Dispatched FIXED with 1 workgroup; returns at once when nothing was left (the usual case).
#include "contact.glsl"

void main()
{
    if (step_aborted() || counters.solver.y == 0u || gl_LocalInvocationID.x != 0u) return;
    uint count = counters.colouring.z;
    for (uint k = 0u; k < count; k++) contact_sweep(colour_work[k], push.args.z, push.args.y);
}
