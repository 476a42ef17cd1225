#version 450
/* Contact overlay: one instance per manifold of the world's last step, read from the
 * world's manifold buffer (bound whole, or as much as one binding may hold; pc.mode.w is the
 * first manifold of the last step).
 * Each of the manifold's points gets a short line along the normal (from body a towards b)
 * and a small cross; vertices of points past the manifold's count are hidden. Depth-tested
 * against the scene, lifted towards the eye first (TR_CONTACT_LIFT_SHARE). LINE_LIST,
 * TB_MAX_MANIFOLD_POINTS * TR_CONTACT_VERTICES_PER_POINT vertices per instance. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(set = 0, binding = TR_BIND_MANIFOLDS, std430) readonly buffer Manifolds {
    tb_gpu_manifold manifolds[];
};

layout(location = 0) out vec3 out_color;

const uint NORMAL_VERTICES = 2u * TB_MAX_MANIFOLD_POINTS;

void main()
{
    uint m = pc.mode.w + uint(gl_InstanceIndex);
    uint v = uint(gl_VertexIndex);
    bool is_normal = v < NORMAL_VERTICES;
    uint k = is_normal ? v / 2u : (v - NORMAL_VERTICES) / 6u;   /* the point */
    float end = (v & 1u) != 0u ? 1.0 : 0.0;                     /* which end of the segment */
    out_color = vec3(0.0);
    if (k >= min(manifolds[m].info.x, TB_MAX_MANIFOLD_POINTS)) { gl_Position = HIDDEN; return; }
    vec3 p = manifolds[m].point[k].xyz;
    vec3 world;
    if (is_normal) {
        float len = TR_CONTACT_NORMAL_SHARE * distance(pc.eye.xyz, pc.target.xyz);
        world = p + end * len * manifolds[m].normal.xyz;
        out_color = vec3(TR_CONTACT_NORMAL_R, TR_CONTACT_NORMAL_G, TR_CONTACT_NORMAL_B) / 255.0;
    } else {
        uint axis = ((v - NORMAL_VERTICES) % 6u) / 2u;
        vec3 dir = vec3(0.0);
        dir[axis] = 1.0;
        float arm = TR_CONTACT_CROSS_SHARE * distance(pc.eye.xyz, p);
        world = p + (2.0 * end - 1.0) * arm * dir;
        out_color = vec3(TR_CONTACT_POINT_R, TR_CONTACT_POINT_G, TR_CONTACT_POINT_B) / 255.0;
    }
    /* Towards the eye along the view ray (TR_CONTACT_LIFT_SHARE): the depth test then
     * hides the overlay only behind something thicker than the lift. */
    world += TR_CONTACT_LIFT_SHARE * (pc.eye.xyz - world);
    gl_Position = pc.view_proj * vec4(world, 1.0);
}
