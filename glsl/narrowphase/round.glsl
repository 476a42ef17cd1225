// Contact manifolds of the pairs with a capsule, cylinder or cone (narrowphase/round_points):
// the normal from GJK (cores apart) or EPA (cores overlapping), then the points from the
// two shapes' supporting features along it, as persistent-manifold engines build them:
//
// - Each shape offers the feature it presents along the normal (np_feature_of): a face
//   polygon (a box or hull face, a cylinder's cap or a cone's base as an octagon whose first
//   corner is the rim's farthest point, a triangle), a line (a capsule's or cylinder's side,
//   a cone's slant line) when the normal is within 10 degrees of square to it, or a point.
// - Where one feature is a face within 25 degrees of the normal, the other's polygon, line
//   or point is clipped by the face's side planes (Sutherland-Hodgman) and its corners below the
//   face plane plus the margin are the points, measured along the face normal, which
//   becomes the manifold's; more than four are reduced (hull.glsl).
// - Two parallel lines overlap on a segment: its two ends.
// - Anything else (or nothing left after clipping) is one point: the closest points.
//
// A cylinder standing on its cap gets four points, lying on its side two (a line contact),
// tilted on its rim one; so does a cone on its base, its slant side, its rim.
//
// Feature keys: bit 31 one closest point; else bit 30 set when the reference face is the
// second shape's, bits 22-29 the reference feature, 14-21 the incident feature, 0-13 the
// corner's label (an incident corner k: k; a crossing made by reference side s of the
// polygon edge from a corner labelled L: (s + 1) << 6 | L & 63).
#ifndef TB_NP_ROUND_GLSL
#define TB_NP_ROUND_GLSL

#extension GL_EXT_control_flow_attributes : require

#define NP_FEATURE_MAX 32u      // a hull face's most corners (TB_HULL_MAX_FACE_VERTICES)
#define NP_DISC_CORNERS 8u      // a cap or base circle as a polygon
#define NP_CLIP_ROOM 48u        // a clipped polygon's corners: 32 + 8 sides, and some
#define NP_LINE_SINE 0.17       // sin 10 degrees: a side within it of square to the normal
#define NP_FACE_COSINE 0.9      // cos 25 degrees: a face within it of the normal
// GJK's tolerance for contacts: |v| within 0.1 % of the distance bound. Over a skin of 4 cm
// that is 40 microns, and on a curved surface of radius R a normal within sqrt(2e-3 d / R)
// (under a degree); feature normals replace it on faces anyway. GJK's iterations on curved
// shapes, not its answer, are what a tighter one buys.
#define NP_GJK_CONTACT_TOLERANCE 1.0e-3

// A feature's corners live in np_feature_v[slot] (a private array each of the two shapes
// fills), not in the struct: structs of arrays passed by value cost registers, and one
// driver failed to build the kernel with them.
vec3 np_feature_v[2][NP_FEATURE_MAX];

struct np_feature {
    uint slot;      // which row of np_feature_v holds the corners
    uint count;     // 1 a point, 2 a line, 3 or more a face polygon
    vec3 normal;    // a face's outward unit normal
    uint id;        // which feature of the shape (feature keys)
};

np_feature np_feature_points(uint slot, vec3 p, vec3 q, uint count, uint id)
{
    np_feature f;
    f.slot = slot;
    np_feature_v[f.slot][0] = p;
    np_feature_v[f.slot][1] = q;
    f.count = count;
    f.normal = vec3(0.0);
    f.id = id;
    return f;
}

// A circle of radius r about centre c, facing `normal`, as an octagon whose first corner
// lies in direction `start` (unit, square to normal).
np_feature np_feature_disc(uint slot, vec3 c, vec3 normal, vec3 start, float r, uint id)
{
    np_feature f;
    f.slot = slot;
    vec3 e2 = cross(normal, start);
    // cos and sin of k 45 degrees.
    const float h = 0.70710678;
    const vec2 turn[NP_DISC_CORNERS] = vec2[](vec2(1, 0), vec2(h, h), vec2(0, 1), vec2(-h, h),
                                              vec2(-1, 0), vec2(-h, -h), vec2(0, -1), vec2(h, -h));
    for (uint k = 0u; k < NP_DISC_CORNERS; k++)
        np_feature_v[f.slot][k] = c + r * (turn[k].x * start + turn[k].y * e2);
    f.count = NP_DISC_CORNERS;
    f.normal = normal;
    f.id = id;
    return f;
}

