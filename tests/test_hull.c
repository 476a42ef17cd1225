/* Host convex hulls (src/geom/hull.c): topology, merged faces and mass properties against
 * closed forms, checked on boxes, tetrahedra, cylinders and random clouds; bad input is
 * rejected with a message and the output left alone. No GPU is used. */
#include "harness.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/hull.h"

#define MAX_POINTS 4096
#define PI 3.14159265358979323846
static float pts[MAX_POINTS][3];

/* ---- helpers -------------------------------------------------------------------------- */

/* Rotate v by the unit quaternion q (x, y, z, w), or by its inverse. */
static void qrot(const double q[4], int inverse, const double v[3], double out[3])
{
    double x = inverse ? -q[0] : q[0], y = inverse ? -q[1] : q[1], z = inverse ? -q[2] : q[2];
    double w = q[3];
    double t[3] = { 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0]) };
    out[0] = v[0] + w * t[0] + (y * t[2] - z * t[1]);
    out[1] = v[1] + w * t[1] + (z * t[0] - x * t[2]);
    out[2] = v[2] + w * t[2] + (x * t[1] - y * t[0]);
}

/* An input point in the hull's principal frame. */
static void to_principal(const tb_hull* h, const float p[3], double out[3])
{
    double d[3] = { p[0] - h->center[0], p[1] - h->center[1], p[2] - h->center[2] };
    qrot(h->rotation, 1, d, out);
}

/* The same tolerance the library uses (3 float epsilons of the centred cloud's extent). */
static double cloud_eps(const float (*p)[3], int n)
{
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = p[0][k];
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) { lo[k] = fmin(lo[k], p[i][k]); hi[k] = fmax(hi[k], p[i][k]); }
    return 3 * FLT_EPSILON * 0.5 * ((hi[0] - lo[0]) + (hi[1] - lo[1]) + (hi[2] - lo[2]));
}

