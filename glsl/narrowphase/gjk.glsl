// GJK distance between the cores of two convex shapes (convex.glsl), with the signed-volume
// sub-algorithm of Montanari, Petrinic and Barbieri ("Improving the GJK algorithm for faster
// and more reliable distance queries between convex objects", ACM TOG 2017) in place of
// Johnson's: the simplex's closest point to the origin is found from signed volumes of the
// simplex and its faces projected where they are largest, so no Cramer's determinants of
// nearly dependent dot products are formed, and the search for the closest sub-simplex
// only visits the faces the origin lies beyond.
//
// The search runs on the Minkowski difference A - B: each simplex vertex w = a - b keeps
// its two support points a and b, and the closest points of the shapes are the same
// barycentric sums of them. It ends when a new support point gets no closer than the
// current one (the distance is found), when the simplex holds the origin or the distance is
// within float noise of zero (the cores overlap: EPA's business), or after
// NP_GJK_ITERATIONS with the best point found so far (status NP_GJK_LIMIT).
#ifndef TB_NP_GJK_GLSL
#define TB_NP_GJK_GLSL

#define NP_GJK_ITERATIONS 32u
#define NP_GJK_SEPARATED 0u
#define NP_GJK_OVERLAP 1u
#define NP_GJK_LIMIT 2u
#define NP_GJK_STALLS 3u
#define NP_GJK_FAR 4u         // status: a support plane shows the cores farther than asked
#define NP_GJK_TOLERANCE 1.0e-6   // queries: converged when |v|^2 - v.w is within it of |v|^2
#define NP_GJK_LOOSE 1.0e-5   // relative gap still taken as converged at the limit

// B's support points are not kept: b = a - w wherever one is needed (EPA's start), so the
// simplex is a third smaller. Every index into w, a and lambda is a constant once loops are
// unrolled (vertices are picked by selects, never by a computed index), so the simplex
// stays in registers: indexed by a variable, a GPU compiler puts private arrays in memory.
struct np_simplex {
    vec3 w[4];      // Minkowski points a - b (slots n..3 unused, finite)
    vec3 a[4];      // A's support points
    vec4 lambda;    // barycentric weights of the closest point (zero beyond n)
    uint n;
};

bool np_same_sign(float x, float y)
{
    return (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0);
}

// Component i of v by selects, as np_comp (manifold.glsl) for a vec3: a component picked by
// a computed index is a private array the GPU compiler keeps in memory.
float np_comp4(vec4 v, uint i)
{
    return i == 0u ? v.x : (i == 1u ? v.y : (i == 2u ? v.z : v.w));
}

// Vertex i (0-3) of four, by selects.
vec3 np_pick(vec3 p0, vec3 p1, vec3 p2, vec3 p3, uint i)
{
    return i == 0u ? p0 : (i == 1u ? p1 : (i == 2u ? p2 : p3));
}

// v less its part along the unit vector u, when u is one (a zero u removes nothing).
vec3 np_reject(vec3 v, vec3 u)
{
    return v - u * dot(v, u);
}

vec3 np_unit_or_zero(vec3 e)
{
    float ee = dot(e, e);
    return ee > 0.0 ? e * inversesqrt(ee) : vec3(0.0);
}

// The closest point to the origin of the simplex p (n of 1-3 vertices, weights l): the
// weighted sum of its vertices, made orthogonal to its edges again. The sum of vertices far
// from the origin carries their rounding (float's epsilon times |w|) in every direction;
// left in, the part along the simplex tilts the direction of v by up to epsilon |w| / |v|,
// and with it the normal and the next support points, which a long face turns into a
// distance error of that tilt times its length. Removed against an orthonormal basis of the
// edges, twice (once more takes out what the first pass rounded), only the error across the
// simplex stays: the distance's own.
vec3 np_simplex_point_of(vec3 p0, vec3 p1, vec3 p2, vec3 l, uint n)
{
    vec3 v = l.x * p0 + l.y * p1 + l.z * p2;
    if (n < 2u || n > 3u) return v;
    vec3 e1 = p1 - p0;
    vec3 e2 = n == 3u ? p2 - p0 : vec3(0.0);
    if (dot(e2, e2) > dot(e1, e1)) {
        vec3 t = e1;
        e1 = e2;
        e2 = t;
    }
    vec3 u1 = np_unit_or_zero(e1);
    vec3 u2 = np_unit_or_zero(np_reject(np_reject(e2, u1), u1));
    for (uint pass = 0u; pass < 2u; pass++) v = np_reject(np_reject(v, u1), u2);
    return v;
}

