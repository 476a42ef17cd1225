// Box against box: the separating axis test on the 15 axes of two boxes (3 + 3 face
// normals, 9 edge cross products), then either
// - a face contact: the face of the reference box on the chosen axis, the incident face of
//   the other box (its face most anti-parallel to the reference normal), the incident face
//   clipped by the reference face's four side planes, the points within the margin, and a
//   reduction to four of them; or
// - an edge contact: one point midway between the closest points of the two edges.
//
// The clipped polygon is the intersection of two convex quadrilaterals in the reference
// face's plane, so its corners are of three kinds only: incident corners inside the
// reference face, reference corners inside the incident face, and crossings of an incident
// edge with a reference side. They are enumerated one by one (24 candidates) instead of
// clipping a vertex list with Sutherland-Hodgman: the same polygon, but no private array
// indexed at run time, and each point is born with the features that make it, its key.
//
// Feature keys, in the canonical order of the pair (first, second):
//   face contact: bit 30 set when the reference face is the second box's; bits 24-26 the
//     reference face, bits 16-18 the incident face (face = 2 * axis + (outward along +axis));
//     bits 0-7 the clip feature: 0-3 incident corner j, 4-7 reference corner k,
//     8 + 4 * j + s the crossing of incident edge j with reference side s.
//   edge contact: bit 31 set; bits 0-3 the first box's edge, bits 4-7 the second's
//     (edge = 4 * axis + the signs of the two other coordinates, bit 0 for axis + 1 and
//     bit 1 for axis + 2).
#ifndef TB_NP_BOX_BOX_GLSL
#define TB_NP_BOX_BOX_GLSL

// An axis replaces the one found before only when it separates clearly more (penetrates
// clearly less), so the choice does not flip between steps on rounding: faces of the first
// box before faces of the second, faces before edges.
#define NP_AXIS_REL_TOL 0.05
#define NP_AXIS_ABS_TOL 5.0e-4
// Edge pairs whose cross product is shorter than this (squared sine) are near parallel:
// their axis is no better than a face axis and its direction is noise.
#define NP_EDGE_PARALLEL 1.0e-6
#define NP_BIG 3.0e38

bool np_clearly_better(float candidate, float current)
{
    return candidate > current + NP_AXIS_ABS_TOL + NP_AXIS_REL_TOL * abs(current);
}

// Half the extent of a box's projection onto l, times |l|.
float np_box_radius(np_body box, vec3 l)
{
    vec3 h = box.params.xyz;
    return h.x * abs(dot(box.rot[0], l)) + h.y * abs(dot(box.rot[1], l)) +
           h.z * abs(dot(box.rot[2], l));
}

// ---- face contact -----------------------------------------------------------------------

// The incident face in reference face coordinates (s, t along the reference face's two
// edge axes, h height above it), and the reference face as a rectangle.
struct np_clip {
    vec3 centre;   // incident face centre
    vec3 u1, u2;   // incident face half edge vectors
    vec3 normal;   // incident face outward normal (z < 0: it faces the reference face)
    vec2 rect;     // reference face half extents
    vec2 extent;   // the same plus the clip tolerance
    float winding; // +1 or -1: orientation of the incident corners 0, 1, 2, 3 in (s, t)
};

// Incident corners go around the face: 0 (-, -), 1 (+, -), 2 (+, +), 3 (-, +).
vec3 np_clip_corner(np_clip c, uint j)
{
    float s1 = (j == 1u || j == 2u) ? 1.0 : -1.0;
    float s2 = j >= 2u ? 1.0 : -1.0;
    return c.centre + s1 * c.u1 + s2 * c.u2;
}

// Signed distance outside reference side s: 0 (+s), 1 (+t), 2 (-s), 3 (-t). <= 0 inside.
float np_clip_side(np_clip c, vec2 p, uint side)
{
    float along = (side & 1u) == 0u ? p.x : p.y;
    float extent = (side & 1u) == 0u ? c.extent.x : c.extent.y;
    return (side >= 2u ? -along : along) - extent;
}

