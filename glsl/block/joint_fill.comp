#version 450
#extension GL_GOOGLE_include_directive : require
// Per joint slot, beside block/fill: a joint that holds goes into the lists of its dynamic
// bodies, one entry each (block_joint_entry), with the body at its other end.
#include "joint.glsl"

void put(uint body, uint other, uint j, bool is_b)
{
    uint at = block_start[body] + atomicAdd(block_fill[body], 1u);
    block_entries[at] = uvec2(block_joint_entry(j, is_b), other);
}

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= params.joint_info.x || step_aborted() || !joint_holds(j)) return;
    uvec4 info = joints[j].info;
    if (block_dynamic(info.x)) put(info.x, info.y, j, false);
    if (block_dynamic(info.y)) put(info.y, info.x, j, true);
}
