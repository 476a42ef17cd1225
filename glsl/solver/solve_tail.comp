#version 450
#extension GL_GOOGLE_include_directive : require
// The constraints the colouring left over when all TB_MAX_COLOURS rounds ran (a body
// touching more than 64 others), solved by one thread in pair order after each iteration's
// colours: serial, so still Gauss-Seidel and deterministic. push.args.y = substep,
// push.args.z = the sweep (TB_SOLVE_*).
// Dispatched FIXED with 1 workgroup; returns at once when nothing was left (the usual case).
#include "contact.glsl"

void main()
{
    if (step_aborted() || counters.solver.y == 0u || gl_LocalInvocationID.x != 0u) return;
    uint base = pair_half_base(), count = counters.state.z;
    for (uint p = 0u; p < count; p++)
        if (pairs[base + p].z == TB_NO_COLOUR && manifolds[p].info.x > 0u)
            contact_sweep(p, push.args.z, push.args.y);
}