// The weighted sums of the simplex's w and of its a (weights beyond n are zero).
vec3 np_simplex_sum(np_simplex s)
{
    return s.lambda.x * s.w[0] + s.lambda.y * s.w[1] + s.lambda.z * s.w[2] + s.lambda.w * s.w[3];
}

vec3 np_simplex_a(np_simplex s)
{
    return s.lambda.x * s.a[0] + s.lambda.y * s.a[1] + s.lambda.z * s.a[2] + s.lambda.w * s.a[3];
}

vec3 np_simplex_point(np_simplex s)
{
    if (s.n == 4u) return np_simplex_sum(s);
    return np_simplex_point_of(s.w[0], s.w[1], s.w[2], s.lambda.xyz, s.n);
}

// The sub-algorithm gives weights over the vertices it was handed, zero for those it drops
// (a drop mask beside them, as weights may round to zero): the simplex is then packed once,
// in the GJK loop, instead of copied at every sub-simplex tried.

// Segment p q: the origin's projection on the line, measured along the axis where the
// segment is longest. Weights of p and q; keep: which of them stay (bits 0, 1).
vec2 np_sv_segment(vec3 p, vec3 q, out uint keep)
{
    vec3 t = q - p;
    float tt = dot(t, t);
    keep = 1u;
    if (tt == 0.0) return vec2(1.0, 0.0);
    vec3 x = p - t * (dot(p, t) / tt);
    vec3 at = abs(t);
    uint k = at.x >= at.y && at.x >= at.z ? 0u : (at.y >= at.z ? 1u : 2u);
    float pk = np_comp(p, k), qk = np_comp(q, k), xk = np_comp(x, k);
    float mu = pk - qk;
    float c0 = xk - qk;    // p's weight times mu
    float c1 = pk - xk;    // q's
    if (np_same_sign(mu, c0) && np_same_sign(mu, c1)) {
        keep = 3u;
        return vec2(c0, c1) / (c0 + c1);
    }
    // Beyond an end: that end alone.
    if (!np_same_sign(mu, c0)) {
        keep = 2u;
        return vec2(0.0, 1.0);
    }
    return vec2(1.0, 0.0);
}

// Twice the signed area of the triangle (p, q, r) in the coordinate plane (x, y).
float np_area2(vec2 p, vec2 q, vec2 r)
{
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
}

// Triangle p0 p1 p2: the origin's projection on its plane, weighed by the areas of the
// triangles it makes with each edge in the coordinate plane where the triangle is largest.
// A weight of the wrong sign puts the projection beyond the opposite edge; the closest of
// those edges' answers wins. Weights of the three; keep: bits of those that stay.
vec3 np_sv_triangle(vec3 p0, vec3 p1, vec3 p2, out uint keep)
{
    vec3 n = cross(p1 - p0, p2 - p0);
    float nn = dot(n, n);
    vec3 p = nn > 0.0 ? n * (dot(p0, n) / nn) : vec3(0.0);
    vec3 an = abs(n);
    // Keep the two axes after the largest one in cyclic order, so the projected area has
    // the sign of that component of n.
    uint k = an.x >= an.y && an.x >= an.z ? 0u : (an.y >= an.z ? 1u : 2u);
    uint i = (k + 1u) % 3u, j = (k + 2u) % 3u;
    vec2 q0 = vec2(np_comp(p0, i), np_comp(p0, j)), q1 = vec2(np_comp(p1, i), np_comp(p1, j));
    vec2 q2 = vec2(np_comp(p2, i), np_comp(p2, j)), pp = vec2(np_comp(p, i), np_comp(p, j));
    float mu = np_area2(q0, q1, q2);
    vec3 c = vec3(np_area2(pp, q1, q2), np_area2(q0, pp, q2), np_area2(q0, q1, pp));
    keep = 7u;
    // Over their own sum, not mu: the areas round with the vertices' size, and for a
    // sliver far from the origin weights that do not sum to one scale v with them.
    if (np_same_sign(mu, c.x) && np_same_sign(mu, c.y) && np_same_sign(mu, c.z))
        return c / (c.x + c.y + c.z);
    keep = 1u;
    vec3 best = vec3(1.0, 0.0, 0.0);
    float best_d = 3.0e38;
    for (uint m = 0u; m < 3u; m++) {
        if (np_same_sign(mu, np_comp(c, m))) continue;
        // The edge opposite vertex m: its next two, in cyclic order.
        uint e0 = (m + 1u) % 3u, e1 = (m + 2u) % 3u;
        vec3 a = np_pick(p0, p1, p2, p2, e0), b = np_pick(p0, p1, p2, p2, e1);
        uint edge_keep;
        vec2 l = np_sv_segment(a, b, edge_keep);
        bool both = edge_keep == 3u;
        vec3 v = np_simplex_point_of(edge_keep == 2u ? b : a, b, b, both ? vec3(l, 0.0) : vec3(1.0, 0.0, 0.0), both ? 2u : 1u);
        if (dot(v, v) < best_d) {
            best_d = dot(v, v);
            best = vec3(e0 == 0u ? l.x : (e1 == 0u ? l.y : 0.0),
                        e0 == 1u ? l.x : (e1 == 1u ? l.y : 0.0),
                        e0 == 2u ? l.x : (e1 == 2u ? l.y : 0.0));
            keep = (edge_keep & 1u) << e0 | (edge_keep >> 1u) << e1;
        }
    }
    return best;
}

