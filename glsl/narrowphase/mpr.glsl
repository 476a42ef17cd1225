// Penetration of two overlapping cores (convex.glsl) by Minkowski portal refinement (Gary
// Snethen's XenoCollide, Game Programming Gems 7): the alternative to EPA (epa.glsl) that
// distance queries may choose.
//
// MPR follows one ray through the Minkowski difference A - B: from an interior point w0 (the
// centre of A less the centre of B) through the origin, out to the surface. Portal discovery
// finds three support points w1, w2, w3 whose triangle (the portal) the ray crosses;
// refinement replaces one of them at a time by the support point along the portal's normal,
// keeping the ray inside the cone from w0 through the portal, until that support point lies
// on the portal (within a float tolerance). The portal is then a patch of the surface where
// the ray leaves it: its normal is the answer's, the origin's distance to its plane the depth,
// and the barycentric weights of the origin's projection on it give the witness points.
//
// What it measures is therefore the overlap along the direction in which the ray leaves,
// not the least overlap over all directions, which is the penetration depth: the two agree
// where the line between the centres crosses the surface at right angles (a ball, a face met
// head on) and MPR's depth is the larger otherwise, an upper bound where EPA's is a lower
// one. In exchange it keeps no polytope: five support points in private memory, a few
// cross products an iteration, and no search over faces.
//
// The side tests use det(p, q, w0) = dot(cross(p, q), w0), which is negative when the origin
// lies on the inner side of the plane through w0, p and q; the portal is wound so that this
// holds for (w1, w2), (w2, w3) and (w3, w1), which is what "the ray crosses the portal"
// means, and its normal cross(w2 - w1, w3 - w1) then points away from w0.
#ifndef TB_NP_MPR_GLSL
#define TB_NP_MPR_GLSL

#define NP_MPR_ITERATIONS 32u
#define NP_MPR_PORTAL 0u    // discovery found a portal
#define NP_MPR_ON_RAY 1u    // w1 lies on the ray: the surface is met there, at right angles
#define NP_MPR_NONE 2u      // the origin is not strictly inside (touching), or no portal

struct np_mpr_result {
    bool found;         // a depth was found; else, when the normal is not zero, the cores touch
    vec3 normal;        // unit, from A to B: moving B along it parts the cores
    float depth;        // of the cores
    vec3 pa, pb;        // witness points on the cores
    uint iterations;    // of discovery and refinement together
};

// Slot 0 the interior point, 1 to 3 the portal, 4 the newest support point.
vec3 np_mpr_w[5];
vec3 np_mpr_a[5];
vec3 np_mpr_b[5];
uint np_mpr_iterations;

// The support point of A - B along d into slot m. The direction is made unit first: the
// round shapes' rims (np_rim) tell a zero direction by an absolute length.
void np_mpr_support(np_convex A, np_convex B, uint m, vec3 d)
{
    d = normalize(d);
    np_core_supports(A, B, d, np_mpr_a[m], np_mpr_b[m]);
    np_mpr_w[m] = np_mpr_a[m] - np_mpr_b[m];
}

void np_mpr_move(uint from, uint to)
{
    np_mpr_w[to] = np_mpr_w[from];
    np_mpr_a[to] = np_mpr_a[from];
    np_mpr_b[to] = np_mpr_b[from];
}

// det(p, q, w0): negative when the origin is on the inner side of the plane (w0, p, q).
float np_mpr_side(vec3 p, vec3 q)
{
    return dot(cross(p, q), np_mpr_w[0]);
}

// Portal discovery. The ray leaves from w0; where the centres coincide, any ray will do, and
// w0 is moved back along it by a small part of the shapes' reach so that the side tests,
// which all measure against w0, keep a direction to measure.
uint np_mpr_discover(np_convex A, np_convex B)
{
    np_mpr_a[0] = np_core_centre(A);
    np_mpr_b[0] = np_core_centre(B);
    np_mpr_w[0] = np_mpr_a[0] - np_mpr_b[0];
    vec3 w0 = np_mpr_w[0];
    vec3 ray = dot(w0, w0) > 0.0 ? normalize(-w0) : vec3(1.0, 0.0, 0.0);
    np_mpr_support(A, B, 1u, ray);
    float reach = dot(np_mpr_w[1] - w0, ray);
    if (length(w0) < 1.0e-5 * reach) np_mpr_w[0] = w0 = -1.0e-5 * reach * ray;
    // The support point along the ray short of the origin: the origin is not inside.
    if (!(dot(np_mpr_w[1], ray) > 0.0)) return NP_MPR_NONE;
    vec3 w1 = np_mpr_w[1];
    vec3 n = cross(w1, w0);
    if (dot(n, n) <= 1.0e-10 * dot(w1, w1) * dot(w0, w0)) return NP_MPR_ON_RAY;
    // The plane of w0, w1 and the origin; a support point off it on either side makes a
    // face (w0, w1, w2) with the origin on one side of it. A difference lying in that plane
    // (two crossing segments, a segment and a point) has none: no portal.
    np_mpr_support(A, B, 2u, n);
    if (!(dot(np_mpr_w[2], n) > 0.0)) return NP_MPR_NONE;
    if (np_mpr_side(np_mpr_w[1], np_mpr_w[2]) > 0.0) {
        np_mpr_move(1u, 3u);
        np_mpr_move(2u, 1u);
        np_mpr_move(3u, 2u);
    }
    // Search along the face's normal towards the origin for w3; where the origin lies beyond
    // one of the new side planes, w3 takes the place of the vertex opposite that plane's edge
    // and the search goes on from the new face.
    for (; np_mpr_iterations < NP_MPR_ITERATIONS; np_mpr_iterations++) {
        n = cross(np_mpr_w[1] - w0, np_mpr_w[2] - w0);
        if (!(dot(n, n) > 0.0)) return NP_MPR_NONE;
        np_mpr_support(A, B, 3u, n);
        if (!(dot(np_mpr_w[3], n) > 0.0)) return NP_MPR_NONE;
        if (np_mpr_side(np_mpr_w[3], np_mpr_w[1]) > 0.0) np_mpr_move(3u, 2u);
        else if (np_mpr_side(np_mpr_w[2], np_mpr_w[3]) > 0.0) np_mpr_move(3u, 1u);
        else return NP_MPR_PORTAL;
    }
    return NP_MPR_NONE;
}