// d's part square to the unit axis u, normalised; `fallback` (square to u) where d runs
// (nearly) along u.
vec3 np_radial(vec3 d, vec3 u, vec3 fallback)
{
    vec3 p = d - u * dot(d, u);
    float len = length(p);
    return len > 0.05 ? p / len : fallback;
}

np_feature np_capsule_feature(np_convex c, vec3 d, uint slot)
{
    vec3 u = c.body.rot[1];
    float cu = dot(u, d), h = c.body.params.y;
    vec3 skin = c.radius * d;
    if (abs(cu) < NP_LINE_SINE && h > 0.0)
        return np_feature_points(slot, c.body.pos - u * h + skin, c.body.pos + u * h + skin, 2u, 1u);
    float side = cu >= 0.0 ? 1.0 : -1.0;
    return np_feature_points(slot, c.body.pos + side * h * u + skin, vec3(0.0), 1u, cu >= 0.0 ? 2u : 3u);
}

np_feature np_cylinder_feature(np_convex c, vec3 d, uint slot)
{
    vec3 u = c.body.rot[1];
    float cu = dot(u, d), r = c.body.params.x, h = c.body.params.y;
    vec3 radial = np_radial(d, u, c.body.rot[0]);
    if (abs(cu) < NP_LINE_SINE) {
        vec3 rim = c.body.pos + radial * r;
        return np_feature_points(slot, rim - u * h, rim + u * h, 2u, 1u);
    }
    vec3 normal = cu >= 0.0 ? u : -u;
    return np_feature_disc(slot, c.body.pos + normal * h, normal, radial, r, cu >= 0.0 ? 2u : 3u);
}

np_feature np_cone_feature(np_convex c, vec3 d, uint slot)
{
    vec3 u = c.body.rot[1];
    float r = c.body.params.x, h = c.body.params.y;
    vec3 radial = np_radial(d, u, c.body.rot[0]);
    vec3 apex = c.body.pos + 1.5 * h * u, base = c.body.pos - 0.5 * h * u;
    vec3 rim = base + radial * r;
    vec3 slant = normalize(2.0 * h * radial + r * u);   // the side's outward normal there
    if (dot(d, slant) > 0.985) return np_feature_points(slot, apex, rim, 2u, 1u);
    if (dot(d, apex) >= dot(d, rim)) return np_feature_points(slot, apex, vec3(0.0), 1u, 4u);
    return np_feature_disc(slot, base, -u, radial, r, 2u);
}

np_feature np_box_feature(np_convex c, vec3 d, uint slot)
{
    vec3 l = transpose(c.body.rot) * d, al = abs(l), h = c.body.params.xyz;
    uint k = al.x >= al.y && al.x >= al.z ? 0u : (al.y >= al.z ? 1u : 2u);
    uint i = (k + 1u) % 3u, j = (k + 2u) % 3u;
    float side = l[k] >= 0.0 ? 1.0 : -1.0;
    np_feature f;
    f.slot = slot;
    const vec2 corners[4] = vec2[4](vec2(1, 1), vec2(-1, 1), vec2(-1, -1), vec2(1, -1));
    for (uint m = 0u; m < 4u; m++) {
        vec3 x;
        x[k] = side * h[k];
        x[i] = corners[m].x * h[i];
        x[j] = corners[m].y * h[j];
        np_feature_v[f.slot][m] = c.body.pos + c.body.rot * x;
    }
    vec3 n = vec3(0.0);
    n[k] = side;
    f.count = 4u;
    f.normal = c.body.rot * n;
    f.id = 2u * k + (side > 0.0 ? 1u : 0u);
    return f;
}

np_feature np_hull_feature(np_convex c, vec3 d, uint slot)
{
    np_hull h = np_hull_of(c.body);
    vec3 l = transpose(c.body.rot) * d;
    uint best = 0u;
    float most = -2.0;
    for (uint f = 0u; f < h.faces; f++) {
        float s = dot(np_hull_plane(h, f).xyz, l);
        if (s > most) {
            most = s;
            best = f;
        }
    }
    uvec2 face = np_hull_face(h, best);
    np_feature f;
    f.slot = slot;
    for (uint k = 0u; k < face.y; k++)
        np_feature_v[f.slot][k] = c.body.pos + c.body.rot * np_hull_face_vertex(h, face, k);
    f.count = face.y;
    f.normal = c.body.rot * np_hull_plane(h, best).xyz;
    f.id = best;
    return f;
}