// Signed volume of the tetrahedron (p, q, r, o), six times over.
float np_volume6(vec3 p, vec3 q, vec3 r, vec3 o)
{
    return dot(q - p, cross(r - p, o - p));
}

// Tetrahedron w0..w3: the origin inside it (every weight of the sign of the whole volume)
// ends the search; else the closest of the faces it lies beyond. Weights of the four; keep:
// bits of those that stay.
vec4 np_sv_tetrahedron(vec3 w0, vec3 w1, vec3 w2, vec3 w3, out uint keep)
{
    vec3 o = vec3(0.0);
    vec4 c = vec4(np_volume6(o, w1, w2, w3), np_volume6(w0, o, w2, w3),
                  np_volume6(w0, w1, o, w3), np_volume6(w0, w1, w2, o));
    float mu = c.x + c.y + c.z + c.w;
    bool inside = true;
    [[unroll]] for (uint m = 0u; m < 4u; m++) inside = inside && np_same_sign(mu, c[m]);
    keep = 15u;
    if (inside) return c / mu;
    keep = 1u;
    vec4 best = vec4(1.0, 0.0, 0.0, 0.0);
    float best_d = 3.0e38;
    for (uint m = 0u; m < 4u; m++) {
        if (np_same_sign(mu, np_comp4(c, m))) continue;
        // The face without vertex m, its vertices in their order.
        uint f0 = m == 0u ? 1u : 0u, f1 = m <= 1u ? 2u : 1u, f2 = m <= 2u ? 3u : 2u;
        vec3 p0 = np_pick(w0, w1, w2, w3, f0), p1 = np_pick(w0, w1, w2, w3, f1);
        vec3 p2 = np_pick(w0, w1, w2, w3, f2);
        uint face_keep;
        vec3 l = np_sv_triangle(p0, p1, p2, face_keep);
        // The kept vertices packed, as the point is taken from them.
        uint count = bitCount(face_keep);
        vec3 k0 = (face_keep & 1u) != 0u ? p0 : ((face_keep & 2u) != 0u ? p1 : p2);
        vec3 k1 = (face_keep & 3u) == 3u ? p1 : p2;
        float l0 = (face_keep & 1u) != 0u ? l.x : ((face_keep & 2u) != 0u ? l.y : l.z);
        float l1 = (face_keep & 3u) == 3u ? l.y : l.z;
        vec3 v = np_simplex_point_of(k0, k1, p2, vec3(l0, count > 1u ? l1 : 0.0, count > 2u ? l.z : 0.0), count);
        if (dot(v, v) < best_d) {
            best_d = dot(v, v);
            // The face's vertices f0 < f1 < f2 are three of the four, all but m.
            best = m == 0u ? vec4(0.0, l) : (m == 1u ? vec4(l.x, 0.0, l.yz)
                 : (m == 2u ? vec4(l.xy, 0.0, l.z) : vec4(l, 0.0)));
            keep = (face_keep & 1u) << f0 | ((face_keep >> 1u) & 1u) << f1 | (face_keep >> 2u) << f2;
        }
    }
    return best;
}

