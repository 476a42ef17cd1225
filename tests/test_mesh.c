/* Host triangle meshes (src/geom/mesh.c): active edges on grids, folds, a box, fins, wrong
 * windings and welded-by-position seams, against the rule in glsl/common/layout.h and a
 * brute-force reference on bumpy terrain and fans; degenerate triangles flagged, counted and
 * nobody's neighbour; bad input refused with a sentence and the output left alone; the GPU
 * image's header, sections, triangles and vertices; a 500 x 500 grid built quickly. No GPU
 * is used. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geom/mesh.h"

#define PI 3.14159265358979323846
#define ALL_ACTIVE (TB_MESH_EDGE_ACTIVE_0 | TB_MESH_EDGE_ACTIVE_1 | TB_MESH_EDGE_ACTIVE_2)

/* ---- helpers -------------------------------------------------------------------------- */

typedef struct soup {
    float* xyz;
    uint32_t* indices;
    uint32_t vertex_count, triangle_count;
} soup;

static void soup_free(soup* s)
{
    free(s->xyz);
    free(s->indices);
}

static tb_mesh build_or_fail(const float* xyz, uint32_t vertices, const uint32_t* indices,
                             uint32_t triangles)
{
    tb_mesh m;
    char error[256] = "";
    if (tb_mesh_build(xyz, vertices, indices, triangles, &m, error, sizeof error))
        fail_msg("tb_mesh_build: %s", error);
    assert_int_equal(m.vertex_count, vertices);
    assert_int_equal(m.triangle_count, triangles);
    assert_memory_equal(m.xyz, xyz, 3 * sizeof(float) * vertices);
    assert_memory_equal(m.indices, indices, 3 * sizeof(uint32_t) * triangles);
    assert_int_equal(m.bvh.triangle_count, triangles);
    return m;
}

static int active(const tb_mesh* m, uint32_t t, uint32_t k)
{
    return (m->flags[t] & (TB_MESH_EDGE_ACTIVE_0 << k)) != 0;
}

/* The edge of triangle t between vertices a and b (either way round). */
static uint32_t edge_of(const tb_mesh* m, uint32_t t, uint32_t a, uint32_t b)
{
    const uint32_t* i = m->indices + 3 * t;
    for (uint32_t k = 0; k < 3; k++) {
        uint32_t p = i[k], q = i[(k + 1) % 3];
        if ((p == a && q == b) || (p == b && q == a)) return k;
    }
    fail_msg("triangle %u has no edge %u-%u", t, a, b);
    return 3;
}

static int edge_active(const tb_mesh* m, uint32_t t, uint32_t a, uint32_t b)
{
    return active(m, t, edge_of(m, t, a, b));
}

/* A (cells x cells) grid of 1 m quads over x and z, two triangles each facing +y, sharing
 * vertices; y from `height` when given. */
static soup grid(uint32_t cells, float (*height)(uint32_t x, uint32_t z))
{
    uint32_t side = cells + 1;
    soup s = { malloc(3 * sizeof(float) * side * side),
               malloc(6 * sizeof(uint32_t) * cells * cells), side * side, 2 * cells * cells };
    assert_non_null(s.xyz);
    assert_non_null(s.indices);
    for (uint32_t z = 0; z < side; z++)
        for (uint32_t x = 0; x < side; x++) {
            float* v = s.xyz + 3 * (z * side + x);
            v[0] = (float)x;
            v[1] = height ? height(x, z) : 0.0f;
            v[2] = (float)z;
        }
    for (uint32_t z = 0; z < cells; z++)
        for (uint32_t x = 0; x < cells; x++) {
            uint32_t* t = s.indices + 6 * (z * cells + x), a = z * side + x;
            const uint32_t quad[6] = { a, a + side, a + 1, a + 1, a + side, a + side + 1 };
            memcpy(t, quad, sizeof quad);
        }
    return s;
}