np_feature np_triangle_feature(np_convex c, vec3 d, uint slot)
{
    np_feature f;
    f.slot = slot;
    np_feature_v[f.slot][0] = c.v0;
    np_feature_v[f.slot][1] = c.v1;
    np_feature_v[f.slot][2] = c.v2;
    vec3 n = normalize(cross(c.v1 - c.v0, c.v2 - c.v0));
    f.count = 3u;
    f.normal = dot(n, d) >= 0.0 ? n : -n;
    f.id = 0u;
    return f;
}

// A mesh triangle as a convex shape of its own.
np_convex np_convex_of_triangle(np_body mesh, np_triangle t)
{
    np_convex c;
    c.body = mesh;
    c.body.type = NP_SHAPE_TRIANGLE;
    c.v0 = t.v0;
    c.v1 = t.v1;
    c.v2 = t.v2;
    c.core = vec3(0.0);
    c.radius = 0.0;
    return c;
}

// The feature a capsule, cylinder or cone c presents along the unit direction d.
np_feature np_round_feature_of(np_convex c, vec3 d, uint slot)
{
    uint type = c.body.type;
    if (type == TB_GPU_SHAPE_CAPSULE) return np_capsule_feature(c, d, slot);
    if (type == TB_GPU_SHAPE_CYLINDER) return np_cylinder_feature(c, d, slot);
    return np_cone_feature(c, d, slot);
}

// The feature shape c presents along the unit direction d, on its surface.
np_feature np_feature_of(np_convex c, vec3 d, uint slot)
{
    uint type = c.body.type;
    if (np_is_round(type)) return np_round_feature_of(c, d, slot);
    if (type == TB_GPU_SHAPE_BOX) return np_box_feature(c, d, slot);
    if (type == TB_GPU_SHAPE_HULL) return np_hull_feature(c, d, slot);
    if (type == NP_SHAPE_TRIANGLE) return np_triangle_feature(c, d, slot);
    return np_feature_points(slot, c.body.pos + c.radius * d, vec3(0.0), 1u, 0u);   // sphere
}

// ---- candidates: clipped corners with their separations and labels ------------------------

vec4 np_cand[NP_CLIP_ROOM];     // xyz a point on the incident surface, w its separation
uint np_cand_label[NP_CLIP_ROOM];
uint np_cand_count;
vec4 np_clip_buf[NP_CLIP_ROOM];  // the clipper's second polygon (w the label, float-coded)

void np_cand_add(vec3 x, uint label)
{
    if (np_cand_count >= NP_CLIP_ROOM) return;
    np_cand[np_cand_count] = vec4(x, 0.0);
    np_cand_label[np_cand_count] = label;
    np_cand_count++;
}

// Side s of a face polygon: xyz its outward unit normal within the face plane, w its offset
// (inside: dot(xyz, x) <= w); zero for an edge of no length.
vec4 np_face_side(np_feature f, uint s, vec3 centre)
{
    vec3 p = np_feature_v[f.slot][s], q = np_feature_v[f.slot][s + 1u == f.count ? 0u : s + 1u];
    vec3 n = cross(q - p, f.normal);
    if (dot(n, n) == 0.0) return vec4(0.0);
    n = normalize(n);
    if (dot(n, centre - p) > 0.0) n = -n;
    return vec4(n, dot(n, p));
}

vec3 np_face_centre(np_feature f)
{
    vec3 c = vec3(0.0);
    for (uint k = 0u; k < f.count; k++) c += np_feature_v[f.slot][k];
    return c / float(f.count);
}

// The incident point if it lies in the reference face's prism (then the face normal is the
// exact normal: a sphere or a capsule's end over a face).
void np_clip_point(np_feature ref, vec3 x)
{
    vec3 centre = np_face_centre(ref);
    np_cand_count = 0u;
    for (uint s = 0u; s < ref.count; s++) {
        vec4 side = np_face_side(ref, s, centre);
        if (dot(side.xyz, x) > side.w) return;
    }
    np_cand_add(x, 0u);
}