bool np_clip_inside_rect(np_clip c, vec2 p)
{
    return all(lessThanEqual(abs(p), c.extent));
}

float np_cross2(vec2 a, vec2 b)
{
    return a.x * b.y - a.y * b.x;
}

bool np_clip_inside_incident(np_clip c, vec2 p)
{
    for (uint j = 0u; j < 4u; j++) {
        vec2 a = np_clip_corner(c, j).xy, b = np_clip_corner(c, (j + 1u) & 3u).xy;
        if (np_cross2(b - a, p - a) * c.winding < 0.0) return false;
    }
    return true;
}

// Height of the incident face above the reference face at (s, t).
float np_clip_height(np_clip c, vec2 p)
{
    return c.centre.z - dot(c.normal.xy, p - c.centre.xy) / c.normal.z;
}

// Candidate `id` (see the feature keys above) as (s, t, h, 1), or w = 0 when it is not a
// corner of the clipped polygon or lies beyond the margin.
vec4 np_clip_candidate(np_clip c, uint id, float margin)
{
    vec3 p;
    bool ok;
    if (id < 4u) {
        p = np_clip_corner(c, id);
        ok = np_clip_inside_rect(c, p.xy);
    } else if (id < 8u) {
        uint k = id - 4u;
        vec2 q = vec2((k == 1u || k == 2u) ? c.extent.x : -c.extent.x,
                      k >= 2u ? c.extent.y : -c.extent.y);
        p = vec3(q, np_clip_height(c, q));
        ok = np_clip_inside_incident(c, q);
    } else {
        uint j = (id - 8u) >> 2u, side = (id - 8u) & 3u;
        vec3 a = np_clip_corner(c, j), b = np_clip_corner(c, (j + 1u) & 3u);
        float da = np_clip_side(c, a.xy, side), db = np_clip_side(c, b.xy, side);
        ok = (da <= 0.0) != (db <= 0.0);
        p = mix(a, b, ok ? da / (da - db) : 0.0);
        ok = ok && np_clip_side(c, p.xy, (side + 1u) & 3u) <= 0.0 &&
             np_clip_side(c, p.xy, (side + 3u) & 3u) <= 0.0;
    }
    // Within the tolerance outside the reference face: onto its edge, on the incident face.
    vec2 inside = clamp(p.xy, -c.rect, c.rect);
    if (any(notEqual(inside, p.xy))) p = vec3(inside, np_clip_height(c, inside));
    return vec4(p, ok && p.z < margin ? 1.0 : 0.0);
}

// More than four points: keep the deepest, the one farthest from it, and the two extreme
// on either side of the line through those (largest triangles), i.e. the extremes along
// two orthogonal directions in the contact plane. Returns the mask of the four kept.
uint np_clip_reduce(np_clip c, uint mask, uint deepest, float margin)
{
    vec2 p0 = np_clip_candidate(c, deepest, margin).xy;
    uint rest = mask & ~(1u << deepest);
    uint far = deepest;
    float far_d2 = -1.0;
    for (uint m = rest; m != 0u; m &= m - 1u) {
        uint id = uint(findLSB(m));
        vec2 q = np_clip_candidate(c, id, margin).xy - p0;
        if (dot(q, q) > far_d2) { far_d2 = dot(q, q); far = id; }
    }
    vec2 axis = np_clip_candidate(c, far, margin).xy - p0;
    rest &= ~(1u << far);
    uint left = far, right = far;
    float most = -NP_BIG, least = NP_BIG;
    for (uint m = rest; m != 0u; m &= m - 1u) {
        uint id = uint(findLSB(m));
        float side = np_cross2(axis, np_clip_candidate(c, id, margin).xy - p0);
        if (side > most) { most = side; left = id; }
    }
    rest &= ~(1u << left);
    for (uint m = rest; m != 0u; m &= m - 1u) {
        uint id = uint(findLSB(m));
        float side = np_cross2(axis, np_clip_candidate(c, id, margin).xy - p0);
        if (side < least) { least = side; right = id; }
    }
    return (1u << deepest) | (1u << far) | (1u << left) | (1u << right);
}

