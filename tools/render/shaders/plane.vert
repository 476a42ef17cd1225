#version 450
/* One large quad per plane body (instanced over body slots, non-planes hidden), in the
 * plane, centred where the camera target projects onto it; 6 vertices, no vertex buffer.
 * With TR_FLAG_DEFAULT_PLANE: a single horizontal quad under the scene instead. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec2 out_uv;          /* metres along the plane's two tangents */
layout(location = 2) flat out vec3 out_normal;
layout(location = 3) flat out vec3 out_color;

const vec2 CORNERS[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1),
                                vec2(-1, -1), vec2(1, 1), vec2(-1, 1));

void main()
{
    uint slot = uint(gl_InstanceIndex);
    vec3 n = vec3(0.0, 1.0, 0.0);
    vec3 origin = vec3(0.0, pc.light.w, 0.0); /* the default grid, under the scene */
    out_color = vec3(0.72, 0.72, 0.70);
    if ((pc.mode.z & TR_FLAG_DEFAULT_PLANE) == 0u) {
        out_world = vec3(0.0); out_uv = vec2(0.0); out_normal = n;
        if (!body_alive(slot)) { gl_Position = HIDDEN; return; }
        tb_gpu_shape shape = shapes[body_info[slot].x];
        if (shape.info.x != TB_GPU_SHAPE_PLANE) { gl_Position = HIDDEN; return; }
        vec4 q = body_rot[slot];
        n = normalize(quat_rotate(q, shape.params.xyz));
        origin = body_pos[slot].xyz + quat_rotate(q, shape.params.xyz * shape.params.w);
        out_color = body_color(slot, TB_GPU_SHAPE_PLANE);
    }
    /* Tangents from a fixed helper axis, so a y-up plane's grid follows x and z. */
    vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 t1 = normalize(cross(helper, n));
    vec3 t2 = cross(n, t1);
    vec3 centre = pc.target.xyz - dot(pc.target.xyz - origin, n) * n;
    vec2 c = CORNERS[gl_VertexIndex] * (2.0 * pc.eye.w);
    vec3 world = centre + c.x * t1 + c.y * t2;
    out_world = world;
    out_uv = vec2(dot(world - origin, t1), dot(world - origin, t2));
    out_normal = n;
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
