#version 450
/* Instanced body meshes, one instance per body slot: a unit mesh (sphere, box, capsule,
 * cylinder or cone; render_mesh.c) sized by the shape, or one hull or compound shape's own
 * mesh (pc.mode.w its shape slot); other shapes and dead slots hidden. A triangle-mesh
 * shape's mesh is drawn once per body of that shape only: its instances are the body slots
 * mesh_lists.comp listed (pc.mode.w where they start). With TR_FLAG_SEE_THROUGH, static
 * bodies are split between this draw and a see-through one (TR_FLAG_STATIC_PASS, static
 * bodies only) in mesh.frag. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_position;   /* unit mesh (radius, half extents or half
                                               height 1), or a hull's or mesh's vertices in
                                               its body frame */
layout(location = 1) in vec3 in_normal;

layout(set = 0, binding = TR_BIND_MESH_INSTANCES, std430) readonly buffer MeshInstances { uint mesh_instances[]; };

layout(location = 0) out vec3 out_normal;
layout(location = 1) flat out vec3 out_color;
layout(location = 2) out vec3 out_world;
layout(location = 3) flat out uint out_static;

/* How the unit mesh of a shape of `type` stretches along each axis: spheres by the radius,
 * boxes by the half extents, cylinders and cones by the radius across and the half height
 * along y; shapes with meshes of their own (hulls, compounds, meshes) not at all. */
vec3 unit_scale(uint type, vec4 params)
{
    if (type == TB_GPU_SHAPE_SPHERE) return vec3(params.x);
    if (type == TB_GPU_SHAPE_BOX) return params.xyz;
    if (type == TB_GPU_SHAPE_CYLINDER || type == TB_GPU_SHAPE_CONE) return params.xyx;
    return vec3(1.0);
}

/* The vertex and its normal sized by the shape, in the body frame (tr_sized_vertex on the
 * host does the same). A capsule's unit vertex is its normal plus (0, +-1, 0): the normal
 * goes by the radius and the rest by the half height, so the caps stay round. Otherwise
 * the normal goes by the inverse scale, so a cone's side stays square to its surface. */
void sized(uint type, vec4 params, out vec3 position, out vec3 normal)
{
    if (type == TB_GPU_SHAPE_CAPSULE) {
        position = params.x * in_normal + params.y * (in_position - in_normal);
        normal = in_normal;
        return;
    }
    vec3 scale = unit_scale(type, params);
    position = in_position * scale;
    normal = in_normal / scale;
}

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
    vec3 position, normal;
    sized(type, shape.params, position, normal);
    vec4 q = body_rot[slot];
    vec3 world = body_pos[slot].xyz + quat_rotate(q, position);
    out_normal = quat_rotate(q, normal);   /* not unit length: mesh.frag normalizes */
    out_color = body_color(slot, type);
    out_world = world;
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