// The incident line clipped to the reference face's prism.
void np_clip_line(np_feature ref, np_feature inc)
{
    vec3 centre = np_face_centre(ref);
    vec2 range = vec2(0.0, 1.0);
    for (uint s = 0u; s < ref.count; s++) {
        vec4 side = np_face_side(ref, s, centre);
        float dp = dot(side.xyz, np_feature_v[inc.slot][0]) - side.w, dq = dot(side.xyz, np_feature_v[inc.slot][1]) - side.w;
        if (dp > 0.0 && dq > 0.0) range = vec2(1.0, 0.0);
        else if (dp > 0.0) range.x = max(range.x, dp / (dp - dq));
        else if (dq > 0.0) range.y = min(range.y, dp / (dp - dq));
    }
    np_cand_count = 0u;
    if (range.x > range.y) return;
    np_cand_add(mix(np_feature_v[inc.slot][0], np_feature_v[inc.slot][1], range.x), 0u);
    np_cand_add(mix(np_feature_v[inc.slot][0], np_feature_v[inc.slot][1], range.y), 1u);
}

// The incident polygon clipped by the reference face's side planes (Sutherland-Hodgman),
// into np_cand.
void np_clip_polygon(np_feature ref, np_feature inc)
{
    np_cand_count = 0u;
    for (uint k = 0u; k < inc.count; k++) np_cand_add(np_feature_v[inc.slot][k], k);
    vec3 centre = np_face_centre(ref);
    for (uint s = 0u; s < ref.count && np_cand_count > 0u; s++) {
        vec4 side = np_face_side(ref, s, centre);
        if (side.xyz == vec3(0.0)) continue;
        uint n = 0u;
        for (uint k = 0u; k < np_cand_count; k++) {
            vec4 p = np_cand[k], q = np_cand[k + 1u == np_cand_count ? 0u : k + 1u];
            float dp = dot(side.xyz, p.xyz) - side.w, dq = dot(side.xyz, q.xyz) - side.w;
            uint label = np_cand_label[k];
            if (dp <= 0.0 && n < NP_CLIP_ROOM) np_clip_buf[n++] = vec4(p.xyz, float(label));
            if ((dp <= 0.0) != (dq <= 0.0) && n < NP_CLIP_ROOM)
                np_clip_buf[n++] = vec4(mix(p.xyz, q.xyz, dp / (dp - dq)),
                                        float(((s + 1u) << 6u) | (label & 63u)));
        }
        for (uint k = 0u; k < n; k++) {
            np_cand[k] = vec4(np_clip_buf[k].xyz, 0.0);
            np_cand_label[k] = uint(np_clip_buf[k].w);
        }
        np_cand_count = n;
    }
}

// The candidates below `plane` (xyz unit normal, w offset) plus the margin, at most four
// (hull.glsl's reduction), each written midway between its surface point and the plane.
uint np_cand_emit(np_target t, vec4 plane, float margin, uint key)
{
    uint n = 0u;
    for (uint k = 0u; k < np_cand_count; k++) {
        float separation = dot(plane.xyz, np_cand[k].xyz) - plane.w;
        if (separation >= margin) continue;
        np_cand[n] = vec4(np_cand[k].xyz, separation);
        np_cand_label[n] = np_cand_label[k];
        n++;
    }
    uint picked[4] = uint[4](NP_NONE, NP_NONE, NP_NONE, NP_NONE);
    uint count = min(n, 4u);
    for (uint pick = 0u; pick < count; pick++) {
        float best = -3.0e38;
        vec3 p0 = pick > 0u ? np_cand[picked[0]].xyz : vec3(0.0);
        vec3 p1 = pick > 1u ? np_cand[picked[1]].xyz : vec3(0.0);
        for (uint k = 0u; k < n; k++) {
            bool taken = false;
            for (uint m = 0u; m < pick; m++) taken = taken || picked[m] == k;
            float score = n <= 4u ? float(n - k) : np_reduce_score(pick, np_cand[k].xyz, np_cand[k].w, p0, p1, plane.xyz);
            if (!taken && (picked[pick] == NP_NONE || score > best)) {
                best = score;
                picked[pick] = k;
            }
        }
    }
    for (uint m = 0u; m < count; m++) {
        vec4 c = np_cand[picked[m]];
        np_emit(t, m, c.xyz - plane.xyz * (0.5 * c.w), c.w, key | np_cand_label[picked[m]]);
    }
    return count;
}

