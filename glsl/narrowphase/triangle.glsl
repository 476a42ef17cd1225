// A convex shape against one triangle of a mesh (the shape first in the canonical order, the
// mesh second; normals point from the shape to the triangle). Triangles are one-sided: a
// shape wholly behind a triangle's plane gets no contact from it, and a contact's normal
// always has the triangle's front on its side, so a shape partly behind (a hard landing
// can sink its centre below a terrain's surface) is pushed back out to the front.
//
// Internal edges: a triangle's inactive edges and vertices (layout.h, TB_MESH_EDGE_ACTIVE_*)
// lie where the mesh is flat or folds concavely, so a contact there takes the triangle's
// face normal instead of the edge's or the vertex's direction. A body sliding over a flat
// mesh then meets only face normals, and no seam between triangles pushes it up or back.
//
// Sphere: the triangle's point closest to the centre (Ericson, "Real-Time Collision
// Detection", 5.1.5), one point, feature key 0.
// Hull (boxes through their hull data): the separating axis test in the hull's frame with the
// triangle as a flat polytope: the triangle's normal, the hull's face normals, and the
// crosses of hull edges with the triangle's active edges that build a face of the Minkowski
// difference (hull_sat.glsl's arc test, the triangle edge's arc running from the face normal
// to the edge's outward direction: the front quarter of it, one-sided). The triangle's face
// wins ties (the tolerances of box_box.glsl). Points: the hull's part over the triangle
// (its lowest corners, np_tri_prism_contact), or the triangle clipped by the reference hull
// face's sides, reduced to four (hull.glsl); one point for an edge axis.
// Feature keys: triangle reference: bit 30 | the corner's kind << 26 | its features; hull
// face reference: face << 22 | clip feature; edges: bit 31 | hull edge << 15 | triangle edge.
#ifndef TB_NP_TRIANGLE_GLSL
#define TB_NP_TRIANGLE_GLSL

struct np_triangle {
    vec3 v0, v1, v2;    // in the frame the routine works in
    vec3 normal;        // unit, towards the front; zero for a degenerate triangle
    uint flags;         // TB_MESH_*
};

// Triangle `index` of mesh or heightfield body `mesh`, mapped into a frame by
// x -> rot * x + pos from the mesh's body frame.
np_triangle np_load_triangle(np_body mesh, uint index, mat3 rot, vec3 pos)
{
    vec3 p0, p1, p2;
    uint flags;
    if (mesh.type == TB_GPU_SHAPE_HEIGHTFIELD) {
        field_triangle(field_of_shape(mesh.shape), index, p0, p1, p2, flags);
    } else {
        mesh_view m = mesh_of_shape(mesh.shape);
        uvec4 tri = mesh_triangle(m, index);
        p0 = mesh_vertex(m, tri.x);
        p1 = mesh_vertex(m, tri.y);
        p2 = mesh_vertex(m, tri.z);
        flags = tri.w;
    }
    np_triangle t;
    t.v0 = rot * p0 + pos;
    t.v1 = rot * p1 + pos;
    t.v2 = rot * p2 + pos;
    t.flags = flags;
    vec3 n = cross(t.v1 - t.v0, t.v2 - t.v0);
    float n2 = dot(n, n);
    if (n2 == 0.0) t.flags |= TB_MESH_DEGENERATE;
    t.normal = n2 > 0.0 ? n * inversesqrt(n2) : vec3(0.0);
    return t;
}

vec3 np_tri_vertex(np_triangle t, uint k)
{
    return k == 0u ? t.v0 : (k == 1u ? t.v1 : t.v2);
}

bool np_tri_edge_active(np_triangle t, uint k)
{
    return (t.flags & (1u << k)) != 0u;
}

// Vertex k ends edge k + 2 (mod 3) and starts edge k.
bool np_tri_vertex_active(np_triangle t, uint k)
{
    return np_tri_edge_active(t, k) || np_tri_edge_active(t, (k + 2u) % 3u);
}

// Features of a triangle: 0 its face, 1 + k edge k, 4 + k vertex k.
bool np_tri_feature_active(np_triangle t, uint feature)
{
    if (feature == 0u) return true;
    return feature < 4u ? np_tri_edge_active(t, feature - 1u)
                        : np_tri_vertex_active(t, feature - 4u);
}