// Reference box r, its face on `axis` with outward normal nr (facing box i); key carries
// the reference side and faces. The normal of the contact is nr.
uint np_box_face_contact(np_target t, np_body r, np_body i, uint axis, vec3 nr, uint key,
                         float margin)
{
    uint r1 = (axis + 1u) % 3u, r2 = (axis + 2u) % 3u;
    vec3 t1 = np_col(r.rot, r1), t2 = np_col(r.rot, r2);
    vec3 face_centre = r.pos + nr * np_comp(r.params.xyz, axis);
    mat3 to_face = transpose(mat3(t1, t2, nr));
    vec3 along = transpose(i.rot) * nr;
    vec3 aligned = abs(along);
    uint ia = aligned.x >= aligned.y && aligned.x >= aligned.z ? 0u
                                                                 : (aligned.y >= aligned.z ? 1u : 2u);
    float outward = np_comp(along, ia) > 0.0 ? -1.0 : 1.0;
    uint i1 = (ia + 1u) % 3u, i2 = (ia + 2u) % 3u;
    vec3 hi = i.params.xyz;
    vec3 ni = outward * np_col(i.rot, ia);
    np_clip c;
    c.centre = to_face * (i.pos + ni * np_comp(hi, ia) - face_centre);
    c.u1 = to_face * (np_col(i.rot, i1) * np_comp(hi, i1));
    c.u2 = to_face * (np_col(i.rot, i2) * np_comp(hi, i2));
    c.normal = to_face * ni;
    vec2 extent = vec2(np_comp(r.params.xyz, r1), np_comp(r.params.xyz, r2));
    // Corners of equal faces meet within rounding; the tolerance lets the incident corner
    // win every time instead of a crossing or reference corner a rounding apart.
    vec3 far = abs(face_centre);
    float tol = 1.0e-4 * max(extent.x, extent.y) + 1.0e-6 * (max(far.x, max(far.y, far.z)) + 1.0);
    c.rect = extent;
    c.extent = extent + tol;
    c.winding = np_cross2(c.u1.xy, c.u2.xy) >= 0.0 ? 1.0 : -1.0;
    key |= (2u * ia + (outward > 0.0 ? 1u : 0u)) << 16u;

    uint mask = 0u, deepest = 0u;
    float deepest_h = NP_BIG;
    for (uint id = 0u; id < 24u; id++) {
        vec4 p = np_clip_candidate(c, id, margin);
        if (p.w == 0.0) continue;
        mask |= 1u << id;
        if (p.z < deepest_h) { deepest_h = p.z; deepest = id; }
    }
    if (bitCount(mask) > 4) mask = np_clip_reduce(c, mask, deepest, margin);
    uint count = 0u;
    for (; mask != 0u; mask &= mask - 1u) {
        uint id = uint(findLSB(mask));
        vec3 p = np_clip_candidate(c, id, margin).xyz;
        np_emit(t, count, face_centre + p.x * t1 + p.y * t2 + (0.5 * p.z) * nr, p.z, key | id);
        count++;
    }
    return count;
}

// ---- edge contact -----------------------------------------------------------------------

// Edge of a box along `axis` on the side `signs` (box frame) picks: its centre (world) and key.
vec3 np_box_edge_centre(np_body box, uint axis, vec3 signs)
{
    vec3 offset = signs * box.params.xyz;
    offset[axis] = 0.0;
    return box.pos + box.rot * offset;
}

uint np_box_edge_key(uint axis, vec3 signs)
{
    return 4u * axis + (np_comp(signs, (axis + 1u) % 3u) > 0.0 ? 1u : 0u) +
           (np_comp(signs, (axis + 2u) % 3u) > 0.0 ? 2u : 0u);
}