// The portal's unit normal, away from w0; zero for a portal of no area.
vec3 np_mpr_normal()
{
    vec3 n = cross(np_mpr_w[2] - np_mpr_w[1], np_mpr_w[3] - np_mpr_w[1]);
    float len = length(n);
    return len > 0.0 ? n / len : vec3(0.0);
}

// Portal refinement: the support point w4 along the portal's normal, and the one of the
// three portals of the fan (w4 with an edge of the old portal) that the ray crosses. Which
// one is told by the sides of the old vertices of the plane through the ray and w4: the ray
// leaves through the edge whose ends lie on opposite sides of it the way round the winding
// goes, and w4 replaces the third vertex.
void np_mpr_refine(np_convex A, np_convex B, float size)
{
    for (; np_mpr_iterations < NP_MPR_ITERATIONS; np_mpr_iterations++) {
        vec3 n = np_mpr_normal();
        if (n == vec3(0.0)) return;
        np_mpr_support(A, B, 4u, n);
        float depth = dot(n, np_mpr_w[1]);
        float gain = dot(n, np_mpr_w[4]) - depth;
        if (gain <= 1.0e-5 * size + 1.0e-4 * abs(depth)) return;
        vec3 c = cross(np_mpr_w[4], np_mpr_w[0]);
        float s1 = dot(np_mpr_w[1], c), s2 = dot(np_mpr_w[2], c), s3 = dot(np_mpr_w[3], c);
        if (s1 > 0.0) np_mpr_move(4u, s2 > 0.0 ? 1u : 3u);
        else np_mpr_move(4u, s3 > 0.0 ? 2u : 1u);
    }
}

// The answer along unit n from the support points in slots `v` (barycentric weights `l`).
np_mpr_result np_mpr_answer(vec3 n, float depth, uvec3 v, vec3 l)
{
    np_mpr_result r;
    r.found = true;
    r.normal = n;
    r.depth = max(depth, 0.0);
    r.pa = l.x * np_mpr_a[v.x] + l.y * np_mpr_a[v.y] + l.z * np_mpr_a[v.z];
    r.pb = l.x * np_mpr_b[v.x] + l.y * np_mpr_b[v.y] + l.z * np_mpr_b[v.z];
    r.iterations = np_mpr_iterations;
    return r;
}

// The final portal's answer: the origin's projection p on its plane, weighted by the
// sub-triangles' areas along n (as EPA's face). Weights outside [0, 1] (p beyond the portal,
// on a face met at a slant) keep pb - pa = -depth n, so the points and the depth agree.
np_mpr_result np_mpr_portal_answer(vec3 n)
{
    vec3 w1 = np_mpr_w[1], w2 = np_mpr_w[2], w3 = np_mpr_w[3];
    float depth = dot(n, w1 + w2 + w3) / 3.0;
    vec3 p = n * depth;
    vec3 l = vec3(dot(cross(w2 - p, w3 - p), n), dot(cross(w3 - p, w1 - p), n),
                  dot(cross(w1 - p, w2 - p), n));
    float sum = l.x + l.y + l.z;
    l = sum != 0.0 ? l / sum : vec3(1.0 / 3.0);
    return np_mpr_answer(n, depth, uvec3(1u, 2u, 3u), l);
}

np_mpr_result np_mpr(np_convex A, np_convex B)
{
    np_mpr_result r;
    r.found = false;
    r.normal = vec3(0.0);
    r.depth = 0.0;
    r.pa = r.pb = vec3(0.0);
    np_mpr_iterations = 0u;
    uint found = np_mpr_discover(A, B);
    r.iterations = np_mpr_iterations;
    if (found == NP_MPR_NONE) return r;
    float size = length(np_mpr_w[0]);
    for (uint m = 1u; m < (found == NP_MPR_ON_RAY ? 2u : 4u); m++)
        size = max(size, length(np_mpr_w[m]));
    if (found == NP_MPR_ON_RAY) {
        vec3 n = normalize(-np_mpr_w[0]);
        r = np_mpr_answer(n, dot(n, np_mpr_w[1]), uvec3(1u), vec3(1.0, 0.0, 0.0));
    } else {
        np_mpr_refine(A, B, size);
        vec3 n = np_mpr_normal();
        if (n == vec3(0.0)) return r;
        r = np_mpr_portal_answer(n);
    }
    // A portal with the origin on or beyond it (cores that only touch, within float noise):
    // no depth, but its normal is still the touching direction, as EPA's nearest face.
    r.found = r.depth > 1.0e-6 * size;
    return r;
}

#endif
