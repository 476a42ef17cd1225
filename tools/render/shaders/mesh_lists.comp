#version 450
/* The bodies of each triangle-mesh shape, listed for that shape's indirect draw: one
 * invocation per body slot. A live body whose shape is a mesh shape (mesh_of_shape) takes
 * the next place in its shape's list and raises the draw's instance count, which the host
 * set to 0 before the frame. The order within a list varies from frame to frame; a mesh
 * body is static, so nothing shows it. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = TR_MESH_LIST_GROUP) in;

layout(set = 0, binding = TR_BIND_MESH_OF_SHAPE, std430) readonly buffer MeshOfShape { uint mesh_of_shape[]; };
layout(set = 0, binding = TR_BIND_MESH_COMMANDS, std430) buffer MeshCommands { uint mesh_commands[]; };
layout(set = 0, binding = TR_BIND_MESH_INSTANCES, std430) writeonly buffer MeshInstances { uint mesh_instances[]; };

void main()
{
    /* Rows of groups: a dispatch's width is limited. */
    uint slot = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * TR_MESH_LIST_GROUP;
    if (slot >= pc.mode.x || !body_alive(slot)) return;
    uint shape_slot = body_info[slot].x;
    if (shape_slot >= pc.mode.z) return;
    uint draw = mesh_of_shape[shape_slot];
    if (draw == TR_NO_MESH) return;
    uint k = atomicAdd(mesh_commands[draw * TR_MESH_COMMAND_UINTS + 1u], 1u);
    mesh_instances[draw * pc.mode.y + k] = slot;
}