/* Whether both ends of an edge of the grid lie on the same side of its border. */
static int on_grid_border(uint32_t cells, uint32_t a, uint32_t b)
{
    uint32_t side = cells + 1, ax = a % side, az = a / side, bx = b % side, bz = b / side;
    return (ax == bx && (ax == 0 || ax == cells)) || (az == bz && (az == 0 || az == cells));
}

/* Every grid edge is active exactly when it is on the border; returns the active count. */
static uint32_t check_grid(const tb_mesh* m, uint32_t cells)
{
    uint32_t count = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t* i = m->indices + 3 * t;
            int border = on_grid_border(cells, i[k], i[(k + 1) % 3]);
            if (active(m, t, k) != border)
                fail_msg("triangle %u edge %u: active %d, on the border %d", t, k,
                         active(m, t, k), border);
            count += (uint32_t)border;
        }
    return count;
}

/* ---- grids ---------------------------------------------------------------------------- */

static void test_flat_grid(void** state)
{
    (void)state;
    const uint32_t cells = 6;
    soup s = grid(cells, NULL);
    tb_mesh m = build_or_fail(s.xyz, s.vertex_count, s.indices, s.triangle_count);
    assert_int_equal(m.degenerate_count, 0);
    /* 4 * cells border edges, each one triangle's; the other 6 cells^2 - 4 cells edge slots
     * are the two sides of the grid's interior edges. */
    assert_int_equal(check_grid(&m, cells), 4 * cells);
    uint32_t inactive = 0;
    for (uint32_t t = 0; t < m.triangle_count; t++)
        for (uint32_t k = 0; k < 3; k++) inactive += !active(&m, t, k);
    assert_int_equal(inactive, 6 * cells * cells - 4 * cells);
    tb_mesh_free(&m);
    soup_free(&s);
}

static void test_large_grid(void** state)
{
    (void)state;
    const uint32_t cells = 500;
    soup s = grid(cells, NULL);
    clock_t start = clock();
    tb_mesh m = build_or_fail(s.xyz, s.vertex_count, s.indices, s.triangle_count);
    double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    print_message("%u triangles built in %.3f s\n", m.triangle_count, seconds);
    assert_int_equal(m.triangle_count, 500000);
    assert_int_equal(check_grid(&m, cells), 4 * cells);
    assert_true(seconds < 5.0);
    tb_mesh_free(&m);
    soup_free(&s);
}

/* ---- folds ---------------------------------------------------------------------------- */

/* Two triangles on the shared edge A = 0 -> B = 1 along z: t = (A, B, C) reaching to +x,
 * u = (B, A, D) to -x, both facing +y when flat. `fold` (degrees) tilts each half by half
 * of it: down (a ridge, convex) when positive, up (a valley, concave) when negative. */
static float pair_xyz[12];
static const uint32_t pair_indices[6] = { 0, 1, 2, 1, 0, 3 };

static void make_pair(double fold)
{
    double half = fold / 2 * PI / 180, c = cos(half), s = sin(half);
    const float xyz[12] = { 0, 0, 0, 0, 0, 1, (float)c, (float)-s, 0.5f, (float)-c, (float)-s,
                            0.5f };
    memcpy(pair_xyz, xyz, sizeof xyz);
}

/* Whether the shared edge is active, asserting both triangles agree and the others are. */
static int fold_active(double fold)
{
    make_pair(fold);
    tb_mesh m = build_or_fail(pair_xyz, 4, pair_indices, 2);
    int a = edge_active(&m, 0, 0, 1);
    assert_int_equal(a, edge_active(&m, 1, 0, 1));
    assert_int_equal(m.flags[0] | (TB_MESH_EDGE_ACTIVE_0 << edge_of(&m, 0, 0, 1)), ALL_ACTIVE);
    assert_int_equal(m.flags[1] | (TB_MESH_EDGE_ACTIVE_0 << edge_of(&m, 1, 0, 1)), ALL_ACTIVE);
    tb_mesh_free(&m);
    return a;
}