static void build_ok(const float (*p)[3], int n, tb_hull* h)
{
    char err[256] = "";
    if (tb_hull_build(&p[0][0], (uint32_t)n, h, err, sizeof err) != 0)
        fail_msg("tb_hull_build of %d points failed: %s", n, err);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void vert(const tb_hull* h, uint32_t i, double v[3])
{
    for (int k = 0; k < 3; k++) v[k] = h->vertices[i][k];
}

static void plane(const tb_hull* h, uint32_t f, double n[3], double* d)
{
    for (int k = 0; k < 3; k++) n[k] = h->planes[f][k];
    *d = h->planes[f][3];
}

static uint32_t face_vertex(const tb_hull* h, uint32_t f, uint32_t i)
{
    return h->indices[h->faces[f].first + i % h->faces[f].count];
}

/* Volume from the face planes alone: sum of area * offset / 3 (divergence theorem). */
static double volume_from_faces(const tb_hull* h)
{
    double vol = 0;
    for (uint32_t f = 0; f < h->face_count; f++) {
        double n[3], d, s[3] = { 0, 0, 0 };
        plane(h, f, n, &d);
        for (uint32_t i = 0; i < h->faces[f].count; i++) {
            double a[3], b[3];
            vert(h, face_vertex(h, f, i), a);
            vert(h, face_vertex(h, f, i + 1), b);
            s[0] += a[1] * b[2] - a[2] * b[1];
            s[1] += a[2] * b[0] - a[0] * b[2];
            s[2] += a[0] * b[1] - a[1] * b[0];
        }
        vol += 0.5 * dot3(s, n) * d / 3;
    }
    return vol;
}

/* Clouds with noise about as large as the tolerance may keep corners that are straight
 * within it; the other tests ask for strictly convex faces. */
static int strict_convexity = 1;

/* Each face: unit normal, vertices on its plane, strictly convex counter-clockwise loop. */
static void check_faces(const tb_hull* h, double tol)
{
    for (uint32_t f = 0; f < h->face_count; f++) {
        double n[3], d;
        plane(h, f, n, &d);
        assert_true(h->faces[f].count >= 3);
        th_assert_near(sqrt(dot3(n, n)), 1.0, 1e-6, 0);
        for (uint32_t i = 0; i < h->faces[f].count; i++) {
            double a[3], b[3], c[3], e[3], g[3], t[3];
            vert(h, face_vertex(h, f, i), a);
            vert(h, face_vertex(h, f, i + 1), b);
            vert(h, face_vertex(h, f, i + 2), c);
            if (fabs(dot3(n, a) - d) > tol) fail_msg("face %u vertex %u off its plane by %g", f, i, dot3(n, a) - d);
            for (int k = 0; k < 3; k++) { e[k] = b[k] - a[k]; g[k] = c[k] - b[k]; }
            t[0] = e[1] * g[2] - e[2] * g[1];
            t[1] = e[2] * g[0] - e[0] * g[2];
            t[2] = e[0] * g[1] - e[1] * g[0];
            /* The turn at b, as a distance of c from line ab: positive beyond rounding
             * (strictly convex), or at least not negative beyond the tolerance. */
            double turn = dot3(t, n) / sqrt(dot3(e, e));
            double least = strict_convexity ? 1e-7 * (1 + fabs(d)) : -tol;
            if (!(turn > least)) fail_msg("face %u is not convex at vertex %u (turn %g)", f, i + 1, turn);
        }
    }
}

/* Each edge once; left runs v0 -> v1, right v1 -> v0; every face side is an edge. */
static void check_edges(const tb_hull* h)
{
    assert_int_equal(h->edge_count * 2, h->index_count);
    for (uint32_t e = 0; e < h->edge_count; e++) {
        const tb_hull_edge* ed = &h->edges[e];
        assert_true(ed->left < h->face_count && ed->right < h->face_count && ed->left != ed->right);
        int in_left = 0, in_right = 0;
        for (uint32_t i = 0; i < h->faces[ed->left].count; i++)
            in_left += face_vertex(h, ed->left, i) == ed->v0 && face_vertex(h, ed->left, i + 1) == ed->v1;
        for (uint32_t i = 0; i < h->faces[ed->right].count; i++)
            in_right += face_vertex(h, ed->right, i) == ed->v1 && face_vertex(h, ed->right, i + 1) == ed->v0;
        if (in_left != 1 || in_right != 1) fail_msg("edge %u (%u-%u) does not match its faces", e, ed->v0, ed->v1);
        for (uint32_t g = 0; g < e; g++)
            assert_false((h->edges[g].v0 == ed->v0 && h->edges[g].v1 == ed->v1) ||
                         (h->edges[g].v0 == ed->v1 && h->edges[g].v1 == ed->v0));
    }
}

/* Every vertex on at least three faces (so none inside a face or on a straight edge). */
static void check_vertices(const tb_hull* h)
{
    for (uint32_t v = 0; v < h->vertex_count; v++) {
        int faces = 0;
        for (uint32_t f = 0; f < h->face_count; f++)
            for (uint32_t i = 0; i < h->faces[f].count; i++) faces += face_vertex(h, f, i) == v;
        if (faces < 3) fail_msg("vertex %u is on %d faces", v, faces);
    }
}

/* How far below face f's plane the deepest vertex of face g lies. */
static double max_depth(const tb_hull* h, uint32_t f, uint32_t g)
{
    double n[3], d, depth = 0;
    plane(h, f, n, &d);
    for (uint32_t i = 0; i < h->faces[g].count; i++) {
        double x[3];
        vert(h, face_vertex(h, g, i), x);
        depth = fmax(depth, d - dot3(n, x));
    }
    return depth;
}

/* Everything a hull of the cloud p must satisfy, in the principal frame. */
static void check_hull(const tb_hull* h, const float (*p)[3], int n)
{
    /* A noisy cloud may be built at up to 16 times the tolerance (tb_hull_build retries). */
    double eps = cloud_eps(p, n), tol = (strict_convexity ? 4 : 6 * 16) * eps;
    assert_int_equal((int)h->vertex_count - (int)h->edge_count + (int)h->face_count, 2);
    for (uint32_t i = 0; i < h->index_count; i++) assert_true(h->indices[i] < h->vertex_count);
    check_faces(h, tol);
    check_edges(h);
    check_vertices(h);
    for (int i = 0; i < n; i++) {
        double x[3];
        to_principal(h, p[i], x);
        for (uint32_t f = 0; f < h->face_count; f++) {
            double nn[3], d;
            plane(h, f, nn, &d);
            if (dot3(nn, x) - d > tol) fail_msg("point %d is %g outside face %u (tol %g)", i, dot3(nn, x) - d, f, tol);
        }
        for (int k = 0; k < 3; k++)
            if (!(x[k] >= h->aabb_min[k] - tol && x[k] <= h->aabb_max[k] + tol))
                fail_msg("point %d is outside the box on axis %d: %g not in [%g, %g] (tol %g)", i,
                         k, x[k], (double)h->aabb_min[k], (double)h->aabb_max[k], tol);
    }
    th_assert_near(volume_from_faces(h), h->volume, 0, strict_convexity ? 1e-5 : 1e-4);
    for (uint32_t e = 0; e < h->edge_count; e++) {
        uint32_t l = h->edges[e].left, r = h->edges[e].right;
        double bend = fmax(max_depth(h, l, r), max_depth(h, r, l));
        if (strict_convexity && bend < 0.25 * eps) fail_msg("faces %u and %u are coplanar (within %g): not merged", l, r, bend);
    }
}

static int cmp_double(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

/* Principal moments per kg, sorted, against the expected ones (any order). */
static void check_moments(const tb_hull* h, double a, double b, double c, double rel)
{
    double got[3] = { h->unit_inertia[0], h->unit_inertia[1], h->unit_inertia[2] };
    double want[3] = { a, b, c };
    qsort(got, 3, sizeof got[0], cmp_double);
    qsort(want, 3, sizeof want[0], cmp_double);
    for (int k = 0; k < 3; k++) th_assert_near(got[k], want[k], 0, rel);
}

/* The corners of a box with half extents e, rotated by q and moved by t. */
static int box_points(const double e[3], const double q[4], const double t[3], float (*out)[3])
{
    for (int i = 0; i < 8; i++) {
        double v[3] = { (i & 1) ? e[0] : -e[0], (i & 2) ? e[1] : -e[1], (i & 4) ? e[2] : -e[2] }, w[3];
        qrot(q, 0, v, w);
        for (int k = 0; k < 3; k++) out[i][k] = (float)(w[k] + t[k]);
    }
    return 8;
}

/* Every output vertex, taken back to the input frame, is one of the input points. */
static void check_vertices_map_back(const tb_hull* h, const float (*p)[3], int n, double tol)
{
    for (uint32_t v = 0; v < h->vertex_count; v++) {
        double x[3], w[3], best = INFINITY;
        vert(h, v, x);
        qrot(h->rotation, 0, x, w);
        for (int k = 0; k < 3; k++) w[k] += h->center[k];
        for (int i = 0; i < n; i++) {
            double d[3] = { w[0] - p[i][0], w[1] - p[i][1], w[2] - p[i][2] };
            best = fmin(best, sqrt(dot3(d, d)));
        }
        if (best > tol) fail_msg("vertex %u lands %g from every input point", v, best);
    }
}

static void check_box(const tb_hull* h, const double e[3], const double t[3], double rel)
{
    assert_int_equal(h->vertex_count, 8);
    assert_int_equal(h->face_count, 6);
    assert_int_equal(h->edge_count, 12);
    for (uint32_t f = 0; f < 6; f++) assert_int_equal(h->faces[f].count, 4);
    th_assert_near(h->volume, 8 * e[0] * e[1] * e[2], 0, rel);
    for (int k = 0; k < 3; k++) th_assert_near(h->center[k], t[k], 1e-5, rel);
    double x2 = e[0] * e[0], y2 = e[1] * e[1], z2 = e[2] * e[2];
    check_moments(h, (y2 + z2) / 3, (x2 + z2) / 3, (x2 + y2) / 3, rel);
    th_assert_near(dot3(h->rotation, h->rotation) + h->rotation[3] * h->rotation[3], 1, 1e-12, 0);
}

static void test_box_corners(void** state)
{
    (void)state;
    const double e[3] = { 1, 2, 3 }, q[4] = { 0, 0, 0, 1 }, t[3] = { 0.5, -1, 2 };
    float (*p)[3] = pts;
    int n = box_points(e, q, t, p);
    tb_hull h;
    build_ok((const float (*)[3])p, n, &h);
    check_box(&h, e, t, 1e-6);
    check_hull(&h, (const float (*)[3])p, n);
    check_vertices_map_back(&h, (const float (*)[3])p, n, 1e-5);
    tb_hull_free(&h);
}

/* Corners, a 5 x 5 grid on every face (edges and corners included, so many repeats) and
 * every point once more: still the 8 corners, 6 quads and 12 edges. */
static void test_box_face_grids(void** state)
{
    (void)state;
    const double e[3] = { 0.5, 1.5, 1 }, q[4] = { 0, 0, 0, 1 }, t[3] = { 0, 0, 0 };
    int n = box_points(e, q, t, pts);
    for (int axis = 0; axis < 3; axis++)
        for (int side = -1; side <= 1; side += 2)
            for (int i = 0; i < 5; i++)
                for (int j = 0; j < 5; j++) {
                    int u = (axis + 1) % 3, v = (axis + 2) % 3;
                    pts[n][axis] = (float)(side * e[axis]);
                    pts[n][u] = (float)(e[u] * (-1 + i * 0.5));
                    pts[n][v] = (float)(e[v] * (-1 + j * 0.5));
                    n++;
                }
    memcpy(pts[n], pts[0], (size_t)n * sizeof pts[0]);
    n *= 2;
    tb_hull h;
    build_ok((const float (*)[3])pts, n, &h);
    check_box(&h, e, t, 1e-6);
    check_hull(&h, (const float (*)[3])pts, n);
    tb_hull_free(&h);
}

static void test_box_rotated(void** state)
{
    (void)state;
    th_rng rng = th_rng_seed(7);
    for (int trial = 0; trial < 20; trial++) {
        tb_quat r = th_rng_quat(&rng);
        double q[4] = { r.x, r.y, r.z, r.w }, len = sqrt(dot3(q, q) + q[3] * q[3]);
        for (int k = 0; k < 4; k++) q[k] /= len;
        double e[3] = { th_rng_range(&rng, 0.1f, 2), th_rng_range(&rng, 0.1f, 2), th_rng_range(&rng, 0.1f, 2) };
        double t[3] = { th_rng_range(&rng, -10, 10), th_rng_range(&rng, -10, 10), th_rng_range(&rng, -10, 10) };
        int n = box_points(e, q, t, pts);
        tb_hull h;
        build_ok((const float (*)[3])pts, n, &h);
        /* The corners are rounded to float about 10 from the origin: 1e-6 each. */
        check_box(&h, e, t, 1e-4);
        check_hull(&h, (const float (*)[3])pts, n);
        check_vertices_map_back(&h, (const float (*)[3])pts, n, 1e-5 * (1 + 10));
        tb_hull_free(&h);
    }
}

/* Regular tetrahedron (edge L = 2 sqrt 2): volume L^3 / (6 sqrt 2), moments m L^2 / 20. */
static void test_regular_tetrahedron(void** state)
{
    (void)state;
    const float p[4][3] = { { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 } };
    tb_hull h;
    build_ok(p, 4, &h);
    assert_int_equal(h.vertex_count, 4);
    assert_int_equal(h.face_count, 4);
    assert_int_equal(h.edge_count, 6);
    th_assert_near(h.volume, 8.0 / 3, 0, 1e-9);
    for (int k = 0; k < 3; k++) th_assert_near(h.center[k], 0, 1e-9, 0);
    check_moments(&h, 0.4, 0.4, 0.4, 1e-9);
    check_hull(&h, p, 4);
    tb_hull_free(&h);
}

/* Corner tetrahedron (0, a e_x, b e_y, c e_z), moved by t: volume abc / 6, centroid
 * t + (a, b, c) / 4, and per unit mass I_xx = 3 (b^2 + c^2) / 80, I_xy = a b / 80 (Tonon
 * 2004). The tensor rebuilt from the principal moments and rotation must match it. */
static void test_corner_tetrahedron(void** state)
{
    (void)state;
    const double s[3] = { 1, 2, 3 }, t[3] = { -1, 4, 0.5 };
    float p[4][3];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) p[i][k] = (float)(t[k] + (i == k + 1 ? s[k] : 0));
    tb_hull h;
    build_ok((const float (*)[3])p, 4, &h);
    assert_int_equal(h.vertex_count, 4);
    assert_int_equal(h.face_count, 4);
    assert_int_equal(h.edge_count, 6);
    th_assert_near(h.volume, s[0] * s[1] * s[2] / 6, 0, 1e-7);
    for (int k = 0; k < 3; k++) th_assert_near(h.center[k], t[k] + s[k] / 4, 1e-6, 0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double want = i == j ? 3 * (s[(i + 1) % 3] * s[(i + 1) % 3] + s[(i + 2) % 3] * s[(i + 2) % 3]) / 80
                                 : s[i] * s[j] / 80;
            double got = 0; /* (R diag(I) R^T)_ij = sum_k R_ik I_k R_jk */
            for (int k = 0; k < 3; k++) {
                double ek[3] = { k == 0, k == 1, k == 2 }, col[3];
                qrot(h.rotation, 0, ek, col);
                got += col[i] * h.unit_inertia[k] * col[j];
            }
            th_assert_near(got, want, 1e-6, 1e-5);
        }
    check_hull(&h, (const float (*)[3])p, 4);
    check_vertices_map_back(&h, (const float (*)[3])p, 4, 1e-5);
    tb_hull_free(&h);
}

/* Points in a ball of radius 1 (with some of them repeated and some on a coarse lattice,
 * which makes coplanar faces): everything check_hull asks for, or a GPU limit error. */
static void test_random_clouds(void** state)
{
    (void)state;
    static const int sizes[] = { 4, 5, 6, 8, 12, 20, 50, 100, 300, 1000, 2000 };
    int built = 0;
    for (int seed = 1; seed <= 60; seed++)
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
            th_rng rng = th_rng_seed((uint64_t)seed * 1000 + s);
            int n = sizes[s], lattice = seed % 3 == 0;
            for (int i = 0; i < n; i++) {
                float x, y, z;
                do {
                    x = th_rng_range(&rng, -1, 1); y = th_rng_range(&rng, -1, 1); z = th_rng_range(&rng, -1, 1);
                    if (lattice) { x = roundf(x * 3) / 3; y = roundf(y * 3) / 3; z = roundf(z * 3) / 3; }
                } while (x * x + y * y + z * z > 1);
                pts[i][0] = x + 3; pts[i][1] = y - 2; pts[i][2] = z;
            }
            if (n > 10) memcpy(pts[n - 5], pts[0], 5 * sizeof pts[0]);
            tb_hull h;
            char err[256] = "";
            if (tb_hull_build(&pts[0][0], (uint32_t)n, &h, err, sizeof err) != 0) {
                if (!strstr(err, "GPU limit") && !strstr(err, "span no volume"))
                    fail_msg("seed %d, %d points: %s", seed, n, err);
                continue;
            }
            check_hull(&h, (const float (*)[3])pts, n);
            tb_hull_free(&h);
            built++;
        }
    assert_true(built > 500);
}

