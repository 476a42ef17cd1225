#version 450
/* Instanced sphere or box: one instance per body slot; other shapes and dead slots hidden. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_position;   /* unit mesh: radius 1 or half extents 1 */
layout(location = 1) in vec3 in_normal;

layout(location = 0) out vec3 out_normal;
layout(location = 1) flat out vec3 out_color;

void main()
{
    uint slot = uint(gl_InstanceIndex);
    out_normal = vec3(0.0);
    out_color = vec3(0.0);
    if (!body_alive(slot)) { gl_Position = HIDDEN; return; }
    tb_gpu_shape shape = shapes[body_info[slot].x];
    uint type = shape.info.x;
    if (type != pc.mode.x) { gl_Position = HIDDEN; return; }
    vec3 scale = type == TB_GPU_SHAPE_SPHERE ? vec3(shape.params.x) : shape.params.xyz;
    vec4 q = body_rot[slot];
    vec3 world = body_pos[slot].xyz + quat_rotate(q, in_position * scale);
    /* Box normals are axis-aligned and sphere scaling is uniform: rotating is enough. */
    out_normal = quat_rotate(q, in_normal);
    out_color = body_color(slot, type);
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