// The triangle's point closest to p and its feature (Voronoi regions of the vertices, then
// the edges, then the face).
vec3 np_tri_closest(np_triangle t, vec3 p, out uint feature)
{
    vec3 a = t.v0, b = t.v1, c = t.v2, ab = b - a, ac = c - a;
    vec3 ap = p - a, bp = p - b, cp = p - c;
    float d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp);
    float d5 = dot(ab, cp), d6 = dot(ac, cp);
    float vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    feature = 0u;
    if (d1 <= 0.0 && d2 <= 0.0) feature = 4u;
    else if (d3 >= 0.0 && d4 <= d3) feature = 5u;
    else if (d6 >= 0.0 && d5 <= d6) feature = 6u;
    else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) feature = 1u;
    else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) feature = 2u;
    else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) feature = 3u;
    if (feature >= 4u) return np_tri_vertex(t, feature - 4u);
    if (feature == 1u) return a + ab * (d1 / (d1 - d3));
    if (feature == 2u) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    if (feature == 3u) return a + ac * (d2 / (d2 - d6));
    float scale = 1.0 / (va + vb + vc);
    return a + ab * (vb * scale) + ac * (vc * scale);
}

// ---- sphere ---------------------------------------------------------------------------------

// The triangle in world space. A centre behind the plane (a hard landing took it there)
// is pushed back out along the face normal while it lies over the triangle.
uint np_sphere_triangle(np_target t, np_body s, np_triangle tri, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    if ((tri.flags & TB_MESH_DEGENERATE) != 0u) return 0u;
    float height = dot(tri.normal, s.pos - tri.v0);
    if (height < -s.params.x || height >= s.params.x + margin) return 0u;
    uint feature;
    vec3 q = np_tri_closest(tri, s.pos, feature);
    if (height < 0.0 && feature != 0u) return 0u;
    vec3 gap = s.pos - q, outward = tri.normal;
    if (feature != 0u && np_tri_feature_active(tri, feature) &&
        dot(gap, gap) > 1.0e-12 * (dot(s.pos, s.pos) + 1.0)) {
        outward = normalize(gap);
    } else {
        q = s.pos - tri.normal * height;   // the face's plane below the centre
    }
    normal = -outward;
    return np_sphere_point(t, s, normal, q, margin);
}

// ---- hull -----------------------------------------------------------------------------------

// Whether the triangle's deepest feature along -n (hull frame) is active: its deepest vertex,
// or the edge of its two deepest when they lie level.
bool np_tri_deepest_active(np_triangle tri, vec3 n)
{
    float d0 = dot(n, tri.v0), d1 = dot(n, tri.v1), d2 = dot(n, tri.v2);
    uint k = d0 <= d1 && d0 <= d2 ? 0u : (d1 <= d2 ? 1u : 2u);
    float least = min(d0, min(d1, d2));
    float size = length(tri.v1 - tri.v0) + length(tri.v2 - tri.v1) + length(tri.v0 - tri.v2);
    float level = 1.0e-4 * size;
    uint next = (k + 1u) % 3u, before = (k + 2u) % 3u;
    float dn = next == 0u ? d0 : (next == 1u ? d1 : d2);
    float db = before == 0u ? d0 : (before == 1u ? d1 : d2);
    if (dn - least <= level) return np_tri_edge_active(tri, k);
    if (db - least <= level) return np_tri_edge_active(tri, before);
    return np_tri_vertex_active(tri, k);
}

// The hull faces lying lowest against the triangle: how far the triangle's deepest vertex
// is above each. x the best of all faces, y of the faces that face the triangle's front
// (whose normal, from the hull to the triangle, runs against the triangle's); `face` the
// latter's.
vec2 np_tri_best_hull_faces(np_hull h, np_triangle tri, out uint face)
{
    vec2 best = vec2(-NP_BIG);
    face = 0u;
    for (uint f = 0u; f < h.faces; f++) {
        vec4 plane = np_hull_plane(h, f);
        float s = min(dot(plane.xyz, tri.v0), min(dot(plane.xyz, tri.v1), dot(plane.xyz, tri.v2))) -
                  plane.w;
        best.x = max(best.x, s);
        if (dot(plane.xyz, tri.normal) < 0.0 && s > best.y) {
            best.y = s;
            face = f;
        }
    }
    return best;
}

