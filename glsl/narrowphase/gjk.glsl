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
// simplex the sub-algorithm copies about is a third smaller.
struct np_simplex {
    vec3 w[4];      // Minkowski points a - b
    vec3 a[4];      // A's support points
    vec4 lambda;    // barycentric weights of the closest point
    uint n;
};

bool np_same_sign(float x, float y)
{
    return (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0);
}

// The simplex of s's vertices i, j, k (the first n of them).
np_simplex np_simplex_pick(np_simplex s, uint i, uint j, uint k, uint n)
{
    np_simplex t = s;
    uvec3 idx = uvec3(i, j, k);
    for (uint m = 0u; m < n; m++) {
        t.w[m] = s.w[idx[m]];
        t.a[m] = s.a[idx[m]];
    }
    t.n = n;
    return t;
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

// The simplex's closest point to the origin: the weighted sum of its vertices, made
// orthogonal to its edges again. The sum of vertices far from the origin carries their
// rounding (float's epsilon times |w|) in every direction; left in, the part along the
// simplex tilts the direction of v by up to epsilon |w| / |v|, and with it the normal and
// the next support points, which a long face turns into a distance error of that tilt times
// its length. Removed against an orthonormal basis of the edges, twice (once more takes out
// what the first pass rounded), only the error across the simplex stays: the distance's own.
vec3 np_simplex_point(np_simplex s)
{
    vec3 v = vec3(0.0);
    for (uint m = 0u; m < s.n; m++) v += s.lambda[m] * s.w[m];
    if (s.n < 2u || s.n > 3u) return v;
    vec3 e1 = s.w[1] - s.w[0];
    vec3 e2 = s.n == 3u ? s.w[2] - s.w[0] : vec3(0.0);
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

// The weighted sums of the simplex's w and of its a.
vec3 np_simplex_sum(np_simplex s)
{
    vec3 sum = vec3(0.0);
    for (uint m = 0u; m < s.n; m++) sum += s.lambda[m] * s.w[m];
    return sum;
}

vec3 np_simplex_a(np_simplex s)
{
    vec3 sum = vec3(0.0);
    for (uint m = 0u; m < s.n; m++) sum += s.lambda[m] * s.a[m];
    return sum;
}

// Segment w0 w1: the origin's projection on the line, measured along the axis where the
// segment is longest.
np_simplex np_sv_segment(np_simplex s)
{
    vec3 t = s.w[1] - s.w[0];
    float tt = dot(t, t);
    if (tt == 0.0) {
        s.n = 1u;
        s.lambda = vec4(1.0, 0.0, 0.0, 0.0);
        return s;
    }
    vec3 p = s.w[0] - t * (dot(s.w[0], t) / tt);
    vec3 at = abs(t);
    uint k = at.x >= at.y && at.x >= at.z ? 0u : (at.y >= at.z ? 1u : 2u);
    float mu = s.w[0][k] - s.w[1][k];
    float c0 = p[k] - s.w[1][k];    // w0's weight times mu
    float c1 = s.w[0][k] - p[k];    // w1's
    if (np_same_sign(mu, c0) && np_same_sign(mu, c1)) {
        s.lambda = vec4(c0, c1, 0.0, 0.0) / (c0 + c1);
        return s;
    }
    // Beyond an end: that end alone.
    if (!np_same_sign(mu, c0)) s = np_simplex_pick(s, 1u, 0u, 0u, 1u);
    else s.n = 1u;
    s.lambda = vec4(1.0, 0.0, 0.0, 0.0);
    return s;
}

// Twice the signed area of the triangle (p, q, r) in the coordinate plane (x, y).
float np_area2(vec2 p, vec2 q, vec2 r)
{
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
}

// Triangle w0 w1 w2: the origin's projection on its plane, weighed by the areas of the
// triangles it makes with each edge in the coordinate plane where the triangle is largest.
// A weight of the wrong sign puts the projection beyond the opposite edge; the closest of
// those edges' answers wins.
np_simplex np_sv_triangle(np_simplex s)
{
    vec3 n = cross(s.w[1] - s.w[0], s.w[2] - s.w[0]);
    float nn = dot(n, n);
    vec3 p = nn > 0.0 ? n * (dot(s.w[0], n) / nn) : vec3(0.0);
    vec3 an = abs(n);
    // Keep the two axes after the largest one in cyclic order, so the projected area has
    // the sign of that component of n.
    uint k = an.x >= an.y && an.x >= an.z ? 0u : (an.y >= an.z ? 1u : 2u);
    uint i = (k + 1u) % 3u, j = (k + 2u) % 3u;
    vec2 q0 = vec2(s.w[0][i], s.w[0][j]), q1 = vec2(s.w[1][i], s.w[1][j]);
    vec2 q2 = vec2(s.w[2][i], s.w[2][j]), pp = vec2(p[i], p[j]);
    float mu = np_area2(q0, q1, q2);
    vec3 c = vec3(np_area2(pp, q1, q2), np_area2(q0, pp, q2), np_area2(q0, q1, pp));
    if (np_same_sign(mu, c.x) && np_same_sign(mu, c.y) && np_same_sign(mu, c.z)) {
        // Over their own sum, not mu: the areas round with the vertices' size, and for a
        // sliver far from the origin weights that do not sum to one scale v with them.
        s.lambda = vec4(c / (c.x + c.y + c.z), 0.0);
        return s;
    }
    np_simplex best = s;
    float best_d = 3.0e38;
    for (uint m = 0u; m < 3u; m++) {
        if (np_same_sign(mu, c[m])) continue;
        np_simplex e = np_sv_segment(np_simplex_pick(s, (m + 1u) % 3u, (m + 2u) % 3u, 0u, 2u));
        vec3 v = np_simplex_point(e);
        if (dot(v, v) < best_d) {
            best_d = dot(v, v);
            best = e;
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
// ends the search; else the closest of the faces it lies beyond.
np_simplex np_sv_tetrahedron(np_simplex s)
{
    vec3 o = vec3(0.0);
    vec4 c = vec4(np_volume6(o, s.w[1], s.w[2], s.w[3]), np_volume6(s.w[0], o, s.w[2], s.w[3]),
                  np_volume6(s.w[0], s.w[1], o, s.w[3]), np_volume6(s.w[0], s.w[1], s.w[2], o));
    float mu = c.x + c.y + c.z + c.w;
    bool inside = true;
    for (uint m = 0u; m < 4u; m++) inside = inside && np_same_sign(mu, c[m]);
    if (inside) {
        s.lambda = c / mu;
        return s;
    }
    np_simplex best = s;
    float best_d = 3.0e38;
    for (uint m = 0u; m < 4u; m++) {
        if (np_same_sign(mu, c[m])) continue;
        uvec3 f = m == 0u ? uvec3(1u, 2u, 3u)
                : (m == 1u ? uvec3(0u, 2u, 3u) : (m == 2u ? uvec3(0u, 1u, 3u) : uvec3(0u, 1u, 2u)));
        np_simplex e = np_sv_triangle(np_simplex_pick(s, f.x, f.y, f.z, 3u));
        vec3 v = np_simplex_point(e);
        if (dot(v, v) < best_d) {
            best_d = dot(v, v);
            best = e;
        }
    }
    return best;
}

np_simplex np_sv_reduce(np_simplex s)
{
    if (s.n == 4u) return np_sv_tetrahedron(s);
    if (s.n == 3u) return np_sv_triangle(s);
    if (s.n == 2u) return np_sv_segment(s);
    s.lambda = vec4(1.0, 0.0, 0.0, 0.0);
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
np_gjk_result np_gjk_within(np_convex A, np_convex B, float far, float tolerance)
{
    np_gjk_result r;
    np_simplex s;
    s.n = 0u;
    s.lambda = vec4(0.0);
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
    for (it = 0u; it < NP_GJK_ITERATIONS; it++) {
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
        for (uint m = 0u; m < s.n; m++) repeated = repeated || s.w[m] == w;
        // The distance never grows in exact arithmetic: steps that do not shrink it are
        // float noise in the sub-algorithm, and NP_GJK_STALLS of them in a row end the search.
        if (repeated || stalls >= NP_GJK_STALLS) {
            r.status = NP_GJK_SEPARATED;
            break;
        }
        s.w[s.n] = w;
        s.a[s.n] = a;
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

// The distance query's GJK: from the centres, to float's tolerance, to the end.
np_gjk_result np_gjk(np_convex A, np_convex B)
{
    return np_gjk_within(A, B, -1.0, NP_GJK_TOLERANCE);
}

#endif