static void test_folds(void** state)
{
    (void)state;
    assert_false(fold_active(0));       /* flat */
    assert_true(fold_active(30));       /* a roof: convex */
    assert_false(fold_active(-30));     /* a valley: concave */
    assert_false(fold_active(0.5));     /* nearly flat, convex */
    assert_false(fold_active(-0.5));
    assert_false(fold_active(1.0));     /* TB_MESH_FLAT_COSINE is about 1.15 degrees */
    assert_true(fold_active(1.3));
    assert_false(fold_active(-1.3));
    assert_true(fold_active(90));
    assert_false(fold_active(-90));
    assert_false(fold_active(-170));    /* a deep slot */
    assert_true(fold_active(179));      /* a knife edge */
}

/* The pair with u turned over: both run A -> B, so the edge is active, flat or in a
 * valley (where, but for the winding, the fold would hide it). */
static void test_inconsistent_winding(void** state)
{
    (void)state;
    const uint32_t indices[6] = { 0, 1, 2, 0, 1, 3 };
    const double folds[2] = { 0, -30 };
    for (int f = 0; f < 2; f++) {
        make_pair(folds[f]);
        tb_mesh m = build_or_fail(pair_xyz, 4, indices, 2);
        assert_int_equal(m.flags[0], ALL_ACTIVE);
        assert_int_equal(m.flags[1], ALL_ACTIVE);
        tb_mesh_free(&m);
    }
}

/* A third triangle on the flat pair's edge (a fin standing up): three triangles meet, so the
 * edge is active on all of them. */
static void test_non_manifold_edge(void** state)
{
    (void)state;
    make_pair(0);
    float xyz[15];
    memcpy(xyz, pair_xyz, sizeof pair_xyz);
    const float top[3] = { 0, 1, 0.5f };
    memcpy(xyz + 12, top, sizeof top);
    const uint32_t indices[9] = { 0, 1, 2, 1, 0, 3, 0, 1, 4 };
    tb_mesh m = build_or_fail(xyz, 5, indices, 3);
    for (uint32_t t = 0; t < 3; t++) assert_int_equal(m.flags[t], ALL_ACTIVE);
    tb_mesh_free(&m);
}

/* The flat pair with its own copies of A and B: adjacency is by index, so no neighbours. */
static void test_welded_by_position_only(void** state)
{
    (void)state;
    make_pair(0);
    float xyz[18];
    memcpy(xyz, pair_xyz, sizeof pair_xyz);
    memcpy(xyz + 12, pair_xyz, 6 * sizeof(float));
    const uint32_t indices[6] = { 0, 1, 2, 5, 4, 3 };
    tb_mesh m = build_or_fail(xyz, 6, indices, 2);
    assert_int_equal(m.flags[0], ALL_ACTIVE);
    assert_int_equal(m.flags[1], ALL_ACTIVE);
    tb_mesh_free(&m);
}

/* ---- a box ---------------------------------------------------------------------------- */

/* Vertex i of the 2 m box is (x, y, z) = +-1 from bits 0, 1, 2 of i. */
static float box_xyz[24];
static uint32_t box_indices[36];

/* Each face a quad split along the diagonal from its first corner, wound outward. */
static void make_box(void)
{
    for (uint32_t i = 0; i < 8; i++)
        for (uint32_t a = 0; a < 3; a++) box_xyz[3 * i + a] = (i >> a & 1) ? 1.0f : -1.0f;
    const uint32_t faces[6][4] = { { 0, 2, 6, 4 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 },
                                   { 2, 3, 7, 6 }, { 0, 1, 3, 2 }, { 4, 5, 7, 6 } };
    for (uint32_t f = 0; f < 6; f++)
        for (uint32_t h = 0; h < 2; h++) {
            uint32_t* t = box_indices + 6 * f + 3 * h;
            t[0] = faces[f][0];
            t[1] = faces[f][1 + h];
            t[2] = faces[f][2 + h];
            const float* p[3] = { box_xyz + 3 * t[0], box_xyz + 3 * t[1], box_xyz + 3 * t[2] };
            double e1[3], e2[3], n[3], centre = 0;
            for (int a = 0; a < 3; a++) {
                e1[a] = p[1][a] - p[0][a];
                e2[a] = p[2][a] - p[0][a];
            }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            for (int a = 0; a < 3; a++) centre += n[a] * (p[0][a] + p[1][a] + p[2][a]);
            if (centre < 0) {
                uint32_t swap = t[1];
                t[1] = t[2];
                t[2] = swap;
            }
        }
}

