// The separating axis test between two convex hulls A and B (the pair's first and second
// shapes): face normals of A, face normals of B, and edge pairs, following Dirk Gregorius,
// "The Separating Axis Test between Convex Polyhedra" (GDC 2013).
//
// - A face axis of A measures how far B's deepest vertex lies above the face's plane.
// - Edge pairs are pruned on the Gauss map: an edge of A and an edge of B give a candidate
//   axis only when they build a face of the Minkowski difference A - B, i.e. when the arc
//   of A's edge (between its two face normals) crosses the arc of B's edge negated. Then A
//   is supported along the axis by its edge and B against it by its edge, so the
//   separation is one dot product: dot(n, pB - pA), n = cross(eA, eB) turned away from A's
//   centre. No vertex is projected per edge pair: each test is a few dot products.
//
// Every search stops at the first axis that separates by the contact margin or more (the
// pair then has no contact); that axis is cached in the manifold (tb_gpu_manifold.axis) and
// tried first in the next step, which for resting, separated neighbours is all the work.
//
// Axis codes (tb_gpu_manifold.axis.x; 0 is none): bits 30-31 the kind, NP_AXIS_FACE_A
// (bits 0-14 A's face), NP_AXIS_FACE_B (B's face) or NP_AXIS_EDGES (bits 15-29 A's edge,
// bits 0-14 B's edge). axis.y holds the separation along it (float bits) for a pair apart,
// and for a touching pair how far the two moved since the axis was chosen (hull_hull.glsl).
#ifndef TB_NP_HULL_SAT_GLSL
#define TB_NP_HULL_SAT_GLSL

#define NP_AXIS_FACE_A 1u
#define NP_AXIS_FACE_B 2u
#define NP_AXIS_EDGES 3u

uint np_axis_code(uint kind, uint i, uint j)
{
    return (kind << 30u) | (i << 15u) | j;
}

void np_set_axis(np_target t, uint code, float separation)
{
    manifolds[t.slot].axis.xyz = uvec3(code, floatBitsToUint(separation), 0u);
}

// ---- face axes -----------------------------------------------------------------------------

// How far hull o's deepest vertex lies above the plane of face f of hull r (negative: o
// reaches below it); o_in_r maps o's body frame into r's.
float np_face_separation(np_hull r, uint f, np_hull o, np_frame o_in_r)
{
    vec4 plane = np_hull_plane(r, f);
    // The plane's normal in o's frame: one dot product per vertex of o.
    vec3 dir = transpose(o_in_r.rot) * plane.xyz;
    float lowest = NP_BIG;
    for (uint i = 0u; i < o.vertices; i++) lowest = min(lowest, dot(dir, np_hull_vertex(o, i)));
    return lowest + dot(plane.xyz, o_in_r.pos) - plane.w;
}

// The face of r that o lies highest above, and how high; stops at the first face o lies
// beyond the margin above.
float np_best_face(np_hull r, np_hull o, np_frame o_in_r, float margin, out uint face)
{
    float best = -NP_BIG;
    face = 0u;
    for (uint f = 0u; f < r.faces; f++) {
        float s = np_face_separation(r, f, o, o_in_r);
        if (s > best) {
            best = s;
            face = f;
            if (s >= margin) break;
        }
    }
    return best;
}

// ---- edge axes -----------------------------------------------------------------------------

// An edge of A seen in B's frame: its face normals u (left) and v (right), its direction
// e = cross(u, v) and a point on it.
struct np_edge {
    vec3 u, v, e, p;
};

np_edge np_load_edge_a(np_hull a, uint i, np_frame a_in_b)
{
    uvec2 faces = np_hull_edge_faces(a, i);
    np_edge edge;
    edge.u = a_in_b.rot * np_hull_plane(a, faces.x).xyz;
    edge.v = a_in_b.rot * np_hull_plane(a, faces.y).xyz;
    edge.e = cross(edge.u, edge.v);
    edge.p = np_apply(a_in_b, np_hull_vertex(a, np_hull_edge_vertices(a, i).x));
    return edge;
}

// Do the arcs u-v (A's edge) and (-p)-(-q) (B's edge negated) cross on the unit sphere?
// ea is parallel to cross(u, v), eb to cross(p, q), both with positive factors: the great
// circles' normals. The arcs cross when each arc's ends lie on opposite sides of the other's
// circle, and on the same hemisphere (the last test rules out the crossing of the circles
// opposite to both arcs).
bool np_minkowski_face(vec3 u, vec3 v, vec3 ea, vec3 p, vec3 q, vec3 eb)
{
    float pa = dot(p, ea), qa = dot(q, ea), ub = dot(u, eb), vb = dot(v, eb);
    return pa * qa < 0.0 && ub * vb < 0.0 && pa * vb < 0.0;
}

