// Sphere against sphere, plane and box. A sphere touches with one point whose feature never
// changes, so its feature key is 0. Each routine gets the pair in canonical order (the
// sphere first) and returns the normal from the first shape to the second.
#ifndef TB_NP_SPHERE_GLSL
#define TB_NP_SPHERE_GLSL

// A plane body's half-space {p : dot(xyz, p) <= w} in world space.
vec4 np_world_plane(np_body plane)
{
    vec3 n = plane.rot * plane.params.xyz;
    return vec4(n, plane.params.w + dot(n, plane.pos));
}

// Emits the point between the sphere's surface point (its centre moved by r along the
// normal) and the other surface point q; separation is measured along the normal.
uint np_sphere_point(np_target t, np_body s, vec3 normal, vec3 q, float margin)
{
    vec3 p = s.pos + normal * s.params.x;
    float separation = dot(q - p, normal);
    if (separation >= margin) return 0u;
    np_emit(t, 0u, 0.5 * (p + q), separation, 0u);
    return 1u;
}

uint np_sphere_sphere(np_target t, np_body s1, np_body s2, float margin, out vec3 normal)
{
    vec3 d = s2.pos - s1.pos;
    float len = length(d);
    // Concentric spheres have no preferred direction: any unit normal will do.
    normal = len > 1.0e-6 * (s1.params.x + s2.params.x) ? d / len : vec3(0.0, 1.0, 0.0);
    return np_sphere_point(t, s1, normal, s2.pos - normal * s2.params.x, margin);
}

uint np_sphere_plane(np_target t, np_body s, np_body plane, float margin, out vec3 normal)
{
    vec4 half_space = np_world_plane(plane);
    float height = dot(half_space.xyz, s.pos) - half_space.w;
    normal = -half_space.xyz;
    return np_sphere_point(t, s, normal, s.pos - half_space.xyz * height, margin);
}

// The closest point of the box to the centre; a centre inside the box leaves through the
// face nearest to it (the axis of least penetration).
uint np_sphere_box(np_target t, np_body s, np_body box, float margin, out vec3 normal)
{
    vec3 h = box.params.xyz;
    vec3 local = transpose(box.rot) * (s.pos - box.pos);
    vec3 surface = clamp(local, -h, h);
    vec3 gap = local - surface;
    vec3 outward;  // box frame, from the box surface towards the centre
    if (dot(gap, gap) > 1.0e-12 * dot(h, h)) {
        outward = normalize(gap);
    } else {
        vec3 depth = h - abs(local);
        uint k = depth.x <= depth.y && depth.x <= depth.z ? 0u : (depth.y <= depth.z ? 1u : 2u);
        float side = np_comp(local, k) >= 0.0 ? 1.0 : -1.0;
        outward = vec3(0.0);
        outward[k] = side;
        surface = local;
        surface[k] = side * h[k];
    }
    normal = -(box.rot * outward);
    return np_sphere_point(t, s, normal, box.pos + box.rot * surface, margin);
}

#endif