/* A box edge joins corners differing in one coordinate; a face's diagonal, in two. */
static int is_box_edge(uint32_t a, uint32_t b)
{
    uint32_t d = a ^ b;
    return d == 1 || d == 2 || d == 4;
}

static void test_box(void** state)
{
    (void)state;
    make_box();
    tb_mesh m = build_or_fail(box_xyz, 8, box_indices, 12);
    uint32_t active_count = 0;
    for (uint32_t t = 0; t < 12; t++)
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t a = m.indices[3 * t + k], b = m.indices[3 * t + (k + 1) % 3];
            assert_int_equal(active(&m, t, k), is_box_edge(a, b));
            active_count += (uint32_t)active(&m, t, k);
        }
    /* 12 box edges seen from both faces; the 6 diagonals (12 slots) are inactive. */
    assert_int_equal(active_count, 24);
    tb_mesh_free(&m);

    /* The box turned inside out (a room seen from within): every fold is concave. */
    uint32_t inside[36];
    for (uint32_t t = 0; t < 12; t++) {
        inside[3 * t] = box_indices[3 * t];
        inside[3 * t + 1] = box_indices[3 * t + 2];
        inside[3 * t + 2] = box_indices[3 * t + 1];
    }
    m = build_or_fail(box_xyz, 8, inside, 12);
    for (uint32_t t = 0; t < 12; t++) assert_int_equal(m.flags[t], 0);
    tb_mesh_free(&m);
}

/* ---- degenerate triangles ------------------------------------------------------------- */

static void test_degenerate_triangles(void** state)
{
    (void)state;
    make_pair(0);
    float xyz[21];
    memcpy(xyz, pair_xyz, sizeof pair_xyz);
    /* 4 on edge A-B; 5 1e-8 m above the middle of A-C; 6 the middle of B-C. */
    const float more[9] = { 0, 0, 0.25f, 0.5f, 1e-8f, 0.25f, 0.5f, 0, 0.75f };
    memcpy(xyz + 12, more, sizeof more);
    /* The flat pair t0, t1; a triangle of no area on their edge A-B (not a third
     * neighbour); a repeated index; a sliver on t0's edge C-A and a triangle of no area on
     * its edge B-C (neither its neighbour). */
    const uint32_t indices[18] = { 0, 1, 2, 1, 0, 3, 0, 1, 4, 3, 3, 0, 0, 5, 2, 2, 1, 6 };
    tb_mesh m = build_or_fail(xyz, 7, indices, 6);
    assert_int_equal(m.degenerate_count, 4);
    for (uint32_t t = 2; t < 6; t++) assert_int_equal(m.flags[t], TB_MESH_DEGENERATE);
    assert_false(edge_active(&m, 0, 0, 1));   /* still only two real triangles there */
    assert_false(edge_active(&m, 1, 0, 1));
    assert_true(edge_active(&m, 0, 1, 2));    /* degenerate triangles are no neighbours */
    assert_true(edge_active(&m, 0, 2, 0));
    tb_mesh_free(&m);

    /* A thin but real triangle (1 m by 1 mm) is not degenerate. */
    const float thin[9] = { 0, 0, 0, 1, 0, 0, 0.5f, 0, -1e-3f };
    const uint32_t one[3] = { 0, 1, 2 };
    m = build_or_fail(thin, 3, one, 1);
    assert_int_equal(m.degenerate_count, 0);
    assert_int_equal(m.flags[0], ALL_ACTIVE);
    tb_mesh_free(&m);
}

/* ---- against a brute-force reference ------------------------------------------------- */

static void normal(const tb_mesh* m, uint32_t t, double n[3], double v[3][3])
{
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++) v[k][a] = m->xyz[3 * m->indices[3 * t + k] + a];
    double e1[3], e2[3];
    for (int a = 0; a < 3; a++) {
        e1[a] = v[1][a] - v[0][a];
        e2[a] = v[2][a] - v[0][a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; a++) n[a] /= l;
}

