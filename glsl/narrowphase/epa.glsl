// Penetration of two overlapping cores (convex.glsl) by the expanding polytope algorithm
// (van den Bergen, "Proximity queries and penetration depth computation on 3D game
// objects", GDC 2001): starting from GJK's last simplex, grown to a tetrahedron about the
// origin, the polytope inside the Minkowski difference A - B is expanded towards its face
// closest to the origin by the support point along that face's normal until the support
// point lies on the face (within a float tolerance). That face's normal is the direction in
// which A moves out of B the least, its distance the depth, and the face's barycentric
// weights of the origin's projection give the witness points.
//
// The polytope lives in private arrays of fixed size; running out of room ends the
// expansion with the best face so far. The faces are kept packed (those a new vertex sees
// are dropped as it comes, their slots given to the new ones): a closed polytope of V
// vertices has 2V - 4 faces, so NP_EPA_FACES holds every face NP_EPA_VERTICES can make, and
// a curved core (a cylinder's side, a cone's) that takes all the vertices to close in on its
// depth does not run out of faces first.
#ifndef TB_NP_EPA_GLSL
#define TB_NP_EPA_GLSL

#define NP_EPA_VERTICES 32u
#define NP_EPA_FACES 64u
#define NP_EPA_EDGES 32u
#define NP_EPA_ITERATIONS 32u
#define NP_EPA_FOLDS 16u         // kept faces one fan may take back (np_epa_expand)

struct np_epa_result {
    bool found;     // a depth was found; else, when the normal is not zero, the cores touch
    vec3 normal;    // from A to B (the Minkowski difference's outward normal)
    float depth;    // of the cores
    vec3 pa, pb;    // witness points on the cores
};

vec3 np_epa_w[NP_EPA_VERTICES];
vec3 np_epa_a[NP_EPA_VERTICES];
vec3 np_epa_b[NP_EPA_VERTICES];
uvec3 np_epa_face[NP_EPA_FACES];
vec4 np_epa_plane[NP_EPA_FACES];   // xyz outward unit normal, w distance from the origin
uint np_epa_vertices;
uint np_epa_faces;

uint np_epa_add_vertex(np_convex A, np_convex B, vec3 d)
{
    uint m = np_epa_vertices++;
    np_core_supports(A, B, d, np_epa_a[m], np_epa_b[m]);
    np_epa_w[m] = np_epa_a[m] - np_epa_b[m];
    return m;
}

// Face (i, j, k), its normal outward when the vertices run counter-clockwise seen from
// outside; false for a face of no area.
bool np_epa_add_face(uint i, uint j, uint k)
{
    if (np_epa_faces >= NP_EPA_FACES) return false;
    vec3 n = cross(np_epa_w[j] - np_epa_w[i], np_epa_w[k] - np_epa_w[i]);
    float len = length(n);
    if (!(len > 0.0)) return false;
    n /= len;
    uint f = np_epa_faces++;
    np_epa_face[f] = uvec3(i, j, k);
    np_epa_plane[f] = vec4(n, dot(n, np_epa_w[i]));
    return true;
}

// GJK's simplex grown to a tetrahedron: new vertices along directions off the simplex
// (across a segment, along a triangle's normal) until one adds volume.
bool np_epa_start(np_convex A, np_convex B, np_simplex s)
{
    np_epa_vertices = 0u;
    np_epa_faces = 0u;
    for (uint m = 0u; m < s.n; m++) {
        np_epa_w[m] = s.w[m];
        np_epa_a[m] = s.a[m];
        np_epa_b[m] = s.a[m] - s.w[m];
    }
    np_epa_vertices = s.n;
    const vec3 axes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                                 vec3(0, 0, 1), vec3(0, 0, -1));
    for (uint tries = 0u; np_epa_vertices == 1u && tries < 6u; tries++) {
        np_epa_add_vertex(A, B, axes[tries]);
        vec3 e = np_epa_w[1] - np_epa_w[0];
        if (dot(e, e) <= 1.0e-12 * max(dot(np_epa_w[1], np_epa_w[1]), 1.0e-12)) np_epa_vertices = 1u;
    }
    for (uint tries = 0u; np_epa_vertices == 2u && tries < 6u; tries++) {
        vec3 e = np_epa_w[1] - np_epa_w[0];
        vec3 side = normalize(cross(e, axes[(tries / 2u) * 2u]));
        if (any(isnan(side))) continue;
        np_epa_add_vertex(A, B, (tries & 1u) == 0u ? side : -side);
        vec3 n = cross(e, np_epa_w[2] - np_epa_w[0]);
        if (dot(n, n) <= 1.0e-12 * dot(e, e) * dot(e, e)) np_epa_vertices = 2u;
    }
    for (uint tries = 0u; np_epa_vertices == 3u && tries < 2u; tries++) {
        vec3 n = cross(np_epa_w[1] - np_epa_w[0], np_epa_w[2] - np_epa_w[0]);
        np_epa_add_vertex(A, B, tries == 0u ? n : -n);
        float h = dot(n, np_epa_w[3] - np_epa_w[0]);
        if (abs(h) <= 1.0e-6 * length(n) * length(np_epa_w[3] - np_epa_w[0])) np_epa_vertices = 3u;
    }
    if (np_epa_vertices != 4u) return false;
    // Orient: w3 on the inner side of face (0, 1, 2).
    vec3 n = cross(np_epa_w[1] - np_epa_w[0], np_epa_w[2] - np_epa_w[0]);
    bool flip = dot(n, np_epa_w[3] - np_epa_w[0]) > 0.0;
    uint i1 = flip ? 2u : 1u, i2 = flip ? 1u : 2u;
    return np_epa_add_face(0u, i1, i2) && np_epa_add_face(0u, 3u, i1) &&
           np_epa_add_face(i1, 3u, i2) && np_epa_add_face(i2, 3u, 0u);
}

