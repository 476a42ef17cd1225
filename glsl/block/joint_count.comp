#version 450
#extension GL_GOOGLE_include_directive : require
// Per joint slot, beside block/count (before the scan of the list lengths): a joint that
// holds (joint_holds) counts one list entry on each of its dynamic bodies.
#include "joint.glsl"

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= params.joint_info.x || step_aborted() || !joint_holds(j)) return;
    uvec4 info = joints[j].info;
    if (block_dynamic(info.x)) atomicAdd(block_start[info.x], 1u);
    if (block_dynamic(info.y)) atomicAdd(block_start[info.y], 1u);
}