/* The rule of layout.h read literally, by looking at every other triangle. */
static int reference_active(const tb_mesh* m, uint32_t t, uint32_t k)
{
    uint32_t a = m->indices[3 * t + k], b = m->indices[3 * t + (k + 1) % 3];
    uint32_t sharing = 0, other = 0, other_k = 0;
    for (uint32_t u = 0; u < m->triangle_count; u++) {
        if (u == t || (m->flags[u] & TB_MESH_DEGENERATE)) continue;
        for (uint32_t j = 0; j < 3; j++) {
            uint32_t p = m->indices[3 * u + j], q = m->indices[3 * u + (j + 1) % 3];
            if ((p == a && q == b) || (p == b && q == a)) {
                sharing++;
                other = u;
                other_k = j;
            }
        }
    }
    if (sharing != 1 || m->indices[3 * other + other_k] != b) return 1;
    double nt[3], nu[3], vt[3][3], vu[3][3];
    normal(m, t, nt, vt);
    normal(m, other, nu, vu);
    if (nt[0] * nu[0] + nt[1] * nu[1] + nt[2] * nu[2] >= TB_MESH_FLAT_COSINE) return 0;
    const double* w = vu[(other_k + 2) % 3];
    double front = 0;
    for (int i = 0; i < 3; i++) front += nt[i] * (w[i] - vt[k][i]);
    double e[3], length = 0;
    for (int i = 0; i < 3; i++) e[i] = vt[(k + 1) % 3][i] - vt[k][i];
    for (int i = 0; i < 3; i++) length += e[i] * e[i];
    return front <= 1e-6 * sqrt(length);
}

static void check_against_reference(const tb_mesh* m)
{
    uint32_t counts[2] = { 0, 0 };
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        if (m->flags[t] & TB_MESH_DEGENERATE) {
            assert_int_equal(m->flags[t], TB_MESH_DEGENERATE);
            continue;
        }
        for (uint32_t k = 0; k < 3; k++) {
            int want = reference_active(m, t, k);
            if (active(m, t, k) != want)
                fail_msg("triangle %u edge %u: active %d, the reference says %d", t, k,
                         active(m, t, k), want);
            counts[want]++;
        }
    }
    print_message("%u edge slots active, %u inactive\n", counts[1], counts[0]);
    assert_true(counts[0] > 0 && counts[1] > 0);
}

static th_rng bumps;

static float bumpy(uint32_t x, uint32_t z)
{
    (void)x;
    (void)z;
    return th_rng_range(&bumps, -0.2f, 0.2f);
}

/* Random heights: a mix of convex, concave and nearly flat folds; some triangles turned
 * over and some made degenerate to mix in every rule. */
static void test_bumpy_terrain_against_reference(void** state)
{
    (void)state;
    bumps = th_rng_seed(5);
    soup s = grid(24, bumpy);
    for (uint32_t v = 0; v < s.vertex_count; v += 7) s.xyz[3 * v + 1] = 0; /* flat patches */
    th_rng rng = th_rng_seed(6);
    for (uint32_t t = 0; t < s.triangle_count; t++) {
        uint32_t r = th_rng_u32(&rng) % 40, *i = s.indices + 3 * t;
        if (r == 0) {
            uint32_t swap = i[1];
            i[1] = i[2];
            i[2] = swap;
        } else if (r == 1) {
            i[2] = i[1];
        }
    }
    tb_mesh m = build_or_fail(s.xyz, s.vertex_count, s.indices, s.triangle_count);
    assert_true(m.degenerate_count > 0);
    check_against_reference(&m);
    tb_mesh_free(&m);
    soup_free(&s);
}

/* A tall cone of 200 triangles round one apex and its base as a fan round a centre:
 * vertices with hundreds of edges (sorted otherwise than most vertices' few), convex
 * creases and a flat base. */