// The face contact's candidates: the incident feature clipped by the reference face; the
// reference plane (outward from the reference shape) and the feature key.
void np_face_candidates(np_feature ref, np_feature inc, bool ref_first, out vec4 plane,
                        out uint key)
{
    if (inc.count == 1u) np_clip_point(ref, np_feature_v[inc.slot][0]);
    else if (inc.count == 2u) np_clip_line(ref, inc);
    else np_clip_polygon(ref, inc);
    plane = vec4(ref.normal, dot(ref.normal, np_feature_v[ref.slot][0]));
    key = (ref_first ? 0u : 1u << 30) | ((ref.id & 255u) << 22) | ((inc.id & 255u) << 14);
}

// Two parallel lines: the candidates of the second's part beside the first, measured from
// the plane through the first square to n.
void np_line_candidates(np_feature a, np_feature b, vec3 n, out vec4 plane, out uint key)
{
    vec3 da = np_feature_v[a.slot][1] - np_feature_v[a.slot][0];
    float la = dot(da, da);
    float s0 = dot(np_feature_v[b.slot][0] - np_feature_v[a.slot][0], da) / la, s1 = dot(np_feature_v[b.slot][1] - np_feature_v[a.slot][0], da) / la;
    vec2 range = vec2(0.0, 1.0);
    if (s0 != s1) {
        float t0 = (0.0 - s0) / (s1 - s0), t1 = (1.0 - s0) / (s1 - s0);
        range = vec2(max(0.0, min(t0, t1)), min(1.0, max(t0, t1)));
    } else if (s0 < 0.0 || s0 > 1.0) {
        range = vec2(1.0, 0.0);
    }
    np_cand_count = 0u;
    plane = vec4(n, dot(n, np_feature_v[a.slot][0]));
    key = ((a.id & 255u) << 22) | ((b.id & 255u) << 14);
    if (range.x > range.y) return;
    np_cand_add(mix(np_feature_v[b.slot][0], np_feature_v[b.slot][1], range.x), 0u);
    np_cand_add(mix(np_feature_v[b.slot][0], np_feature_v[b.slot][1], range.y), 1u);
}

// The candidates of two shapes' manifold, given their unit normal n from A to B and their
// surface points pa, pb closest along it (apart: the closest points; overlapping: EPA's
// witnesses): the reference plane they are measured from, the key, and the normal from A to
// B (a face's where one is the reference).
void np_round_candidates(np_convex A, np_convex B, vec3 n, vec3 pa, vec3 pb, float margin,
                         out vec4 plane, out uint key, out vec3 normal)
{
    normal = n;
    // Each shape's feature along n, then, where one is a face within NP_FACE_COSINE of n,
    // the other's again along the face's own normal: GJK's normal is only within its
    // tolerance of the true one, and a curved side's line or a rim's point placed by a
    // tilted normal sits beside the lowest line, where its points would tip a lying
    // cylinder over. One call in a loop, not three: np_feature_of is large.
    np_feature f[2];
    uint ref = 2u;
    [[dont_unroll]] for (uint pass = 0u; pass < 3u; pass++) {
        uint s = pass < 2u ? pass : 1u - ref;
        vec3 d = pass == 0u ? n : (pass == 1u ? -n : -f[ref].normal);
        f[s] = np_feature_of(s == 0u ? A : B, d, s);
        if (pass != 1u) continue;
        float align_a = f[0].count >= 3u ? dot(f[0].normal, n) : -2.0;
        float align_b = f[1].count >= 3u ? dot(f[1].normal, -n) : -2.0;
        if (max(align_a, align_b) < NP_FACE_COSINE) break;
        ref = align_a >= align_b ? 0u : 1u;
    }
    np_cand_count = 0u;
    if (ref != 2u) {
        np_face_candidates(f[ref], f[1u - ref], ref == 0u, plane, key);
        normal = ref == 0u ? f[0].normal : -f[1].normal;
    } else if (f[0].count == 2u && f[1].count == 2u &&
               abs(dot(normalize(np_feature_v[0][1] - np_feature_v[0][0]),
                       normalize(np_feature_v[1][1] - np_feature_v[1][0]))) > 0.985) {
        np_line_candidates(f[0], f[1], n, plane, key);
    }
    bool near = false;
    for (uint k = 0u; k < np_cand_count; k++)
        near = near || dot(plane.xyz, np_cand[k].xyz) - plane.w < margin;
    if (near) return;
    // Anything else (or no candidate left within the margin): the closest points, as B's
    // point measured from the plane through A's square to n.
    normal = n;
    plane = vec4(n, dot(n, pa));
    key = 1u << 31;
    np_cand_count = 0u;
    np_cand_add(pb, 0u);
}

