#version 450
/* Lit body surfaces. With TR_FLAG_SEE_THROUGH, a static body's faces that look up (floors,
 * the tops of walls: from the camera above they hide nothing) stay in the opaque draw and
 * its other faces go to the see-through one (TR_FLAG_STATIC_PASS): blended at the pass's
 * opacity, those turned away from the eye left out, so a wall adds one layer over what it
 * hides. */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_normal;
layout(location = 1) flat in vec3 in_color;
layout(location = 2) in vec3 in_world;
layout(location = 3) flat in uint in_static;

layout(location = 0) out vec4 out_color;

/* Faces whose normal is at most about 45 degrees off straight up. */
const float LOOKS_UP = 0.7;

void main()
{
    vec3 n = normalize(in_normal);
    float alpha = 1.0;
    bool looks_up = n.y > LOOKS_UP;
    if ((pc.mode.z & TR_FLAG_STATIC_PASS) != 0u) {
        if (looks_up || dot(n, pc.eye.xyz - in_world) <= 0.0) discard;
        alpha = float((pc.mode.z >> TR_OPACITY_SHIFT) & 255u) / 255.0;
    } else if ((pc.mode.z & TR_FLAG_SEE_THROUGH) != 0u && in_static != 0u && !looks_up) {
        discard;
    }
    out_color = vec4(shade(in_color, n), alpha);
}
