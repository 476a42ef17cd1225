// Plane against hull (the plane first in the canonical order): the hull's vertices within
// the margin of the plane, reduced to four as clipped points are (hull.glsl). A face lying
// on the plane gives its corners (four of them at most: a box face gives exactly its four);
// an edge two, a vertex one. Feature key: the vertex index.
#ifndef TB_NP_HULL_PLANE_GLSL
#define TB_NP_HULL_PLANE_GLSL

// The normal points from the plane's solid side to the hull.
uint np_plane_hull(np_target t, np_body plane, np_body hull, float margin, out vec3 normal)
{
    vec4 half_space = np_world_plane(plane);
    normal = half_space.xyz;
    np_hull h = np_hull_of(hull);
    // Heights above the plane in the hull's frame: centre + dot(n, vertex).
    vec3 n = transpose(hull.rot) * half_space.xyz;
    float centre = dot(half_space.xyz, hull.pos) - half_space.w;
    uint near = 0u;
    for (uint i = 0u; i < h.vertices; i++)
        if (centre + dot(n, np_hull_vertex(h, i)) < margin) near++;
    uvec4 kept = uvec4(NP_NONE);
    if (near > 4u) {
        vec3 p0 = vec3(0.0), p1 = vec3(0.0);
        for (uint pick = 0u; pick < 4u; pick++) {
            float best = -NP_BIG;
            for (uint i = 0u; i < h.vertices; i++) {
                vec3 v = np_hull_vertex(h, i);
                float height = centre + dot(n, v);
                if (height >= margin || any(equal(kept, uvec4(i)))) continue;
                float score = np_reduce_score(pick, v, height, p0, p1, n);
                if (score > best) {
                    best = score;
                    kept[pick] = i;
                }
            }
            if (pick == 0u) p0 = np_hull_vertex(h, kept[0]);
            if (pick == 1u) p1 = np_hull_vertex(h, kept[1]);
        }
    }
    uint count = 0u;
    for (uint i = 0u; i < h.vertices && count < uint(TB_MAX_MANIFOLD_POINTS); i++) {
        vec3 v = np_hull_vertex(h, i);
        float height = centre + dot(n, v);
        if (height >= margin || (near > 4u && !any(equal(kept, uvec4(i))))) continue;
        vec3 vertex = hull.pos + hull.rot * v;
        np_emit(t, count, vertex - half_space.xyz * (0.5 * height), height, i);
        count++;
    }
    return count;
}

#endif