// The simplex reduced to the sub-simplex nearest the origin, packed into its first slots
// (in their order) with its weights.
np_simplex np_sv_reduce(np_simplex s)
{
    uint keep = 1u;
    vec4 l = vec4(1.0, 0.0, 0.0, 0.0);
    if (s.n == 4u) l = np_sv_tetrahedron(s.w[0], s.w[1], s.w[2], s.w[3], keep);
    else if (s.n == 3u) l.xyz = np_sv_triangle(s.w[0], s.w[1], s.w[2], keep);
    else if (s.n == 2u) l.xy = np_sv_segment(s.w[0], s.w[1], keep);
    // Pack: slot m moves down to the count of kept slots before it (never up).
    uint n = 0u;
    [[unroll]] for (uint m = 0u; m < 4u; m++) {
        if ((keep & (1u << m)) == 0u) continue;
        [[unroll]] for (uint j = 0u; j < m; j++) {
            if (j != n) continue;
            s.w[j] = s.w[m];
            s.a[j] = s.a[m];
            l[j] = l[m];
        }
        n++;
    }
    [[unroll]] for (uint m = 1u; m < 4u; m++) l[m] = m < n ? l[m] : 0.0;
    s.lambda = l;
    s.n = n;
    return s;
}

struct np_gjk_result {
    uint status;        // NP_GJK_*
    float distance;     // between the cores (0 when they overlap)
    vec3 pa, pb;        // closest points of the cores, world space
    vec3 v;             // pa - pb as the simplex gives it: its direction is better than
                        // that of the points' difference, rounded at the points' size
    np_simplex simplex; // the last simplex (EPA starts from it)
    uint iterations;
};