// The horizon as the loose edges of the faces w sees: an edge seen from both sides cancels.
uvec2 np_epa_edge[NP_EPA_EDGES];
uint np_epa_edges;

bool np_epa_add_edge(uint i, uint j)
{
    for (uint e = 0u; e < np_epa_edges; e++) {
        if (np_epa_edge[e] == uvec2(j, i)) {
            np_epa_edge[e] = np_epa_edge[--np_epa_edges];
            return true;
        }
    }
    if (np_epa_edges >= NP_EPA_EDGES) return false;
    np_epa_edge[np_epa_edges++] = uvec2(i, j);
    return true;
}

// The face (of the first `count`) across the edge from i to j: the one that runs from j to i.
uint np_epa_across(uint i, uint j, uint count)
{
    for (uint f = 0u; f < count; f++) {
        uvec3 v = np_epa_face[f];
        if (uvec2(v.x, v.y) == uvec2(j, i) || uvec2(v.y, v.z) == uvec2(j, i) ||
            uvec2(v.z, v.x) == uvec2(j, i)) return f;
    }
    return NP_NONE;
}

// Replaces the faces vertex m sees by a fan from their horizon to m. The faces it does not
// see move down over the slots of those it does. False when the room runs out or the fan
// cannot be mended (below): the polytope is then broken, and the caller answers from the
// face it had.
//
// A face is seen when m lies more than `eps` (float noise of the polytope's size) in front
// of it. A flat side of a core (a cylinder's cap, a box's face) gives many vertices in one
// plane, and a new one in that plane is in front of some of its faces and behind others by
// rounding alone: seen by every face it is in front of, m would fold faces of that plane
// over each other (one wound the wrong way round: an inward normal, a distance below zero,
// which the nearest face would then be). Faces within eps of m stay, unless the fan then
// shows a fold: a new face with the origin behind it (no face of a polytope that holds the
// origin has one) or of no area, m lying in the plane of the kept face across that horizon
// edge. That face goes too, its other two edges join the horizon, and the fan is made
// again, up to NP_EPA_FOLDS times (a cone's apex region may take several).
bool np_epa_expand(uint m, float eps)
{
    np_epa_edges = 0u;
    vec3 w = np_epa_w[m];
    uint kept = 0u;
    for (uint f = 0u; f < np_epa_faces; f++) {
        if (dot(np_epa_plane[f].xyz, w) - np_epa_plane[f].w > eps) {
            uvec3 v = np_epa_face[f];
            if (!np_epa_add_edge(v.x, v.y) || !np_epa_add_edge(v.y, v.z) ||
                !np_epa_add_edge(v.z, v.x)) return false;
            continue;
        }
        np_epa_face[kept] = np_epa_face[f];
        np_epa_plane[kept] = np_epa_plane[f];
        kept++;
    }
    for (uint folds = 0u; folds <= NP_EPA_FOLDS; folds++) {
        np_epa_faces = kept;
        uint fold = NP_NONE;
        for (uint e = 0u; e < np_epa_edges && fold == NP_NONE; e++) {
            if (np_epa_faces >= NP_EPA_FACES) return false;
            if (!np_epa_add_face(np_epa_edge[e].x, np_epa_edge[e].y, m) ||
                np_epa_plane[np_epa_faces - 1u].w < -eps) fold = e;
        }
        if (fold == NP_NONE) return true;
        uvec2 edge = np_epa_edge[fold];
        uint g = np_epa_across(edge.x, edge.y, kept);
        if (g == NP_NONE || folds == NP_EPA_FOLDS) return false;
        uvec3 v = np_epa_face[g];
        kept--;
        np_epa_face[g] = np_epa_face[kept];
        np_epa_plane[g] = np_epa_plane[kept];
        if (!np_epa_add_edge(v.x, v.y) || !np_epa_add_edge(v.y, v.z) ||
            !np_epa_add_edge(v.z, v.x)) return false;
    }
    return false;
}