static void test_fans_against_reference(void** state)
{
    (void)state;
    const uint32_t n = 200;
    soup s = { malloc(3 * sizeof(float) * (n + 2)), malloc(6 * sizeof(uint32_t) * n), n + 2,
               2 * n };
    assert_non_null(s.xyz);
    assert_non_null(s.indices);
    const float apex[6] = { 0, 10, 0, 0, 0, 0 };
    memcpy(s.xyz, apex, sizeof apex);
    for (uint32_t i = 0; i < n; i++) {
        double angle = 2 * PI * i / n;
        float* v = s.xyz + 3 * (i + 2);
        v[0] = (float)cos(angle);
        v[1] = 0;
        v[2] = (float)sin(angle);
        uint32_t a = i + 2, b = (i + 1) % n + 2;
        const uint32_t tris[6] = { 0, b, a, 1, a, b };
        memcpy(s.indices + 6 * i, tris, sizeof tris);
    }
    tb_mesh m = build_or_fail(s.xyz, s.vertex_count, s.indices, s.triangle_count);
    check_against_reference(&m);
    /* Neighbouring cone faces are 1.8 degrees apart: active. The base is flat. */
    for (uint32_t i = 0; i < n; i++) {
        assert_true(edge_active(&m, 2 * i, 0, i + 2));
        assert_false(edge_active(&m, 2 * i + 1, 1, i + 2));
        assert_true(edge_active(&m, 2 * i + 1, i + 2, (i + 1) % n + 2));
    }
    tb_mesh_free(&m);
    soup_free(&s);
}

/* ---- bad input ------------------------------------------------------------------------ */

static void expect_refused(const float* xyz, uint32_t vertices, const uint32_t* indices,
                           uint32_t triangles, const char* words)
{
    tb_mesh out;
    memset(&out, 0xab, sizeof out);
    tb_mesh before = out;
    char error[256] = "";
    assert_int_equal(tb_mesh_build(xyz, vertices, indices, triangles, &out, error,
                                   sizeof error), -1);
    assert_memory_equal(&out, &before, sizeof out);
    if (!strstr(error, words)) fail_msg("error \"%s\" does not say \"%s\"", error, words);
    /* No buffer, or one too small, is no problem. */
    assert_int_equal(tb_mesh_build(xyz, vertices, indices, triangles, &out, NULL, 0), -1);
    assert_int_equal(tb_mesh_build(xyz, vertices, indices, triangles, &out, error, 4), -1);
    assert_int_equal(strlen(error), 3);
}