// GJK converged when |v|^2 - v.w <= tolerance |v|^2. With far >= 0 it gives up as soon as a
// support plane shows the cores more than `far` apart (status NP_GJK_FAR, distance that
// lower bound, v the separating direction, no points): contacts ask only whether the shapes
// come within their margin, and for many of the broadphase's pairs an early support plane
// already says no.
// At most `iterations` (NP_GJK_ITERATIONS or fewer) supports.
np_gjk_result np_gjk_capped(np_convex A, np_convex B, float far, float tolerance,
                            uint iterations)
{
    np_gjk_result r;
    np_simplex s;
    s.n = 0u;
    s.lambda = vec4(0.0);
    [[unroll]] for (uint m = 0u; m < 4u; m++) s.w[m] = s.a[m] = vec3(0.0);
    vec3 v = np_core_centre(A) - np_core_centre(B);
    if (dot(v, v) == 0.0) v = vec3(1.0, 0.0, 0.0);
    r.status = NP_GJK_LIMIT;
    float scale = 0.0;   // the largest |w|^2 seen: the size the float noise scales with
    // The best-bounded simplex's answer (not the simplex itself, which the loop would carry
    // as a second copy): its point v, its weighted sum of w and of a.
    vec3 best_v = vec3(0.0), best_sum = vec3(0.0), best_pa = vec3(0.0);
    float best_gap = 3.0e38;
    float least = 3.0e38;   // the smallest |v|^2 so far
    uint stalls = 0u;
    uint it;
    for (it = 0u; it < iterations; it++) {
        // Supports along the unit v: the shapes' tests of a direction's size (a rim's
        // direction near a cylinder's axis) are then relative, however short v has become.
        float vv = dot(v, v);
        vec3 u = v * inversesqrt(vv);
        vec3 a, b;
        np_core_supports(A, B, -u, a, b);
        vec3 w = a - b;
        if (far >= 0.0 && dot(u, w) > far) {
            r.status = NP_GJK_FAR;
            r.distance = dot(u, w);
            r.v = v;
            r.pa = r.pb = vec3(0.0);
            r.simplex = s;
            r.iterations = it + 1u;
            return r;
        }
        scale = max(scale, dot(w, w));
        // |v| bounds the distance from above and v.w / |v| from below: their gap is how far
        // this simplex's answer (distance and direction) can be off. The simplex with the
        // smallest gap is the answer, whichever way the search ends.
        float gap = (vv - dot(v, w)) * inversesqrt(vv);
        if (s.n > 0u && gap < best_gap) {
            best_gap = gap;
            best_v = v;
            best_sum = np_simplex_sum(s);
            best_pa = np_simplex_a(s);
        }
        // No closer than v along v: v is the distance (within the tolerance).
        if (s.n > 0u && vv - dot(v, w) <= tolerance * vv) {
            r.status = NP_GJK_SEPARATED;
            break;
        }
        bool repeated = false;
        [[unroll]] for (uint m = 0u; m < 4u; m++) repeated = repeated || (m < s.n && s.w[m] == w);
        // The distance never grows in exact arithmetic: steps that do not shrink it are
        // float noise in the sub-algorithm, and NP_GJK_STALLS of them in a row end the search.
        if (repeated || stalls >= NP_GJK_STALLS) {
            r.status = NP_GJK_SEPARATED;
            break;
        }
        [[unroll]] for (uint m = 0u; m < 4u; m++) {
            s.w[m] = m == s.n ? w : s.w[m];
            s.a[m] = m == s.n ? a : s.a[m];
        }
        s.n++;
        s = np_sv_reduce(s);
        vec3 next = np_simplex_point(s);
        if (s.n == 4u || dot(next, next) <= 1.0e-14 * scale) {
            r.status = NP_GJK_OVERLAP;
            it++;
            break;
        }
        stalls = dot(next, next) >= least ? stalls + 1u : 0u;
        least = min(least, dot(next, next));
        v = next;
    }
    // Separated (or out of iterations): the best-bounded simplex's answer; overlapping: the
    // last simplex's, which EPA starts from.
    bool use_best = r.status != NP_GJK_OVERLAP && best_gap < 3.0e38;
    vec3 last = use_best ? best_v : np_simplex_point(s);
    vec3 sum = use_best ? best_sum : np_simplex_sum(s);
    r.pa = use_best ? best_pa : np_simplex_a(s);
    // Curved against curved (a rim on a cone's side) converges slowly: out of iterations
    // with the gap within NP_GJK_LOOSE of the distance, the answer is as good as separated.
    if (r.status == NP_GJK_LIMIT && best_gap <= NP_GJK_LOOSE * length(last))
        r.status = NP_GJK_SEPARATED;
    // v's direction from np_simplex_point, its length from the weighted sum itself, a point
    // of the simplex: never short of the distance, where a sliver's edge basis might tilt
    // out of its plane and cut v short.
    if (dot(last, last) > 0.0) last *= sqrt(dot(sum, sum) / dot(last, last));
    // Stopped with the origin within float noise of the simplex (no support point is new,
    // or none gets closer): the cores touch or overlap, and EPA decides which (from the last
    // simplex: it holds the newest support points).
    if (r.status != NP_GJK_OVERLAP && dot(last, last) <= 1.0e-10 * scale) r.status = NP_GJK_OVERLAP;
    r.iterations = it;
    r.simplex = s;
    // b's point is a's less v, not b's own weighted sum: the weights carry the rounding of
    // the sub-algorithm along the simplex, which moves the two sums apart across v (it
    // tilts their difference; see np_simplex_point), while v is clean of it. Precise, so
    // that no compiler folds pa - pb back into v: the distance and direction taken from
    // the points must be the points' own.
    precise vec3 pb = r.pa - last;
    r.pb = pb;
    r.v = last;
    r.distance = r.status == NP_GJK_OVERLAP ? 0.0 : length(r.pa - r.pb);
    return r;
}

np_gjk_result np_gjk_within(np_convex A, np_convex B, float far, float tolerance)
{
    return np_gjk_capped(A, B, far, tolerance, NP_GJK_ITERATIONS);
}

// The distance query's GJK: from the centres, to float's tolerance, to the end.
np_gjk_result np_gjk(np_convex A, np_convex B)
{
    return np_gjk_within(A, B, -1.0, NP_GJK_TOLERANCE);
}

#endif