// Edge i of box a against edge j of box b, normal n (from a to b): the edge of a furthest
// along n, the edge of b furthest against it, and the point between their closest points.
uint np_box_edge_contact(np_target t, np_body a, np_body b, uint i, uint j, vec3 n,
                         float margin)
{
    vec3 sa = np_signs(transpose(a.rot) * n), sb = np_signs(-(transpose(b.rot) * n));
    vec3 ca = np_box_edge_centre(a, i, sa), cb = np_box_edge_centre(b, j, sb);
    vec3 ea = np_col(a.rot, i), eb = np_col(b.rot, j);
    float la = np_comp(a.params.xyz, i), lb = np_comp(b.params.xyz, j);
    // Closest points of the two segments (not parallel: the axis was not skipped).
    vec3 r = ca - cb;
    float k = dot(ea, eb), ar = dot(ea, r), br = dot(eb, r);
    float s = clamp((k * br - ar) / (1.0 - k * k), -la, la);
    float u = clamp(br + s * k, -lb, lb);
    s = clamp(u * k - ar, -la, la);
    vec3 pa = ca + s * ea, pb = cb + u * eb;
    float separation = dot(pb - pa, n);
    if (separation >= margin) return 0u;
    uint key = 0x80000000u | np_box_edge_key(i, sa) | (np_box_edge_key(j, sb) << 4u);
    np_emit(t, 0u, 0.5 * (pa + pb), separation, key);
    return 1u;
}

// ---- the pair ---------------------------------------------------------------------------

uint np_box_box(np_target t, np_body a, np_body b, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    vec3 d = b.pos - a.pos;
    float sep_a = -NP_BIG, sep_b = -NP_BIG, sep_e = -NP_BIG;
    uint face_a = 0u, face_b = 0u, edge_a = 0u, edge_b = 0u;
    for (uint k = 0u; k < 3u; k++) {
        float s = abs(dot(d, a.rot[k])) - a.params[k] - np_box_radius(b, a.rot[k]);
        if (s > sep_a) { sep_a = s; face_a = k; }
    }
    for (uint k = 0u; k < 3u; k++) {
        float s = abs(dot(d, b.rot[k])) - b.params[k] - np_box_radius(a, b.rot[k]);
        if (s > sep_b) { sep_b = s; face_b = k; }
    }
    if (max(sep_a, sep_b) >= margin) return 0u;
    for (uint k = 0u; k < 3u; k++) {
        for (uint m = 0u; m < 3u; m++) {
            vec3 l = cross(a.rot[k], b.rot[m]);
            float l2 = dot(l, l);
            if (l2 < NP_EDGE_PARALLEL) continue;
            float s = (abs(dot(d, l)) - np_box_radius(a, l) - np_box_radius(b, l)) * inversesqrt(l2);
            if (s > sep_e) { sep_e = s; edge_a = k; edge_b = m; }
        }
    }
    if (sep_e >= margin) return 0u;

    bool ref_b = np_clearly_better(sep_b, sep_a);
    if (np_clearly_better(sep_e, ref_b ? sep_b : sep_a)) {
        normal = normalize(cross(a.rot[edge_a], b.rot[edge_b]));
        if (dot(normal, d) < 0.0) normal = -normal;
        return np_box_edge_contact(t, a, b, edge_a, edge_b, normal, margin);
    }
    uint axis = ref_b ? face_b : face_a;
    vec3 nr = np_col(ref_b ? b.rot : a.rot, axis);
    float outward = dot(nr, ref_b ? -d : d) >= 0.0 ? 1.0 : -1.0;
    nr *= outward;
    uint key = (ref_b ? 1u << 30u : 0u) | ((2u * axis + (outward > 0.0 ? 1u : 0u)) << 24u);
    normal = ref_b ? -nr : nr;
    return ref_b ? np_box_face_contact(t, b, a, axis, nr, key, margin)
                 : np_box_face_contact(t, a, b, axis, nr, key, margin);
}

#endif