uint np_epa_closest_face()
{
    uint best = NP_NONE;
    for (uint f = 0u; f < np_epa_faces; f++)
        if (best == NP_NONE || np_epa_plane[f].w < np_epa_plane[best].w) best = f;
    return best;
}

// The answer of face v (vertex indices) with the given plane.
np_epa_result np_epa_answer(uvec3 v, vec4 plane)
{
    np_epa_result r;
    vec3 n = plane.xyz;
    vec3 p = n * plane.w;
    vec3 w0 = np_epa_w[v.x], w1 = np_epa_w[v.y], w2 = np_epa_w[v.z];
    // Barycentric weights of p from the sub-triangles' areas along n.
    vec3 l = vec3(dot(cross(w1 - p, w2 - p), n), dot(cross(w2 - p, w0 - p), n),
                  dot(cross(w0 - p, w1 - p), n));
    float sum = l.x + l.y + l.z;
    l = sum != 0.0 ? l / sum : vec3(1.0 / 3.0);
    r.found = true;
    r.normal = n;
    r.depth = max(plane.w, 0.0);
    r.pa = l.x * np_epa_a[v.x] + l.y * np_epa_a[v.y] + l.z * np_epa_a[v.z];
    r.pb = l.x * np_epa_b[v.x] + l.y * np_epa_b[v.y] + l.z * np_epa_b[v.z];
    return r;
}

// EPA's normal and witness points, or for cores that only touch (no depth found) its nearest
// face's normal, or where it has none either GJK's points and their direction (its length
// is float noise, its direction too). False when none of them gives a direction.
bool np_epa_or_touch(np_gjk_result g, np_epa_result e, out vec3 n, out vec3 pa, out vec3 pb)
{
    vec3 gap = g.pb - g.pa;
    bool along_gap = !e.found && e.normal == vec3(0.0) && dot(gap, gap) > 0.0;
    n = along_gap ? normalize(gap) : e.normal;
    pa = along_gap ? g.pa : e.pa;
    pb = along_gap ? g.pb : e.pb;
    return n != vec3(0.0);
}

np_epa_result np_epa(np_convex A, np_convex B, np_simplex s)
{
    np_epa_result r;
    r.found = false;
    r.normal = vec3(0.0);
    r.depth = 0.0;
    r.pa = r.pb = vec3(0.0);
    if (!np_epa_start(A, B, s)) return r;
    float size = 0.0;
    for (uint m = 0u; m < 4u; m++) size = max(size, length(np_epa_w[m]));
    uint best = np_epa_closest_face();
    if (best == NP_NONE) return r;
    // The nearest face, kept aside: a failed expansion may overwrite its slot.
    uvec3 face = np_epa_face[best];
    vec4 plane = np_epa_plane[best];
    for (uint it = 0u; it < NP_EPA_ITERATIONS; it++) {
        if (np_epa_vertices >= NP_EPA_VERTICES) break;
        uint m = np_epa_add_vertex(A, B, plane.xyz);
        float gain = dot(plane.xyz, np_epa_w[m]) - plane.w;
        if (gain <= 1.0e-5 * size + 1.0e-4 * abs(plane.w)) break;
        if (!np_epa_expand(m, 1.0e-6 * size)) break;
        best = np_epa_closest_face();
        if (best == NP_NONE) break;
        face = np_epa_face[best];
        plane = np_epa_plane[best];
    }
    // A polytope whose nearest face does not hold the origin in front of it (cores that only
    // touch, within float noise of each other) has no depth to give: not found, but its
    // nearest face's normal is still the touching direction.
    r = np_epa_answer(face, plane);
    r.found = plane.w > 1.0e-6 * size;
    return r;
}

#endif
