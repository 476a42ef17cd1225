// Convex hulls as the narrowphase reads them, rigid frames between two bodies, and the
// contact reduction every hull routine shares.
//
// A hull (boxes carry one too) lives in the world's hull buffers (layout.h,
// TB_BIND_HULL_VECTORS and TB_BIND_HULL_TOPOLOGY), located by tb_gpu_shape.hull, in its body
// frame. Faces are convex polygons, counter-clockwise seen from outside, with outward unit
// normals; an edge v0 -> v1 runs counter-clockwise on its left face and clockwise on its
// right face, so the edge direction is cross(left normal, right normal) scaled by a positive
// factor (src/geom/hull.h has the same conventions).
#ifndef TB_NP_HULL_GLSL
#define TB_NP_HULL_GLSL

struct np_hull {
    uvec4 base;     // x first vertex, y first face plane (hull_vectors); z first edge word,
                    // w face base (hull_topology)
    uint vertices;
    uint faces;
    uint edges;
};

np_hull np_hull_of(np_body b)
{
    np_hull h;
    h.base = shapes[b.shape].hull;
    uvec4 info = shapes[b.shape].info;
    h.vertices = info.y;
    h.faces = info.z;
    h.edges = info.w;
    return h;
}

vec3 np_hull_vertex(np_hull h, uint i)
{
    return hull_vectors[h.base.x + i].xyz;
}

// xyz outward unit normal, w offset: dot(n, x) = w on the face, less inside.
vec4 np_hull_plane(np_hull h, uint f)
{
    return hull_vectors[h.base.y + f];
}

uvec2 np_unpack16(uint word)
{
    return uvec2(word & 0xffffu, word >> 16u);
}

uvec2 np_hull_edge_vertices(np_hull h, uint e)
{
    return np_unpack16(hull_topology[h.base.z + 2u * e]);
}

// x the left face, y the right face.
uvec2 np_hull_edge_faces(np_hull h, uint e)
{
    return np_unpack16(hull_topology[h.base.z + 2u * e + 1u]);
}

// The ring of vertex i: x its first entry, y how many (one per edge at the vertex).
uvec2 np_hull_ring(np_hull h, uint i)
{
    return np_unpack16(hull_topology[h.base.z + 2u * h.edges + i]);
}

// Entry k of the rings: x the neighbouring vertex, y the edge to it.
uvec2 np_hull_ring_entry(np_hull h, uint k)
{
    return np_unpack16(hull_topology[h.base.z + 2u * h.edges + h.vertices + k]);
}

// Hulls of up to this many vertices find a support by looking at every vertex: their
// loads are independent and go out together, where a climb waits on each step's ring, its
// entries and their vertices in turn (on an H100 the look took GJK's supports in the shapes
// pile from 1.45 to 1.34 ms and the separating axis tests of 100k hulls from 3.71 to 3.23).
#define NP_HULL_SCAN_VERTICES 64u

// The vertex of h farthest along d: the first of the farthest among all vertices (hulls of
// up to NP_HULL_SCAN_VERTICES), else climbing from vertex `start` to a neighbour farther
// along d while there is one (on a convex hull the climb ends at the farthest vertex).
uint np_hull_support(np_hull h, vec3 d, uint start)
{
    if (h.vertices <= NP_HULL_SCAN_VERTICES) {
        uint v = 0u;
        float best = dot(d, np_hull_vertex(h, 0u));
        for (uint i = 1u; i < h.vertices; i++) {
            float s = dot(d, np_hull_vertex(h, i));
            if (s > best) {
                best = s;
                v = i;
            }
        }
        return v;
    }
    uint v = start;
    float best = dot(d, np_hull_vertex(h, v));
    for (uint steps = 0u; steps < h.vertices; steps++) {
        uvec2 ring = np_hull_ring(h, v);
        uint next = v;
        for (uint k = 0u; k < ring.y; k++) {
            uint w = np_hull_ring_entry(h, ring.x + k).x;
            float s = dot(d, np_hull_vertex(h, w));
            if (s > best) {
                best = s;
                next = w;
            }
        }
        if (next == v) break;
        v = next;
    }
    return v;
}

// x where the face's vertex indices start (from the face base), y how many; the count is
// bounded so a private polygon of the clipper can hold it.
uvec2 np_hull_face(np_hull h, uint f)
{
    uvec2 face = np_unpack16(hull_topology[h.base.w + f]);
    return uvec2(face.x, min(face.y, uint(TB_HULL_MAX_FACE_VERTICES)));
}

// Vertex k (counter-clockwise from outside) of a face np_hull_face returned.
vec3 np_hull_face_vertex(np_hull h, uvec2 face, uint k)
{
    return np_hull_vertex(h, hull_topology[h.base.w + face.x + k]);
}

// ---- rigid frames --------------------------------------------------------------------------

// Maps the body frame of one body into that of another: x -> rot * x + pos.
struct np_frame {
    mat3 rot;
    vec3 pos;
};

// The frame taking `from`'s body coordinates to `to`'s.
np_frame np_frame_between(np_body to, np_body from)
{
    mat3 back = transpose(to.rot);
    np_frame f;
    f.rot = back * from.rot;
    f.pos = back * (from.pos - to.pos);
    return f;
}

vec3 np_apply(np_frame f, vec3 x)
{
    return f.rot * x + f.pos;
}

// ---- contact reduction ---------------------------------------------------------------------

// More than four candidate points are reduced as in Bullet 3's GPU pipeline (Coumans,
// "GPU rigid body simulation", GDC 2013): keep the deepest point (so the solver removes the
// penetration), then the point farthest from it in the contact plane, then the two points
// farthest either side of the line through those two (the extremes along two orthogonal
// directions in the plane: the largest quadrilateral the four can span).
//
// Callers run pick 0 to 3 over their candidates in a fixed order, skipping those already
// picked, and keep the first candidate of the highest score: the choice is deterministic.
// q is a candidate, h its height above the contact plane (negative: penetrating), p0 and p1
// the first two picks and n the plane's normal, all in one frame.
float np_reduce_score(uint pick, vec3 q, float h, vec3 p0, vec3 p1, vec3 n)
{
    if (pick == 0u) return -h;
    vec3 d = q - p0;
    if (pick == 1u) {
        d -= n * dot(d, n);  // distance within the contact plane
        return dot(d, d);
    }
    // Signed area of (p0, p1, q) seen along n; the heights do not change it.
    float side = dot(cross(p1 - p0, d), n);
    return pick == 2u ? side : -side;
}

#endif