// The crossings of hull edges and the triangle's active edges. A triangle edge's arc on the
// Gauss map runs from the face normal over its outward direction out_k to the back: the
// front quarter gives the axes a contact may take (from the triangle to the hull, between
// its face normal and out_k), the back quarter only separations. Returns the front's best
// (xyz the unit axis from the hull to the triangle, w the separation; edges in `which`, x
// hull, y triangle); `any` the best separation of either quarter.
vec4 np_tri_best_edges(np_hull h, np_triangle tri, out uvec2 which, out float any)
{
    vec4 best = vec4(0.0, 0.0, 0.0, -NP_BIG);
    which = uvec2(0u);
    any = -NP_BIG;
    for (uint k = 0u; k < 3u; k++) {
        if (!np_tri_edge_active(tri, k)) continue;
        vec3 t0 = np_tri_vertex(tri, k), dk = np_tri_vertex(tri, (k + 1u) % 3u) - t0;
        vec3 out_k = cross(dk, tri.normal);   // in the plane, away from the triangle
        for (uint e = 0u; e < h.edges; e++) {
            uvec2 faces = np_hull_edge_faces(h, e);
            vec3 u = np_hull_plane(h, faces.x).xyz, v = np_hull_plane(h, faces.y).xyz;
            vec3 ea = cross(u, v);
            // Both quarters' circle normals are dk: cross(normal, out_k) and cross(out_k, -normal).
            bool front = np_minkowski_face(u, v, ea, tri.normal, out_k, dk);
            if (!front && !np_minkowski_face(u, v, ea, out_k, -tri.normal, dk)) continue;
            vec3 n = cross(ea, dk);
            float n2 = dot(n, n);
            if (n2 < NP_EDGE_PARALLEL * dot(ea, ea) * dot(dk, dk)) continue;
            n *= inversesqrt(n2);
            vec3 pe = np_hull_vertex(h, np_hull_edge_vertices(h, e).x);
            if (dot(n, pe) < 0.0) n = -n;   // away from the hull's centre
            float s = dot(n, t0 - pe);
            any = max(any, s);
            if (front && s > best.w) {
                best = vec4(n, s);
                which = uvec2(e, k);
            }
        }
    }
    return best;
}

// ---- the triangle's face for reference: the hull over its prism -----------------------------

// The hull's part over the triangle (inside the prism its sides cut along its normal) is a
// convex polytope; its lowest points are among its corners: the hull's vertices inside the
// prism, the crossings of the hull's edges with the prism's sides, and where the prism's
// edges (the lines through the triangle's corners along its normal) enter the hull. Those
// are this contact's candidates, all of them, not one incident face's clipped polygon:
// a hull over several triangles has its incident face over another one, and one turning
// within the step brings down corners no face near the deepest vertex holds (a slab that
// landed on one end on a slope spun its other end down through the terrain).
// Feature keys: bit 30 | the candidate's kind << 26 | hull vertex v, hull edge e << 2 |
// side s, or triangle corner k.
#define NP_TRI_CANDIDATE_VERTEX 1u
#define NP_TRI_CANDIDATE_CROSSING 2u
#define NP_TRI_CANDIDATE_CORNER 3u

// Side s of the triangle: xyz its outward unit normal (in the plane), w its offset.
vec4 np_tri_side(np_triangle tri, uint s)
{
    vec3 t0 = np_tri_vertex(tri, s);
    vec3 side = normalize(cross(np_tri_vertex(tri, (s + 1u) % 3u) - t0, tri.normal));
    return vec4(side, dot(side, t0));
}

bool np_tri_in_prism(vec4 s0, vec4 s1, vec4 s2, vec3 x, float tol)
{
    return dot(s0.xyz, x) - s0.w <= tol && dot(s1.xyz, x) - s1.w <= tol &&
           dot(s2.xyz, x) - s2.w <= tol;
}

// Where the line through triangle corner k along the normal enters the hull: xyz the
// point, w its feature key's low bits (float bits: a normal float, kinds 1 to 3 being
// nonzero), or -1 when the line misses the hull.
vec4 np_tri_corner_entry(np_hull h, np_triangle tri, uint k)
{
    vec3 t = np_tri_vertex(tri, k), n = tri.normal;
    // The line t + r n lies inside every face plane for r in [enter, leave].
    float enter = -NP_BIG, leave = NP_BIG;
    for (uint f = 0u; f < h.faces; f++) {
        vec4 plane = np_hull_plane(h, f);
        float along = dot(plane.xyz, n), gap = plane.w - dot(plane.xyz, t);
        if (along < 0.0) enter = max(enter, gap / along);
        else if (along > 0.0) leave = min(leave, gap / along);
        else if (gap < 0.0) enter = NP_BIG;
    }
    return vec4(t + n * enter, enter <= leave ? uintBitsToFloat((NP_TRI_CANDIDATE_CORNER << 26u) | k) : -1.0);
}

// Candidates within the margin, gathered once: at most NP_TRI_FOUND, the lowest kept when
// more come (a hull's part over a triangle has few corners that low).
#define NP_TRI_FOUND 24u