/* A ring of k points at each end of a cylinder, plus points inside the caps. */
static int cylinder(int k, double radius, double half, float (*out)[3])
{
    int n = 0;
    for (int end = -1; end <= 1; end += 2) {
        for (int i = 0; i < k; i++) {
            double a = 2 * PI * i / k;
            out[n][0] = (float)(radius * cos(a)); out[n][1] = (float)(radius * sin(a));
            out[n++][2] = (float)(end * half);
        }
        for (int i = 0; i < 5; i++) {
            out[n][0] = (float)(0.1 * radius * i); out[n][1] = (float)(-0.05 * radius * i);
            out[n++][2] = (float)(end * half);
        }
    }
    return n;
}

static void test_cylinder_caps_merge(void** state)
{
    (void)state;
    int n = cylinder(24, 1.0, 0.75, pts);
    tb_hull h;
    build_ok((const float (*)[3])pts, n, &h);
    assert_int_equal(h.vertex_count, 48);
    assert_int_equal(h.face_count, 26);
    assert_int_equal(h.edge_count, 72);
    int caps = 0;
    for (uint32_t f = 0; f < h.face_count; f++) {
        if (h.faces[f].count == 24) caps++;
        else assert_int_equal(h.faces[f].count, 4);
    }
    assert_int_equal(caps, 2);
    check_hull(&h, (const float (*)[3])pts, n);
    /* Volume of the prism: two 24-gon caps of area (k/2) r^2 sin(2 pi / k), height 1.5. */
    th_assert_near(h.volume, 12 * sin(2 * PI / 24) * 1.5, 0, 1e-6);
    tb_hull_free(&h);
}

