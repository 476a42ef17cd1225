/* Shared by the renderer's shaders: the world's body arrays (set 0, the world's own
 * binding numbers from layout.h), the push constants, and body colours.
 * Included, never compiled alone (the Makefile compiles *.vert, *.frag and *.comp only). */
#include "layout.h"
#include "render_layout.h"

layout(set = 0, binding = TB_BIND_BODY_POS, std430) readonly buffer BodyPos { vec4 body_pos[]; };
layout(set = 0, binding = TB_BIND_BODY_ROT, std430) readonly buffer BodyRot { vec4 body_rot[]; };
layout(set = 0, binding = TB_BIND_BODY_LINVEL, std430) readonly buffer BodyLinvel { vec4 body_linvel[]; };
layout(set = 0, binding = TB_BIND_BODY_INFO, std430) readonly buffer BodyInfo { uvec4 body_info[]; };
layout(set = 0, binding = TB_BIND_BODY_AABB_MIN, std430) readonly buffer BodyAabbMin { vec4 body_aabb_min[]; };
layout(set = 0, binding = TB_BIND_BODY_AABB_MAX, std430) readonly buffer BodyAabbMax { vec4 body_aabb_max[]; };
layout(set = 0, binding = TB_BIND_SHAPES, std430) readonly buffer Shapes { tb_gpu_shape shapes[]; };

layout(push_constant) uniform Push { tr_push pc; };

/* Share of the light that reaches every surface. */
const float AMBIENT = 0.35;

/* Hidden instances get a point outside the clip volume: their triangles are culled. */
const vec4 HIDDEN = vec4(2.0, 2.0, 2.0, 1.0);

vec3 quat_rotate(vec4 q, vec3 v)
{
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

bool body_alive(uint slot) { return (body_info[slot].y & TB_BODY_FLAG_ALIVE) != 0u; }

const vec3 PALETTE[8] = vec3[8](
    vec3(0.90, 0.45, 0.35), vec3(0.35, 0.65, 0.85), vec3(0.55, 0.78, 0.40),
    vec3(0.95, 0.75, 0.30), vec3(0.65, 0.50, 0.85), vec3(0.30, 0.75, 0.70),
    vec3(0.92, 0.55, 0.70), vec3(0.80, 0.60, 0.40));

uint hash_u32(uint x)
{
    x ^= x >> 16; x *= 0x7feb352du;
    x ^= x >> 15; x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* Colour of a body by the current mode (TR_COLOR_* in render.h); static bodies grey. */
vec3 body_color(uint slot, uint shape_type)
{
    if ((body_info[slot].y & TB_BODY_FLAG_DYNAMIC) == 0u) return vec3(0.72, 0.72, 0.70);
    if (pc.mode.y == 1u) {
        float s = clamp(length(body_linvel[slot].xyz) / max(pc.target.w, 1e-6), 0.0, 1.0);
        return mix(vec3(0.25, 0.45, 0.90), vec3(0.90, 0.25, 0.20), s);
    }
    if (pc.mode.y == 2u) {
        if (shape_type == TB_GPU_SHAPE_SPHERE) return vec3(0.92, 0.55, 0.25);
        if (shape_type == TB_GPU_SHAPE_BOX) return vec3(0.25, 0.50, 0.90);
        if (shape_type == TB_GPU_SHAPE_HULL) return vec3(0.35, 0.75, 0.30);
        if (shape_type == TB_GPU_SHAPE_COMPOUND) return vec3(0.65, 0.40, 0.80);
        if (shape_type == TB_GPU_SHAPE_CAPSULE) return vec3(0.20, 0.70, 0.70);
        if (shape_type == TB_GPU_SHAPE_CYLINDER) return vec3(0.80, 0.82, 0.20);
        if (shape_type == TB_GPU_SHAPE_CONE) return vec3(0.90, 0.30, 0.75);
        return vec3(0.72, 0.72, 0.70);
    }
    return PALETTE[hash_u32(slot) & 7u];
}

/* Lambert with one directional light plus ambient. */
vec3 shade(vec3 color, vec3 n)
{
    return color * (AMBIENT + (1.0 - AMBIENT) * max(dot(n, pc.light.xyz), 0.0));
}