// The contact with the triangle's face for reference, in the hull's frame: the candidates
// within the margin of the triangle's plane, more than four reduced (hull.glsl).
uint np_tri_prism_contact(np_target t, np_body hull, np_hull h, np_triangle tri, float margin)
{
    vec4 s0 = np_tri_side(tri, 0u), s1 = np_tri_side(tri, 1u), s2 = np_tri_side(tri, 2u);
    vec3 n = tri.normal;
    float w = dot(n, tri.v0);
    float tol = 1.0e-5 * (length(tri.v0) + length(np_hull_vertex(h, 0u))) + 1.0e-6;
    vec4 found[NP_TRI_FOUND];
    uint count = 0u;
    // Every candidate goes through here: kept while there is room, else in place of the
    // highest kept if lower.
    #define NP_TRI_OFFER(point, key) { \
        vec4 offered = vec4(point, uintBitsToFloat(key)); \
        if (count < NP_TRI_FOUND) { found[count++] = offered; } else { \
            uint top = 0u; \
            for (uint j = 1u; j < NP_TRI_FOUND; j++) \
                if (dot(n, found[j].xyz) > dot(n, found[top].xyz)) top = j; \
            if (dot(n, offered.xyz) < dot(n, found[top].xyz)) found[top] = offered; } }
    for (uint v = 0u; v < h.vertices; v++) {
        vec3 x = np_hull_vertex(h, v);
        if (dot(n, x) - w < margin && np_tri_in_prism(s0, s1, s2, x, tol))
            NP_TRI_OFFER(x, (NP_TRI_CANDIDATE_VERTEX << 26u) | v)
    }
    for (uint e = 0u; e < h.edges; e++) {
        uvec2 ends = np_hull_edge_vertices(h, e);
        vec3 p = np_hull_vertex(h, ends.x), q = np_hull_vertex(h, ends.y);
        if (min(dot(n, p), dot(n, q)) - w >= margin) continue;
        for (uint s = 0u; s < 3u; s++) {
            vec4 side = s == 0u ? s0 : (s == 1u ? s1 : s2);
            float dp = dot(side.xyz, p) - side.w, dq = dot(side.xyz, q) - side.w;
            if ((dp > 0.0) == (dq > 0.0)) continue;
            vec3 x = mix(p, q, dp / (dp - dq));
            if (dot(n, x) - w < margin && np_tri_in_prism(s0, s1, s2, x, tol))
                NP_TRI_OFFER(x, (NP_TRI_CANDIDATE_CROSSING << 26u) | (e << 2u) | s)
        }
    }
    for (uint k = 0u; k < 3u; k++) {
        vec4 x = np_tri_corner_entry(h, tri, k);
        if (x.w >= 0.0 && dot(n, x.xyz) - w < margin) NP_TRI_OFFER(x.xyz, floatBitsToUint(x.w))
    }
    #undef NP_TRI_OFFER
    uvec4 kept = uvec4(NP_NONE);
    if (count > 4u) {
        vec3 p0 = vec3(0.0), p1 = vec3(0.0);
        for (uint pick = 0u; pick < 4u; pick++) {
            float best = -NP_BIG;
            for (uint c = 0u; c < count; c++) {
                if (any(equal(kept, uvec4(c)))) continue;
                float score = np_reduce_score(pick, found[c].xyz, dot(n, found[c].xyz) - w, p0, p1, n);
                if (score > best) {
                    best = score;
                    kept[pick] = c;
                }
            }
            if (pick == 0u) p0 = found[kept[0]].xyz;
            if (pick == 1u) p1 = found[kept[1]].xyz;
        }
    }
    uint emitted = 0u;
    for (uint c = 0u; c < count; c++) {
        if (count > 4u && !any(equal(kept, uvec4(c)))) continue;
        float height = dot(n, found[c].xyz) - w;
        vec3 mid = found[c].xyz - n * (0.5 * height);   // midway between the surfaces
        np_emit(t, emitted, hull.pos + hull.rot * mid, height, (1u << 30u) | floatBitsToUint(found[c].w));
        emitted++;
    }
    return emitted;
}

// ---- a hull face for reference: the triangle clipped by its sides ---------------------------

