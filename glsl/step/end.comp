#version 450
#extension GL_GOOGLE_include_directive : require
// Last stage of a step: count it as done. The parity of this count picks which half of
// the pair and manifold arrays the next step writes, so this step's become "previous".
#include "world.glsl"

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    counters.state.y += 1u;
}