/* Box corners and face grids moved off their planes by up to 1e-7 of the size: the hull
 * stays valid (no slivers breaking convexity or Euler), and within the tolerance the faces
 * are still the box's six. */
static void test_nearly_coplanar_jitter(void** state)
{
    (void)state;
    th_rng rng = th_rng_seed(99);
    for (int trial = 0; trial < 10; trial++) {
        int n = 0;
        for (int axis = 0; axis < 3; axis++)
            for (int side = -1; side <= 1; side += 2)
                for (int i = 0; i < 7; i++)
                    for (int j = 0; j < 7; j++) {
                        pts[n][axis] = (float)side;
                        pts[n][(axis + 1) % 3] = (float)(-1 + i / 3.0);
                        pts[n][(axis + 2) % 3] = (float)(-1 + j / 3.0);
                        for (int k = 0; k < 3; k++) pts[n][k] += th_rng_range(&rng, -1e-7f, 1e-7f) * 2;
                        n++;
                    }
        tb_hull h;
        build_ok((const float (*)[3])pts, n, &h);
        check_hull(&h, (const float (*)[3])pts, n);
        assert_int_equal(h.face_count, 6);
        assert_int_equal(h.vertex_count, 8);
        th_assert_near(h.volume, 8, 0, 1e-5);
        tb_hull_free(&h);
    }
}

