#version 450
/* World AABB wireframe: 24 vertices (12 edges, LINE_LIST) per body slot; dead and
 * unbounded (plane) AABBs hidden. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) out vec3 out_color;

/* Corner ends of the 12 edges; corner bit i picks max on axis i. */
const uint EDGE_CORNERS[24] = uint[24](0, 1, 2, 3, 4, 5, 6, 7,
                                       0, 2, 1, 3, 4, 6, 5, 7,
                                       0, 4, 1, 5, 2, 6, 3, 7);

void main()
{
    uint slot = uint(gl_InstanceIndex);
    out_color = vec3(0.95, 0.70, 0.10);
    vec3 lo = body_aabb_min[slot].xyz, hi = body_aabb_max[slot].xyz;
    bool unbounded = any(greaterThan(max(abs(lo), abs(hi)), vec3(1e17)));
    if (!body_alive(slot) || unbounded) { gl_Position = HIDDEN; return; }
    uint c = EDGE_CORNERS[gl_VertexIndex];
    vec3 p = vec3((c & 1u) != 0u ? hi.x : lo.x, (c & 2u) != 0u ? hi.y : lo.y,
                  (c & 4u) != 0u ? hi.z : lo.z);
    gl_Position = pc.view_proj * vec4(p, 1.0);
    /* A little towards the camera, so edges lying on box faces are not hidden by them. */
    gl_Position.z -= 2e-4 * gl_Position.w;
}