// ---- the pairs -----------------------------------------------------------------------------

// The penetration depth is the least overlap over all axes, so of EPA's normal and the line
// between the centres, the one the shapes overlap less along is the better answer: a net
// under EPA where its polytope went wrong (a float-degenerate start, the size limits) and
// its normal with it (a normal flipped shows as an overlap of nearly the shapes' size).
void np_keep_shallower_axis(np_convex A, np_convex B, inout vec3 n, inout vec3 pa,
                            inout vec3 pb)
{
    vec3 c = np_core_centre(B) - np_core_centre(A);
    if (dot(c, c) == 0.0) return;
    c = normalize(c);
    // How far the cores overlap along c and along n (A's farthest point along the axis
    // beyond B's farthest along its opposite), and A's farthest point along c.
    float overlap[2];
    vec3 a_along_c;
    [[dont_unroll]] for (uint k = 0u; k < 2u; k++) {
        vec3 axis = k == 0u ? c : n, a, b;
        np_core_supports(A, B, axis, a, b);
        overlap[k] = dot(axis, a - b);
        if (k == 0u) a_along_c = a;
    }
    // Only a clear miss is mended: shapes that barely touch overlap along no axis by more
    // than float noise, and a curved surface may leave a tilted axis a little shallower.
    if (!(overlap[0] > 0.0 && overlap[0] < 0.5 * overlap[1])) return;
    n = c;
    pa = a_along_c;
    pb = pa - c * overlap[0];
}

// A sphere's or capsule's core as a segment from p to q (a sphere's of no length), about o;
// false for any other shape.
bool np_core_segment(np_convex c, vec3 o, out vec3 p, out vec3 q)
{
    p = q = c.body.pos - o;
    if (c.body.type == TB_GPU_SHAPE_SPHERE) return true;
    if (c.body.type != TB_GPU_SHAPE_CAPSULE) return false;
    vec3 u = c.body.rot[1];
    p += u * c.core.y;
    q += u * c.core.z;
    return true;
}

// The closest points of segments p1 q1 and p2 q2: x on the first, y on the second (as
// fractions along each). Where the best point of one falls off its segment it is clamped
// and the other's is found again; parallel segments take the first's start.
vec2 np_segments_closest(vec3 p1, vec3 q1, vec3 p2, vec3 q2)
{
    vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    float a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
    if (a == 0.0) return vec2(0.0, e == 0.0 ? 0.0 : clamp(f / e, 0.0, 1.0));
    float c = dot(d1, r);
    if (e == 0.0) return vec2(clamp(-c / a, 0.0, 1.0), 0.0);
    float b = dot(d1, d2), square = a * e - b * b;
    float s = square > 1.0e-7 * a * e ? clamp((b * f - c * e) / square, 0.0, 1.0) : 0.0;
    float t = (b * s + f) / e;
    if (t < 0.0) return vec2(clamp(-c / a, 0.0, 1.0), 0.0);
    if (t > 1.0) return vec2(clamp((b - c) / a, 0.0, 1.0), 1.0);
    return vec2(s, t);
}

// Sphere or capsule A against a capsule B, in closed form: the closest points of their
// segments give the normal and the surface points, exactly and without GJK. Cores that
// cross take the normal square to both segments (or along the centres where they are
// parallel), turned from A towards B. False when farther apart than the margin.
bool np_segments_normal(vec3 p1, vec3 q1, vec3 p2, vec3 q2, float ra, float rb, float margin,
                        out vec3 n, out vec3 pa, out vec3 pb)
{
    vec2 st = np_segments_closest(p1, q1, p2, q2);
    vec3 ca = mix(p1, q1, st.x), cb = mix(p2, q2, st.y), between = cb - ca;
    float distance = length(between);
    n = vec3(0.0, 1.0, 0.0);
    pa = ca;
    pb = cb;
    if (distance - ra - rb >= margin) return false;
    float size = max(max(length(q1 - p1), length(q2 - p2)), ra + rb);
    if (distance > 1.0e-6 * size) {
        n = between / distance;
    } else {
        vec3 centres = 0.5 * (p2 + q2 - p1 - q1), across = cross(q1 - p1, q2 - p2);
        vec3 d = dot(across, across) > 1.0e-12 * size * size * size * size ? across : centres;
        if (dot(d, d) > 0.0) n = normalize(dot(d, centres) < 0.0 ? -d : d);
    }
    pa = ca + n * ra;
    pb = cb - n * rb;
    return true;
}