/* tb_hull_build must fail with a message containing `want` and leave *out untouched. */
static void expect_reject(const float (*p)[3], int n, const char* want)
{
    tb_hull h;
    memset(&h, 0xA5, sizeof h);
    tb_hull before = h;
    char err[256] = "";
    assert_int_equal(tb_hull_build(&p[0][0], (uint32_t)n, &h, err, sizeof err), -1);
    if (!strstr(err, want)) fail_msg("error \"%s\" does not say \"%s\"", err, want);
    assert_memory_equal(&h, &before, sizeof h);
}

static void test_rejections(void** state)
{
    (void)state;
    const float tri[3][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    expect_reject(tri, 3, "at least 4 points");
    int n = box_points((const double[3]){ 1, 1, 1 }, (const double[4]){ 0, 0, 0, 1 },
                       (const double[3]){ 0, 0, 0 }, pts);
    pts[5][1] = NAN;
    expect_reject((const float (*)[3])pts, n, "point 5 is not finite");
    pts[5][1] = 1;
    pts[2][2] = -INFINITY;
    expect_reject((const float (*)[3])pts, n, "point 2 is not finite");
    n = 0;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++, n++) {
            pts[n][0] = (float)i; pts[n][1] = (float)j; pts[n][2] = 0.5f * i - 0.25f * j;
        }
    expect_reject((const float (*)[3])pts, n, "coplanar");
    for (int i = 0; i < 10; i++) { pts[i][0] = pts[i][1] = (float)i; pts[i][2] = 2.0f * i; }
    expect_reject((const float (*)[3])pts, 10, "collinear");
    for (int i = 0; i < 10; i++) { pts[i][0] = 1.5f; pts[i][1] = -2; pts[i][2] = 3; }
    expect_reject((const float (*)[3])pts, 10, "identical");
    n = cylinder(40, 1.0, 0.5, pts);
    expect_reject((const float (*)[3])pts, n, "TB_HULL_MAX_FACE_VERTICES");
    n = 0; /* a fine sphere: more than 256 faces */
    for (int i = 0; i < 30; i++)
        for (int j = 0; j < 30; j++, n++) {
            double a = PI * (i + 0.5) / 30, b = 2 * PI * (j + 0.5 * i) / 30;
            pts[n][0] = (float)(sin(a) * cos(b)); pts[n][1] = (float)(sin(a) * sin(b));
            pts[n][2] = (float)cos(a);
        }
    expect_reject((const float (*)[3])pts, n, "GPU limit TB_HULL_MAX_");
}

