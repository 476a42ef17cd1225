// Sphere against hull (the sphere first in the canonical order): one point, between the
// sphere's surface and the hull's point closest to its centre (feature key 0, as for every
// sphere contact).
//
// The closest point, in the hull's frame, for a centre c:
// - inside (no face plane has c above it): the face plane c is least deep below is where it
//   leaves, as for a sphere in a box (the axis of least penetration);
// - outside: on a face whose plane c lies above, if c's projection onto that plane falls
//   inside the face (convexity: then no other point is closer); else on an edge (vertices
//   are edge ends), the nearest of the edges' closest points.
#ifndef TB_NP_HULL_SPHERE_GLSL
#define TB_NP_HULL_SPHERE_GLSL

// Whether x, on the plane of face f (normal n), lies inside the face polygon.
bool np_hull_face_contains(np_hull h, uint f, vec3 n, vec3 x)
{
    uvec2 face = np_hull_face(h, f);
    vec3 r0 = np_hull_face_vertex(h, face, face.y - 1u);
    for (uint k = 0u; k < face.y; k++) {
        vec3 r1 = np_hull_face_vertex(h, face, k);
        if (dot(cross(r1 - r0, n), x - r0) > 0.0) return false;
        r0 = r1;
    }
    return true;
}

// The hull's point closest to c, which lies outside it.
vec3 np_hull_closest_outside(np_hull h, vec3 c)
{
    for (uint f = 0u; f < h.faces; f++) {
        vec4 plane = np_hull_plane(h, f);
        float d = dot(plane.xyz, c) - plane.w;
        vec3 x = c - plane.xyz * d;
        if (d > 0.0 && np_hull_face_contains(h, f, plane.xyz, x)) return x;
    }
    vec3 closest = c;
    float best = NP_BIG;
    for (uint e = 0u; e < h.edges; e++) {
        uvec2 v = np_hull_edge_vertices(h, e);
        vec3 v0 = np_hull_vertex(h, v.x), d = np_hull_vertex(h, v.y) - v0;
        vec3 x = v0 + d * clamp(dot(c - v0, d) / dot(d, d), 0.0, 1.0);
        float dist2 = dot(c - x, c - x);
        if (dist2 < best) {
            best = dist2;
            closest = x;
        }
    }
    return closest;
}

uint np_sphere_hull(np_target t, np_body s, np_body hull, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    np_hull h = np_hull_of(hull);
    vec3 c = transpose(hull.rot) * (s.pos - hull.pos);
    float highest = -NP_BIG;
    uint face = 0u;
    for (uint f = 0u; f < h.faces; f++) {
        vec4 plane = np_hull_plane(h, f);
        float d = dot(plane.xyz, c) - plane.w;
        if (d > highest) {
            highest = d;
            face = f;
        }
    }
    // A face plane the centre lies beyond the radius and margin above separates them.
    if (highest >= s.params.x + margin) return 0u;
    vec3 outward = np_hull_plane(h, face).xyz;  // hull frame, from the surface to the centre
    vec3 surface = c - outward * highest;
    if (highest > 0.0) {
        vec3 closest = np_hull_closest_outside(h, c), gap = c - closest;
        // A centre on the surface within rounding keeps the face's normal.
        if (dot(gap, gap) > 1.0e-12 * (dot(c, c) + 1.0)) {
            outward = normalize(gap);
            surface = closest;
        }
    }
    normal = -(hull.rot * outward);
    return np_sphere_point(t, s, normal, hull.pos + hull.rot * surface, margin);
}

#endif
