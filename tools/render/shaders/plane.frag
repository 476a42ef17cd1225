#version 450
/* Lit plane with an anti-aliased grid (1 m lines, stronger 10 m lines), fading into the
 * background with distance through alpha (planes are drawn first, over the clear colour). */
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec2 in_uv;
layout(location = 2) flat in vec3 in_normal;
layout(location = 3) flat in vec3 in_color;

layout(location = 0) out vec4 out_color;

/* Coverage of lines at integer uv, about `width` pixels wide; 0 where cells shrink below a
 * few pixels (they would only shimmer). */
float grid_lines(vec2 uv, float width)
{
    vec2 w = max(fwidth(uv), vec2(1e-6));
    vec2 d = abs(fract(uv - 0.5) - 0.5) / w;
    float line = 1.0 - clamp(min(d.x, d.y) - 0.5 * width + 0.5, 0.0, 1.0);
    return line * (1.0 - smoothstep(0.1, 0.3, max(w.x, w.y)));
}

void main()
{
    vec3 to_eye = pc.eye.xyz - in_world;
    vec3 n = dot(in_normal, to_eye) < 0.0 ? -in_normal : in_normal;   /* two-sided */
    vec3 color = shade(in_color, n);
    if ((pc.mode.z & TR_FLAG_GRID) != 0u) {
        color = mix(color, color * 0.70, grid_lines(in_uv, 1.0));
        color = mix(color, color * 0.45, grid_lines(in_uv * 0.1, 1.5));
    }
    float far = pc.eye.w;
    float fade = smoothstep(0.25 * far, 0.9 * far, length(to_eye));
    out_color = vec4(color, 1.0 - fade);
}
