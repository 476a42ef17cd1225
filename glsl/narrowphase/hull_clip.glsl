// Contact points of two hulls once the separating axis test has chosen an axis.
//
// Face axis (Sutherland-Hodgman clipping, as in Bullet 3's GPU pipeline, Coumans GDC 2013):
// the reference face is the face of the axis; the incident face is the other hull's face
// most anti-parallel to the reference normal among those around its deepest vertex. The
// incident polygon is clipped by the side planes of the reference face (one per reference
// edge, not by the reference plane itself); the corners below the reference plane plus the
// margin are the candidates, more than four are reduced (hull.glsl), and each is written midway between the surfaces.
// Everything happens in the reference hull's body frame.
//
// Every polygon corner carries the features that made it, its clip feature: an incident
// vertex, the crossing of an incident edge with a reference side, or a reference vertex
// (two reference sides meeting). Sutherland-Hodgman tells which: each corner also records
// the line the polygon runs along to the next corner (an incident edge or a reference
// side), and a crossing made on that line inherits it.
//
// Edge axis: one point, midway between the closest points of the two edges (none for hulls
// apart whose edges do not cross seen along the axis).
//
// Feature keys, in the canonical order of the pair (first A, second B):
//   face contact: bit 30 set when the reference face is B's; bits 22-29 the reference face,
//     bits 14-21 the incident face, bits 0-11 the clip feature: bits 10-11 its type
//     (NP_CLIP_*), bits 0-4 and 5-9 its indices (incident vertex k: k; crossing: incident
//     edge k (vertex k to k + 1), reference side s (reference vertex s to s + 1): k | s << 5;
//     reference vertex between sides s and s': s | s' << 5).
//   edge contact: bit 31 set; bits 15-29 A's edge, bits 0-14 B's edge.
#ifndef TB_NP_HULL_CLIP_GLSL
#define TB_NP_HULL_CLIP_GLSL

// An incident polygon of up to 32 corners gains at most one corner per reference side (up
// to 32), so 64 corners hold any clipped polygon; the clipper keeps two (input, output).
#define NP_CLIP_MAX (2u * uint(TB_HULL_MAX_FACE_VERTICES))
#define NP_CLIP_INCIDENT_VERTEX 0u
#define NP_CLIP_CROSSING 1u
#define NP_CLIP_REFERENCE_VERTEX 2u
// The line a corner's outgoing polygon edge runs along: an incident edge k (k) or a
// reference side s (NP_CLIP_SIDE | s).
#define NP_CLIP_SIDE 32u

uint np_clip_feature(uint type, uint i, uint j)
{
    return (type << 10u) | (j << 5u) | i;
}

// A polygon corner: xyz in the reference frame, w its label, a float-coded integer (exact:
// below 2^18) holding the clip feature in bits 0-11 and the outgoing line in bits 12-17.
vec4 np_clip_corner(vec3 x, uint feature, uint line)
{
    return vec4(x, float(feature | (line << 12u)));
}

// Where polygon edge p -> q crosses reference side `side` (p's distance outside it dp, q's
// dq, of opposite signs). The edge runs along p's outgoing line; leaving the side's inner
// half-space, the polygon goes on along the side itself.
vec4 np_clip_crossing(vec4 p, vec4 q, float dp, float dq, uint side, bool leaving)
{
    uint line = uint(p.w) >> 12u;
    uint feature = (line & NP_CLIP_SIDE) != 0u
                       ? np_clip_feature(NP_CLIP_REFERENCE_VERTEX, line & 31u, side)
                       : np_clip_feature(NP_CLIP_CROSSING, line, side);
    return np_clip_corner(mix(p.xyz, q.xyz, dp / (dp - dq)), feature,
                          leaving ? (NP_CLIP_SIDE | side) : line);
}

// Side s of reference face `ref` (reference vertex s to s + 1): xyz its outward unit normal,
// w its offset; a zero vector for a degenerate edge.
vec4 np_clip_side(np_hull h, uvec2 ref, uint s, vec3 normal)
{
    vec3 r0 = np_hull_face_vertex(h, ref, s);
    vec3 r1 = np_hull_face_vertex(h, ref, s + 1u == ref.y ? 0u : s + 1u);
    vec3 side = cross(r1 - r0, normal);  // outward: the face lies left of r0 -> r1
    if (dot(side, side) == 0.0) return vec4(0.0);
    side = normalize(side);
    return vec4(side, dot(side, r0));
}

// A corner clipped with the tolerance may lie that little outside the reference face:
// moved onto it (within the reference plane), it lies on both surfaces.
vec3 np_clip_onto_face(np_hull h, uvec2 ref, vec3 normal, vec3 x)
{
    for (uint s = 0u; s < ref.y; s++) {
        vec4 side = np_clip_side(h, ref, s, normal);
        x -= side.xyz * max(dot(side.xyz, x) - side.w, 0.0);
    }
    return x;
}