// Hull face `face` for reference (hull frame): the triangle clipped by the face's sides,
// its corners within the margin of the face's plane, more than four reduced
// (hull_clip.glsl's clipper). Feature keys: face << 22 | clip feature.
uint np_tri_face_contact(np_target t, np_body hull, np_hull h, np_triangle tri, uint face,
                         float margin)
{
    np_incident inc;
    inc.triangle = true;
    inc.hull = h;
    inc.in_ref.rot = mat3(1.0);
    inc.in_ref.pos = vec3(0.0);
    inc.v0 = tri.v0;
    inc.v1 = tri.v1;
    inc.v2 = tri.v2;
    float tol = 1.0e-5 * (length(tri.v0) + length(np_hull_vertex(h, 0u))) +
                1.0e-6 * (length(hull.pos) + 1.0);
    return np_face_clip_contact(t, hull, h, face, inc, face << 22u, tol, margin);
}

// Edge axis: one point midway between the closest points of the hull edge and the
// triangle edge (hull frame), unless apart and beside each other (hull_clip.glsl's rule).
uint np_tri_edge_contact(np_target t, np_body hull, np_hull h, np_triangle tri, uvec2 which,
                         vec3 n, float margin)
{
    uvec2 ends = np_hull_edge_vertices(h, which.x);
    vec3 a0 = np_hull_vertex(h, ends.x), a1 = np_hull_vertex(h, ends.y);
    vec3 b0 = np_tri_vertex(tri, which.y), b1 = np_tri_vertex(tri, (which.y + 1u) % 3u);
    vec3 pa, pb;
    np_segments_closest(a0, a1 - a0, b0, b1 - b0, pa, pb);
    vec3 gap = pb - pa;
    float separation = dot(gap, n);
    if (separation >= margin || (separation > 0.0 && length(gap - n * separation) > 1.0e-4))
        return 0u;
    np_emit(t, 0u, hull.pos + hull.rot * (0.5 * (pa + pb)), separation,
            0x80000000u | (which.x << 15u) | which.y);
    return 1u;
}

// The triangle in the hull's frame. `normal` comes back in world space. Every axis decides
// whether the two are apart; only the front's (the triangle's normal, hull faces facing it,
// edge crossings of the front quarter) may be the contact's, so a triangle that cuts a
// hull near its top never pushes it down through the mesh, and a hull that sank partly
// behind it is pushed back out to the front.
uint np_hull_triangle(np_target t, np_body hull, np_triangle tri, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    if ((tri.flags & TB_MESH_DEGENERATE) != 0u) return 0u;
    np_hull h = np_hull_of(hull);
    float lowest = NP_BIG, highest = -NP_BIG;
    for (uint i = 0u; i < h.vertices; i++) {
        float along = dot(tri.normal, np_hull_vertex(h, i));
        lowest = min(lowest, along);
        highest = max(highest, along);
    }
    float sep_t = lowest - dot(tri.normal, tri.v0);
    // Wholly behind the triangle: no contact (one-sided). Partly behind, it is pushed out
    // to the front: a hull whose centre a hard landing took below a terrain's surface
    // must still come back up rather than fall through.
    if (sep_t >= margin || highest < dot(tri.normal, tri.v0)) return 0u;
    uint face;
    vec2 sep_f = np_tri_best_hull_faces(h, tri, face);
    if (sep_f.x >= margin) return 0u;
    uvec2 which;
    float sep_any_edge;
    vec4 edge = np_tri_best_edges(h, tri, which, sep_any_edge);
    float apart = max(sep_t, max(sep_f.x, sep_any_edge));
    if (apart >= margin) return 0u;
    float front = max(sep_t, max(sep_f.y, edge.w));
    // Apart beside the triangle, overlapping along every front axis: its neighbours' job.
    if (apart > 0.0 && front < 0.0) return 0u;
    // The triangle's face unless a hull face is clearly better over an active feature of
    // the triangle, unless an edge pair is clearly better than that.
    bool hull_ref = np_clearly_better(sep_f.y, sep_t) &&
                    np_tri_deepest_active(tri, np_hull_plane(h, face).xyz);
    uint count = 0u;
    if (np_clearly_better(edge.w, hull_ref ? sep_f.y : sep_t)) {
        normal = hull.rot * edge.xyz;
        count = np_tri_edge_contact(t, hull, h, tri, which, edge.xyz, margin);
    } else if (hull_ref) {
        normal = hull.rot * np_hull_plane(h, face).xyz;
        count = np_tri_face_contact(t, hull, h, tri, face, margin);
    }
    // The triangle's face, chosen, or when the chosen axis's features do not face each
    // other over the triangle (a hull face whose sides leave the triangle out).
    if (count == 0u && sep_t < margin) {
        normal = hull.rot * -tri.normal;
        count = np_tri_prism_contact(t, hull, h, tri, margin);
    }
    return count;
}

#endif