// Edge j of B against A's edge (both in B's frame), A's centre at ca: xyz the unit axis
// pointing away from A, w the separation along it; w = -NP_BIG when the pair builds no
// face of the Minkowski difference or the edges are near parallel (the face axes cover
// parallel edges, and the cross product's direction is noise there).
vec4 np_edge_axis(np_edge a, np_hull b, uint j, vec3 ca)
{
    uvec2 faces = np_hull_edge_faces(b, j);
    vec3 p = np_hull_plane(b, faces.x).xyz, q = np_hull_plane(b, faces.y).xyz;
    vec3 eb = cross(p, q);
    if (!np_minkowski_face(a.u, a.v, a.e, p, q, eb)) return vec4(0.0, 0.0, 0.0, -NP_BIG);
    vec3 n = cross(a.e, eb);
    float n2 = dot(n, n);
    if (n2 < NP_EDGE_PARALLEL * dot(a.e, a.e) * dot(eb, eb)) return vec4(0.0, 0.0, 0.0, -NP_BIG);
    n *= inversesqrt(n2);
    if (dot(n, a.p - ca) < 0.0) n = -n;
    vec3 pb = np_hull_vertex(b, np_hull_edge_vertices(b, j).x);
    return vec4(n, dot(n, pb - a.p));
}

// The edges of B whose arcs an edge of A crosses on the Gauss maps are found by a walk, not
// by trying every edge of B. Negating both arcs keeps crossings, so they are B's edges whose
// arcs the arc from -u to -v (A's face normals negated) crosses on B's own Gauss map, where
// a vertex w of B owns the directions along which it is B's farthest vertex. The walk starts
// at B's farthest vertex along -u and follows d(t) = -((1 - t) u + t v), t from 0 to 1: it
// leaves vertex w for the neighbour w' (over edge w-w') that overtakes w first, where
// dot(d(t), w' - w) turns positive, at t = a / (a - c) with a = dot(u, w' - w) and
// c = dot(v, w' - w) (w' overtakes only if c < 0). Each edge it crosses is tested as before
// (np_edge_axis, which still applies the exact arc test), so a touching pair tests a handful
// of B's edges per edge of A instead of all of them. `start` is where the climb to the first
// vertex begins; the walk's last vertex comes back in it (the next edge of A usually starts
// near there).
float np_walk_edges(np_edge edge, uint i, np_hull b, vec3 ca, vec3 u, vec3 v, float margin,
                    inout uint start, inout float best, inout uint best_a, inout uint best_b)
{
    uint w = np_hull_support(b, -u, start);
    float t = 0.0;
    for (uint steps = 0u; steps < b.edges; steps++) {
        vec3 pw = np_hull_vertex(b, w);
        uvec2 ring = np_hull_ring(b, w);
        float first = 2.0;
        uvec2 exit = uvec2(w, 0u);
        for (uint k = 0u; k < ring.y; k++) {
            uvec2 entry = np_hull_ring_entry(b, ring.x + k);
            vec3 step = np_hull_vertex(b, entry.x) - pw;
            float a = dot(u, step), c = dot(v, step);
            if (c >= 0.0) continue;
            float at = max(a, 0.0) / (max(a, 0.0) - c);
            if (at >= t && at < first) {
                first = at;
                exit = entry;
            }
        }
        if (exit.x == w) break;
        float s = np_edge_axis(edge, b, exit.y, ca).w;
        if (s > best) {
            best = s;
            best_a = i;
            best_b = exit.y;
            if (s >= margin) break;
        }
        w = exit.x;
        t = first;
    }
    start = w;
    return best;
}

// The edge pair separating A and B most; stops at the first beyond the margin.
float np_best_edges(np_hull a, np_hull b, np_frame a_in_b, float margin, out uint best_a,
                    out uint best_b)
{
    float best = -NP_BIG;
    best_a = 0u;
    best_b = 0u;
    uint start = 0u;
    for (uint i = 0u; i < a.edges; i++) {
        np_edge edge = np_load_edge_a(a, i, a_in_b);
        np_walk_edges(edge, i, b, a_in_b.pos, edge.u, edge.v, margin, start, best, best_a,
                      best_b);
        if (best >= margin) return best;
    }
    return best;
}

// ---- last step's axis ----------------------------------------------------------------------

// The separation along a cached axis, or -NP_BIG when it names no axis of these hulls (a
// body slot reused by another shape) or its edge pair no longer builds a Minkowski face
// (then dot(n, pB - pA) would not be the separation). Each value is exact: a cached axis
// that separates proves there is no contact, so the cache never hides one.
float np_axis_separation(uint code, np_hull a, np_hull b, np_frame b_in_a, np_frame a_in_b)
{
    uint kind = code >> 30u, i = (code >> 15u) & 0x7fffu, j = code & 0x7fffu;
    if (kind == NP_AXIS_FACE_A && j < a.faces) return np_face_separation(a, j, b, b_in_a);
    if (kind == NP_AXIS_FACE_B && j < b.faces) return np_face_separation(b, j, a, a_in_b);
    if (kind == NP_AXIS_EDGES && i < a.edges && j < b.edges)
        return np_edge_axis(np_load_edge_a(a, i, a_in_b), b, j, a_in_b.pos).w;
    return -NP_BIG;
}

#endif
