#version 450
#extension GL_GOOGLE_include_directive : require
// Last stage of a step: count it as done. The parity of this count picks which half of
// the pair and manifold arrays the next step writes, so this step's become "previous". The
// contact events it wrote are kept, and its pair count is "last step's" for the next.
#include "world.glsl"

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    counters.state.y += 1u;
    counters.events.yz = uvec2(counters.events.x, counters.state.z);   // see narrowphase/events
}
