#version 450
#extension GL_GOOGLE_include_directive : require
// After the plugin stages of the pre-step (push x = 0) or post-broadphase (x = 1) point:
// note that this step ran them. A step abandoned later (a buffer overflowed) is run again
// from its start; its plugin stages see the note and do not apply their effect twice.
#include "world.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void main()
{
    if (step_aborted() || gl_LocalInvocationID.x != 0u) return;
    if (push.args.x == 0u) counters.plugins.x = counters.state.y + 1u;
    else counters.plugins.y = counters.state.y + 1u;
}