// The supports GJK took in np_round_normal (0 where it did not run): round_points keeps them
// in the manifold (axis.y), and round_cull groups the pair by them in the next step.
uint np_round_supports = 0u;

// Where np_round_normal's GJK showed the two shapes farther apart than the margin: the unit
// direction from A to B along which they are (world space; 0 where it did not). round_points
// keeps it (reuse.glsl), and round_cull tries it first in the next step.
vec3 np_round_apart_along = vec3(0.0);

// Normal (A to B) and surface points of two convex shapes: in closed form for a sphere or
// capsule against a capsule, else GJK on the cores and EPA where they overlap. False when
// they are farther apart than the margin (or EPA found nothing); GJK gives up on a pair as
// soon as a support plane shows that.
bool np_round_normal(np_convex world_a, np_convex world_b, float margin, out vec3 n,
                     out vec3 pa, out vec3 pb)
{
    vec3 o = np_core_centre(world_a);
    vec3 p1, q1, p2, q2;
    if (np_core_segment(world_a, o, p1, q1) && np_core_segment(world_b, o, p2, q2)) {
        bool near = np_segments_normal(p1, q1, p2, q2, world_a.radius, world_b.radius, margin,
                                       n, pa, pb);
        pa += o;
        pb += o;
        return near;
    }
    np_convex A = np_convex_moved(world_a, o), B = np_convex_moved(world_b, o);
    np_gjk_result g = np_gjk_within(A, B, A.radius + B.radius + margin,
                                    NP_GJK_CONTACT_TOLERANCE);
    np_round_supports = g.iterations;
    n = vec3(0.0, 1.0, 0.0);
    pa = g.pa;
    pb = g.pb;
    if (g.status == NP_GJK_FAR) {
        np_round_apart_along = -normalize(g.v);   // the direction of its support plane
        return false;
    }
    if (g.status != NP_GJK_OVERLAP && g.distance > 0.0) {
        n = -normalize(g.v);
        if (g.distance - A.radius - B.radius >= margin) {
            np_round_apart_along = n;
            return false;
        }
    } else {
        if (!np_epa_or_touch(g, np_epa(A, B, g.simplex), n, pa, pb)) return false;
        np_keep_shallower_axis(A, B, n, pa, pb);
    }
    pa += o + n * A.radius;
    pb += o - n * B.radius;
    return true;
}

// The radius of a ball about the body origin that holds the shape.
float np_bounding_radius(np_body b)
{
    tb_gpu_shape s = shapes[b.shape];
    return length(s.aabb_center.xyz) + length(s.aabb_half.xyz);
}

// Whether the bounding balls of a and b come within the margin. Most pairs the broadphase
// finds are apart by more than that, and many of them the balls tell, before GJK's loop.
bool np_balls_near(np_body a, np_body b, float margin)
{
    float reach = np_bounding_radius(a) + np_bounding_radius(b) + margin;
    vec3 between = b.pos - a.pos;
    return dot(between, between) <= reach * reach;
}