static void test_bad_input_refused(void** state)
{
    (void)state;
    float xyz[9] = { 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    uint32_t tri[3] = { 0, 1, 2 };
    expect_refused(NULL, 3, tri, 1, "not NULL");
    expect_refused(xyz, 3, NULL, 1, "not NULL");
    expect_refused(xyz, 3, tri, 0, "at least one triangle");
    expect_refused(xyz, 3, tri, TB_BVH_MAX_TRIANGLES + 1, "at most 16777216 triangles");
    expect_refused(xyz, UINT32_MAX, tri, 1, "at most 4294967289 vertices");
    uint32_t far[3] = { 0, 1, 3 };
    expect_refused(xyz, 3, far, 1, "triangle 0's index 2 is vertex 3, but the mesh has 3");
    xyz[4] = NAN;
    expect_refused(xyz, 3, tri, 1, "vertex 1 is not finite");
    xyz[4] = -INFINITY;
    expect_refused(xyz, 3, tri, 1, "vertex 1 is not finite");
    xyz[4] = 1e7f;
    expect_refused(xyz, 3, tri, 1, "vertex 1 has a coordinate of 1e+07 m, beyond the 1e+06 m");
    xyz[4] = -1.5e6f;
    expect_refused(xyz, 3, tri, 1, "vertex 1 has a coordinate of -1.5e+06 m");
    xyz[4] = 1e6f;     /* at the limit: fine */
    tb_mesh m = build_or_fail(xyz, 3, tri, 1);
    tb_mesh_free(&m);
    xyz[4] = 0;
    const uint32_t flat[6] = { 0, 0, 1, 2, 2, 2 };
    expect_refused(xyz, 3, flat, 2, "every triangle of the mesh is degenerate");
    const float line[9] = { 0, 0, 0, 1, 1, 1, 3, 3, 3 };
    expect_refused(line, 3, tri, 1, "every triangle of the mesh is degenerate");
}

/* ---- the GPU image -------------------------------------------------------------------- */

static float as_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static uint32_t as_uint(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static void test_gpu_image(void** state)
{
    (void)state;
    make_box();
    for (uint32_t i = 0; i < 8; i++) box_xyz[3 * i + 1] = box_xyz[3 * i + 1] * 0.5f + 3.25f;
    tb_mesh m = build_or_fail(box_xyz, 8, box_indices, 12);
    size_t size = tb_mesh_image_size(&m);
    assert_int_equal(size, 4 + 23 + 12 + 8);
    tb_gpu_uvec4* image = malloc((size + 1) * sizeof *image);
    assert_non_null(image);
    memset(image, 0xcd, (size + 1) * sizeof *image);
    tb_mesh_pack(&m, image);
    assert_int_equal(image[size].x, 0xcdcdcdcd);   /* nothing written past the end */

    tb_gpu_mesh_header h;
    memcpy(&h, image, sizeof h);
    double scale[3];
    tb_bvh_steps_per_metre(&m.bvh, scale);
    const float lo[3] = { h.lo.x, h.lo.y, h.lo.z }, hi[3] = { h.hi.x, h.hi.y, h.hi.z };
    const float steps[3] = { h.scale.x, h.scale.y, h.scale.z };
    for (int a = 0; a < 3; a++) {
        assert_true(lo[a] == m.bvh.lo[a] && hi[a] == m.bvh.hi[a]);
        assert_true(steps[a] == (float)scale[a]);
    }
    assert_true(lo[1] == 2.75f && hi[1] == 3.75f && steps[1] == 65535.0f);
    assert_int_equal(as_uint(h.lo.w), 23);
    assert_int_equal(as_uint(h.scale.w), 12);
    assert_int_equal(as_uint(h.hi.w), 8);
    assert_int_equal(h.sections.x, 4);
    assert_int_equal(h.sections.y, 4 + 23);
    assert_int_equal(h.sections.z, 4 + 23 + 12);
    assert_int_equal(h.sections.w, 0);

    assert_memory_equal(image + 4, m.bvh.nodes, 23 * sizeof *m.bvh.nodes);
    for (uint32_t t = 0; t < 12; t++) {
        tb_gpu_uvec4 q = image[h.sections.y + t];
        assert_int_equal(q.x, box_indices[3 * t]);
        assert_int_equal(q.y, box_indices[3 * t + 1]);
        assert_int_equal(q.z, box_indices[3 * t + 2]);
        assert_int_equal(q.w, m.flags[t]);
        uint32_t edges = (q.w & 1) + (q.w >> 1 & 1) + (q.w >> 2 & 1);
        assert_int_equal(edges, 2);                    /* two box edges, one diagonal */
    }
    for (uint32_t v = 0; v < 8; v++) {
        tb_gpu_uvec4 q = image[h.sections.z + v];
        assert_true(as_float(q.x) == box_xyz[3 * v] && as_float(q.y) == box_xyz[3 * v + 1]);
        assert_true(as_float(q.z) == box_xyz[3 * v + 2]);
        assert_int_equal(q.w, 0);
    }
    free(image);
    tb_mesh_free(&m);
    assert_null(m.xyz);
    assert_null(m.bvh.nodes);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flat_grid),
        cmocka_unit_test(test_folds),
        cmocka_unit_test(test_inconsistent_winding),
        cmocka_unit_test(test_non_manifold_edge),
        cmocka_unit_test(test_welded_by_position_only),
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_degenerate_triangles),
        cmocka_unit_test(test_bumpy_terrain_against_reference),
        cmocka_unit_test(test_fans_against_reference),
        cmocka_unit_test(test_bad_input_refused),
        cmocka_unit_test(test_gpu_image),
        cmocka_unit_test(test_large_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
