#version 450
#extension GL_GOOGLE_include_directive : require
// Incremental or from scratch, once per step after isap_measure: from scratch (the LBVH's
// search) when there is no usable last step, a body became large or stopped being large,
// or the endpoints moved so far that the incremental scans (each passed entry read in two
// orders) would visit more than about the LBVH's walks do (a few dozen nodes per body).
// The choice goes where the LBVH's passes look: a skip word and the count it sorts.
#include "world.glsl"
#include "isap.glsl"

const float SCRATCH_WORK_PER_BODY = 32.0;

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    IsapControl c = isap_control();
    float moved = isap_wide(c.c.moved.x, c.c.moved.y);
    bool scratch = !isap_old_valid() || c.c.sort.w != 0u ||
                   2.0 * moved > SCRATCH_WORK_PER_BODY * float(isap_slots());
    c.c.search = uvec4(scratch ? 0u : 1u, scratch ? isap_slots() : 0u, 0u, 0u);
}
