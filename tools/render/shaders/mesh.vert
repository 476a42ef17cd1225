#version 450
/* Instanced body meshes, one instance per body slot: a unit sphere or box scaled by the
 * shape, or one hull or compound shape's own mesh (pc.mode.w its shape slot); other shapes and dead
 * slots hidden. A triangle-mesh shape's mesh is drawn once per body of that shape only:
 * its instances are the body slots mesh_lists.comp listed (pc.mode.w where they start). With TR_FLAG_SEE_THROUGH, static bodies are split between this draw and a
 * see-through one (TR_FLAG_STATIC_PASS, static bodies only) in mesh.frag. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_position;   /* unit mesh (radius 1 or half extents 1), or a
                                               hull's or mesh's vertices in its body frame */
layout(location = 1) in vec3 in_normal;

layout(set = 0, binding = TR_BIND_MESH_INSTANCES, std430) readonly buffer MeshInstances { uint mesh_instances[]; };

layout(location = 0) out vec3 out_normal;
layout(location = 1) flat out vec3 out_color;
layout(location = 2) out vec3 out_world;
layout(location = 3) flat out uint out_static;

void main()
{
    uint slot = pc.mode.x == TB_GPU_SHAPE_MESH ? mesh_instances[pc.mode.w + uint(gl_InstanceIndex)]
                                               : uint(gl_InstanceIndex);
    out_normal = vec3(0.0);
    out_color = vec3(0.0);
    out_world = vec3(0.0);
    out_static = 0u;
    if (!body_alive(slot)) { gl_Position = HIDDEN; return; }
    uint shape_slot = body_info[slot].x;
    tb_gpu_shape shape = shapes[shape_slot];
    uint type = shape.info.x;
    if (type != pc.mode.x) { gl_Position = HIDDEN; return; }
    bool own_mesh = type == TB_GPU_SHAPE_HULL || type == TB_GPU_SHAPE_COMPOUND;
    if (own_mesh && shape_slot != pc.mode.w) { gl_Position = HIDDEN; return; }
    bool is_static = (body_info[slot].y & TB_BODY_FLAG_DYNAMIC) == 0u;
    bool static_pass = (pc.mode.z & TR_FLAG_STATIC_PASS) != 0u;
    if (static_pass && !is_static) { gl_Position = HIDDEN; return; }
    out_static = is_static ? 1u : 0u;
    vec3 scale = type == TB_GPU_SHAPE_SPHERE ? vec3(shape.params.x)
               : type == TB_GPU_SHAPE_BOX ? shape.params.xyz : vec3(1.0);
    vec4 q = body_rot[slot];
    vec3 world = body_pos[slot].xyz + quat_rotate(q, in_position * scale);
    /* Box, hull and mesh normals are per face and sphere scaling is uniform: rotating is
     * enough. */
    out_normal = quat_rotate(q, in_normal);
    out_color = body_color(slot, type);
    out_world = world;
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