// The vertex of h deepest along -n (h's frame); the first of equals.
uint np_support_vertex(np_hull h, vec3 n)
{
    uint best = 0u;
    float least = NP_BIG;
    for (uint v = 0u; v < h.vertices; v++) {
        float c = dot(np_hull_vertex(h, v), n);
        if (c < least) {
            least = c;
            best = v;
        }
    }
    return best;
}

// The incident face: of the faces around h's deepest vertex along -n, the one most
// anti-parallel to n (h's frame; the first of equals). Among all faces the most anti-
// parallel one can miss that vertex (a hull standing on a corner whose faces are steep),
// and the corner would then sink into the reference face unseen. The faces around a vertex
// are those left and right of its edges.
uint np_incident_face(np_hull h, vec3 n)
{
    uint deepest = np_support_vertex(h, n);
    uint face = 0u;
    float least = NP_BIG;
    for (uint e = 0u; e < h.edges; e++) {
        uvec2 ends = np_hull_edge_vertices(h, e);
        if (ends.x != deepest && ends.y != deepest) continue;
        uvec2 sides = np_hull_edge_faces(h, e);
        for (uint k = 0u; k < 2u; k++) {
            uint f = k == 0u ? sides.x : sides.y;
            float c = dot(np_hull_plane(h, f).xyz, n);
            if (c < least || (c == least && f < face)) {
                least = c;
                face = f;
            }
        }
    }
    return face;
}

// An incident polygon for np_face_clip_contact: a face of hull hi (i_in_r mapping hi's
// frame into the reference's), or a triangle already in the reference's frame (a mesh's,
// triangle.glsl).
struct np_incident {
    bool triangle;
    np_hull hull;
    np_frame in_ref;
    vec3 v0, v1, v2;
};

// Reference body r (hull hr, face rf) against the incident polygon: a hull's face most
// anti-parallel to the reference normal (its index joins key), or a triangle; key carries
// the reference side and face; corners within `tol` of a side count as inside. Returns
// the point count.
uint np_face_clip_contact(np_target t, np_body r, np_hull hr, uint rf, np_incident inc,
                          uint key, float tol, float margin)
{
    vec4 plane = np_hull_plane(hr, rf);
    // Two polygons in one array: the clipper reads one half and writes the other.
    vec4 poly[2u * NP_CLIP_MAX];
    uint n = 3u;
    if (inc.triangle) {
        poly[0] = np_clip_corner(inc.v0, np_clip_feature(NP_CLIP_INCIDENT_VERTEX, 0u, 0u), 0u);
        poly[1] = np_clip_corner(inc.v1, np_clip_feature(NP_CLIP_INCIDENT_VERTEX, 1u, 0u), 1u);
        poly[2] = np_clip_corner(inc.v2, np_clip_feature(NP_CLIP_INCIDENT_VERTEX, 2u, 0u), 2u);
    } else {
        uint face_index = np_incident_face(inc.hull, transpose(inc.in_ref.rot) * plane.xyz);
        key |= face_index << 14u;
        uvec2 face = np_hull_face(inc.hull, face_index);
        n = face.y;
        for (uint k = 0u; k < n; k++)
            poly[k] = np_clip_corner(np_apply(inc.in_ref, np_hull_face_vertex(inc.hull, face, k)),
                                     np_clip_feature(NP_CLIP_INCIDENT_VERTEX, k, 0u), k);
    }

    uvec2 ref = np_hull_face(hr, rf);
    uint from = 0u, to = NP_CLIP_MAX;
    for (uint s = 0u; s < ref.y && n > 0u; s++) {
        vec4 side = np_clip_side(hr, ref, s, plane.xyz);
        if (side.xyz == vec3(0.0)) continue;
        uint m = 0u;
        vec4 p = poly[from + n - 1u];
        float dp = dot(side.xyz, p.xyz) - side.w - tol;
        for (uint k = 0u; k < n; k++) {
            vec4 q = poly[from + k];
            float dq = dot(side.xyz, q.xyz) - side.w - tol;
            if ((dp > 0.0) != (dq > 0.0) && m < NP_CLIP_MAX)
                poly[to + m++] = np_clip_crossing(p, q, dp, dq, s, dq > 0.0);
            if (dq <= 0.0 && m < NP_CLIP_MAX) poly[to + m++] = q;
            p = q;
            dp = dq;
        }
        n = m;
        from = to;
        to = NP_CLIP_MAX - to;
    }

    // The corners within the margin of the reference plane; more than four are reduced.
    uint near = 0u;
    for (uint k = 0u; k < n; k++)
        if (dot(plane.xyz, poly[from + k].xyz) - plane.w < margin) near++;
    uvec4 kept = uvec4(NP_NONE);
    if (near > 4u) {
        vec3 p0 = vec3(0.0), p1 = vec3(0.0);
        for (uint pick = 0u; pick < 4u; pick++) {
            float best = -NP_BIG;
            for (uint k = 0u; k < n; k++) {
                vec3 x = poly[from + k].xyz;
                float h = dot(plane.xyz, x) - plane.w;
                if (h >= margin || any(equal(kept, uvec4(k)))) continue;
                float score = np_reduce_score(pick, x, h, p0, p1, plane.xyz);
                if (score > best) {
                    best = score;
                    kept[pick] = k;
                }
            }
            if (pick == 0u) p0 = poly[from + kept[0]].xyz;
            if (pick == 1u) p1 = poly[from + kept[1]].xyz;
        }
    }
    uint count = 0u;
    for (uint k = 0u; k < n; k++) {
        vec4 c = poly[from + k];
        float h = dot(plane.xyz, c.xyz) - plane.w;
        if (h >= margin || (near > 4u && !any(equal(kept, uvec4(k))))) continue;
        vec3 x = np_clip_onto_face(hr, ref, plane.xyz, c.xyz);
        vec3 point = r.pos + r.rot * (x - plane.xyz * (0.5 * h));
        np_emit(t, count, point, h, key | (uint(c.w) & 0xfffu));
        count++;
    }
    return count;
}