// Whether a convex shape a and a round shape b (first and second of a pair) are surely
// farther apart than the margin, by what np_round_pair would find first: their bounding
// balls, the closed form of a sphere or capsule against a capsule, or a support plane
// within GJK's first NP_CULL_ITERATIONS supports (the same supports, so the same answer;
// one: more cost more than they cull).
// A plane or a mesh is never culled. narrowphase/round_cull runs it over every round pair
// so that round_points' warps get only pairs with work: a pair that GJK sends away in one
// or two supports otherwise idles in a warp whose other threads build a manifold.
#define NP_CULL_ITERATIONS 1u
bool np_round_apart(np_body a, np_body b, float margin)
{
    uint first = a.type;
    if (first == TB_GPU_SHAPE_PLANE || first == TB_GPU_SHAPE_MESH ||
        first == TB_GPU_SHAPE_HEIGHTFIELD)
        return false;
    if (!np_balls_near(a, b, margin)) return true;
    np_convex A = np_convex_rounded(a), B = np_convex_rounded(b);
    vec3 o = np_core_centre(A);
    vec3 p1, q1, p2, q2, n, pa, pb;
    if (np_core_segment(A, o, p1, q1) && np_core_segment(B, o, p2, q2))
        return !np_segments_normal(p1, q1, p2, q2, A.radius, B.radius, margin, n, pa, pb);
    A = np_convex_moved(A, o);
    B = np_convex_moved(B, o);
    np_gjk_result g = np_gjk_capped(A, B, A.radius + B.radius + margin,
                                    NP_GJK_CONTACT_TOLERANCE, NP_CULL_ITERATIONS);
    return g.status == NP_GJK_FAR ||
           (g.status == NP_GJK_SEPARATED && g.iterations < NP_CULL_ITERATIONS &&
            g.distance - A.radius - B.radius >= margin);
}

// A plane (first) and a round shape: the shape's feature towards the plane, its corners
// measured from the plane.
void np_plane_candidates(np_body plane, np_body b, out vec4 half_space, out uint key,
                         out vec3 normal)
{
    half_space = np_world_plane(plane);
    normal = half_space.xyz;
    np_convex B = np_convex_of(b);
    np_feature f = np_round_feature_of(B, -normal, 0u);
    np_cand_count = 0u;
    for (uint k = 0u; k < f.count; k++) np_cand_add(np_feature_v[f.slot][k], k);
    key = (f.id & 255u) << 14;
}

// One-sided like triangle.glsl: a contact whose normal would not leave the triangle's front,
// or that touches an inactive edge or corner, takes the face normal.
void np_triangle_sided(np_triangle tri, np_convex A, np_convex B, inout vec3 n, inout vec3 pa,
                       inout vec3 pb)
{
    uint feature;
    np_tri_closest(tri, pa, feature);
    vec3 front = tri.normal;
    bool face = dot(n, front) >= 0.9999;
    if (face || (dot(n, front) > 0.0 && np_tri_feature_active(tri, feature))) return;
    n = front;
    vec3 a;
    np_core_supports(A, B, front, a, pb);   // B's farthest along -front
    pb -= front * B.radius;
    pa = pb - front * dot(pb - tri.v0, front);
}

// A round shape b and the first shape of its pair: a convex body a, or (on_mesh) the mesh
// a's triangle tri, where a shape wholly behind the triangle gets nothing. GJK, EPA and the
// manifold are written here once for both: each is a large part of the kernel, and
// lavapipe's compile time grows faster than its size.
bool np_round_pair(np_body a, np_body b, bool on_mesh, np_triangle tri, float margin,
                   out vec4 plane, out uint key, out vec3 normal)
{
    normal = vec3(0.0);
    np_convex A, B = np_convex_rounded(b);
    if (on_mesh) {
        if ((tri.flags & TB_MESH_DEGENERATE) != 0u) return false;
        A = np_convex_of_triangle(a, tri);
        vec3 back, top;
        np_core_supports(A, B, -tri.normal, back, top);   // B's farthest along the front
        if (dot(top - tri.v0, tri.normal) + B.radius < 0.0) return false;
    } else {
        if (!np_balls_near(a, b, margin)) return false;
        A = np_convex_rounded(a);
    }
    vec3 n, pa, pb;
    if (!np_round_normal(A, B, margin, n, pa, pb)) return false;
    if (on_mesh) np_triangle_sided(tri, A, B, n, pa, pb);
    np_round_candidates(A, B, n, pa, pb, margin, plane, key, normal);
    return true;
}

// The contacts of a round shape b with the first shape of its pair a (a plane, a convex
// body, or on_mesh the mesh a's triangle tri), written to t; the normal from a to b. Every
// kind ends in the one reduction below (np_cand_emit, written once).
uint np_round_contacts(np_target t, np_body a, np_body b, bool on_mesh, np_triangle tri,
                       float margin, out vec3 normal)
{
    vec4 plane;
    uint key;
    bool found = true;
    if (a.type == TB_GPU_SHAPE_PLANE) np_plane_candidates(a, b, plane, key, normal);
    else found = np_round_pair(a, b, on_mesh, tri, margin, plane, key, normal);
    return found ? np_cand_emit(t, plane, margin, key) : 0u;
}

#endif