/* tb_hull_box: closed forms, and the same hull as quickhull finds from the 8 corners. */
static void test_hull_box(void** state)
{
    (void)state;
    const float he[3] = { 0.5f, 2, 1.25f };
    const double e[3] = { he[0], he[1], he[2] }, q[4] = { 0, 0, 0, 1 }, t[3] = { 0, 0, 0 };
    tb_hull b, h;
    char err[256] = "";
    assert_int_equal(tb_hull_box(he, &b, err, sizeof err), 0);
    check_box(&b, e, t, 1e-6);
    for (int k = 0; k < 3; k++) {
        assert_true(b.center[k] == 0 && b.rotation[k] == 0);
        assert_true(b.aabb_min[k] == -he[k] && b.aabb_max[k] == he[k]);
    }
    assert_true(b.rotation[3] == 1);
    th_assert_near(b.unit_inertia[0], (4.0 + 1.5625) / 3, 0, 1e-12);
    th_assert_near(b.unit_inertia[1], (0.25 + 1.5625) / 3, 0, 1e-12);
    th_assert_near(b.unit_inertia[2], (0.25 + 4.0) / 3, 0, 1e-12);
    int n = box_points(e, q, t, pts);
    check_hull(&b, (const float (*)[3])pts, n);
    build_ok((const float (*)[3])pts, n, &h);
    assert_int_equal(h.vertex_count, b.vertex_count);
    assert_int_equal(h.face_count, b.face_count);
    assert_int_equal(h.edge_count, b.edge_count);
    th_assert_near(h.volume, b.volume, 0, 1e-9);
    check_moments(&h, b.unit_inertia[0], b.unit_inertia[1], b.unit_inertia[2], 1e-9);
    tb_hull_free(&h);
    tb_hull_free(&b);
    const float bad[3] = { 1, 0, 1 };
    memset(&b, 0, sizeof b);
    assert_int_equal(tb_hull_box(bad, &b, err, sizeof err), -1);
    assert_non_null(strstr(err, "positive"));
    assert_null(b.vertices);
}