// Reference body r (hull hr, face rf) against incident hull hi, i_in_r mapping hi's frame
// into r's; key carries the reference side and face. Returns the point count.
uint np_hull_face_contact(np_target t, np_body r, np_hull hr, uint rf, np_hull hi,
                          np_frame i_in_r, uint key, float margin)
{
    np_incident inc;
    inc.triangle = false;
    inc.hull = hi;
    inc.in_ref = i_in_r;
    inc.v0 = inc.v1 = inc.v2 = vec3(0.0);
    // Corners within rounding of a side count as inside, so where corners of equal faces
    // meet the incident vertex wins every time, not a crossing a rounding away from it.
    float tol = 1.0e-5 * (length(np_hull_face_vertex(hr, np_hull_face(hr, rf), 0u)) +
                          length(i_in_r.pos)) +
                1.0e-6 * (length(r.pos) + 1.0);
    return np_face_clip_contact(t, r, hr, rf, inc, key, tol, margin);
}

// ---- edge contact -------------------------------------------------------------------------

// Closest points of the segments a0 + s da and b0 + u db, s and u in [0, 1] (Ericson,
// "Real-Time Collision Detection", 5.1.9), for segments that are not parallel.
void np_segments_closest(vec3 a0, vec3 da, vec3 b0, vec3 db, out vec3 pa, out vec3 pb)
{
    vec3 r = a0 - b0;
    float aa = dot(da, da), bb = dot(db, db), ab = dot(da, db), ar = dot(da, r), br = dot(db, r);
    float denom = aa * bb - ab * ab;
    float s = denom > 0.0 ? clamp((ab * br - ar * bb) / denom, 0.0, 1.0) : 0.0;
    float u = (ab * s + br) / bb;
    if (u < 0.0) {
        u = 0.0;
        s = clamp(-ar / aa, 0.0, 1.0);
    } else if (u > 1.0) {
        u = 1.0;
        s = clamp((ab - ar) / aa, 0.0, 1.0);
    }
    pa = a0 + da * s;
    pb = b0 + db * u;
}

// Edge ia of A against edge ib of B along the unit normal n (world, from A to B).
uint np_hull_edge_contact(np_target t, np_body a, np_hull ha, uint ia, np_body b, np_hull hb,
                          uint ib, vec3 n, float margin)
{
    uvec2 va = np_hull_edge_vertices(ha, ia), vb = np_hull_edge_vertices(hb, ib);
    vec3 a0 = a.pos + a.rot * np_hull_vertex(ha, va.x), a1 = a.pos + a.rot * np_hull_vertex(ha, va.y);
    vec3 b0 = b.pos + b.rot * np_hull_vertex(hb, vb.x), b1 = b.pos + b.rot * np_hull_vertex(hb, vb.y);
    vec3 pa, pb;
    np_segments_closest(a0, a1 - a0, b0, b1 - b0, pa, pb);
    vec3 gap = pb - pa;
    float separation = dot(gap, n);
    // Apart, with the closest points beside each other rather than along the axis (the
    // edges do not cross seen along it, so a segment end clamped them): the hulls are
    // nearest at a corner, which no edge point describes; a later step's face axis sees it.
    float beside = length(gap - n * separation);
    if (separation >= margin || (separation > 0.0 && beside > 1.0e-4)) return 0u;
    np_emit(t, 0u, 0.5 * (pa + pb), separation, 0x80000000u | (ia << 15u) | ib);
    return 1u;
}

#endif