/* Box face grids, scaled, rotated and moved, with noise from far below the tolerance to far
 * above it. Noise about as large as the tolerance is the hard case: the hull must still be
 * built and valid (convex within tolerance, closed, every point inside), though it may
 * merge less; the build retries at a coarser tolerance rather than refuse it. */
static void test_noisy_box_grids(void** state)
{
    (void)state;
    th_rng rng = th_rng_seed(5);
    const float amps[] = { 1e-8f, 1e-7f, 5e-7f, 1e-6f, 2e-6f, 5e-6f, 1e-5f, 1e-4f, 1e-3f };
    int built = 0;
    strict_convexity = 0;
    for (int trial = 0; trial < 2000; trial++) {
        float amp = amps[trial % 9];
        int grid = 2 + trial % 6, n = 0;
        tb_quat r = th_rng_quat(&rng);
        double q[4] = { r.x, r.y, r.z, r.w }, len = sqrt(dot3(q, q) + q[3] * q[3]);
        for (int k = 0; k < 4; k++) q[k] /= len;
        double sc[3] = { th_rng_range(&rng, 0.01f, 3), th_rng_range(&rng, 0.01f, 3), th_rng_range(&rng, 0.01f, 3) };
        for (int axis = 0; axis < 3; axis++)
            for (int side = -1; side <= 1; side += 2)
                for (int i = 0; i <= grid; i++)
                    for (int j = 0; j <= grid; j++) {
                        double v[3], w[3];
                        v[axis] = side;
                        v[(axis + 1) % 3] = -1 + 2.0 * i / grid;
                        v[(axis + 2) % 3] = -1 + 2.0 * j / grid;
                        for (int k = 0; k < 3; k++) v[k] = v[k] * sc[k] + th_rng_range(&rng, -amp, amp);
                        if (trial % 2) { qrot(q, 0, v, w); memcpy(v, w, sizeof v); }
                        for (int k = 0; k < 3; k++) pts[n][k] = (float)(v[k] + (trial % 3) * 5);
                        n++;
                    }
        tb_hull h;
        char err[256] = "";
        if (tb_hull_build(&pts[0][0], (uint32_t)n, &h, err, sizeof err) != 0) {
            if (!strstr(err, "GPU limit")) fail_msg("trial %d (noise %g): %s", trial, (double)amp, err);
            continue;
        }
        check_hull(&h, (const float (*)[3])pts, n);
        tb_hull_free(&h);
        built++;
    }
    strict_convexity = 1;
    print_message("  %d of 2000 noisy clouds built\n", built);
    assert_true(built > 1990);   /* all but clouds beyond the GPU limits */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_corners),
        cmocka_unit_test(test_box_face_grids),
        cmocka_unit_test(test_box_rotated),
        cmocka_unit_test(test_regular_tetrahedron),
        cmocka_unit_test(test_corner_tetrahedron),
        cmocka_unit_test(test_random_clouds),
        cmocka_unit_test(test_cylinder_caps_merge),
        cmocka_unit_test(test_nearly_coplanar_jitter),
        cmocka_unit_test(test_rejections),
        cmocka_unit_test(test_hull_box),
        cmocka_unit_test(test_noisy_box_grids),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
