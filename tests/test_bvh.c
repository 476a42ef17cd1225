/* The mesh BVH on the host (src/geom/bvh.c): its structure (every triangle in one leaf,
 * skip indices that end each subtree, boxes that contain what lies below them), the
 * stackless walk against brute force on random soups and a flat terrain grid of a million
 * triangles, the same tree on every build, and bad input refused with a sentence. No GPU
 * is used. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"

/* ---- meshes ----------------------------------------------------------------------------- */

typedef struct mesh {
    float* xyz;
    uint32_t* indices;
    uint32_t vertex_count, triangle_count;
} mesh;

static void mesh_free(mesh* m)
{
    free(m->xyz);
    free(m->indices);
}

/* n triangles of random size (up to `size`) scattered in a 100 m cube, each its own three
 * vertices; every seventh made degenerate (a line or a point). */
static mesh random_soup(uint32_t n, float size, uint64_t seed)
{
    th_rng rng = th_rng_seed(seed);
    mesh m = { malloc(9 * sizeof(float) * n), malloc(3 * sizeof(uint32_t) * n), 3 * n, n };
    assert_non_null(m.xyz);
    assert_non_null(m.indices);
    for (uint32_t t = 0; t < n; t++) {
        float c[3];
        for (int a = 0; a < 3; a++) c[a] = th_rng_range(&rng, -50, 50);
        for (int k = 0; k < 3; k++) {
            for (int a = 0; a < 3; a++) {
                float d = th_rng_range(&rng, -size, size);
                if (t % 7 == 0) d = k == 2 ? 0 : d * (float)k;   /* collinear or repeated */
                m.xyz[9 * t + 3 * k + a] = c[a] + d;
            }
            m.indices[3 * t + k] = 3 * t + k;
        }
    }
    return m;
}

/* A flat square grid of (cells x cells) quads, two triangles each, at y = 0, 1 m cells,
 * sharing vertices. */
static mesh flat_grid(uint32_t cells)
{
    uint32_t side = cells + 1;
    mesh m = { malloc(3 * sizeof(float) * side * side), malloc(6 * sizeof(uint32_t) * cells * cells),
               side * side, 2 * cells * cells };
    assert_non_null(m.xyz);
    assert_non_null(m.indices);
    for (uint32_t z = 0; z < side; z++)
        for (uint32_t x = 0; x < side; x++) {
            float* v = m.xyz + 3 * (z * side + x);
            v[0] = (float)x;
            v[1] = 0;
            v[2] = (float)z;
        }
    for (uint32_t z = 0; z < cells; z++)
        for (uint32_t x = 0; x < cells; x++) {
            uint32_t* t = m.indices + 6 * (z * cells + x), a = z * side + x;
            const uint32_t quad[6] = { a, a + side, a + 1, a + 1, a + side, a + side + 1 };
            memcpy(t, quad, sizeof quad);
        }
    return m;
}

static tb_bvh build_or_fail(const mesh* m)
{
    tb_bvh bvh;
    char error[256] = "";
    if (tb_bvh_build(m->xyz, m->vertex_count, m->indices, m->triangle_count, &bvh, error,
                     sizeof error))
        fail_msg("tb_bvh_build: %s", error);
    return bvh;
}

static void triangle_box(const mesh* m, uint32_t t, float lo[3], float hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
        for (int k = 0; k < 3; k++) {
            float v = m->xyz[3 * (size_t)m->indices[3 * (size_t)t + k] + a];
            lo[a] = fminf(lo[a], v);
            hi[a] = fmaxf(hi[a], v);
        }
    }
}

static int box_overlap(const float alo[3], const float ahi[3], const float blo[3], const float bhi[3])
{
    for (int a = 0; a < 3; a++)
        if (alo[a] > bhi[a] || blo[a] > ahi[a]) return 0;
    return 1;
}

static int box_inside(const float ilo[3], const float ihi[3], const float olo[3], const float ohi[3])
{
    for (int a = 0; a < 3; a++)
        if (ilo[a] < olo[a] || ihi[a] > ohi[a]) return 0;
    return 1;
}

/* ---- structure -------------------------------------------------------------------------- */

/* The subtree at `node`: returns the first node after it, checking on the way that each
 * inner node's skip index is that node, its box holds its children's, and each leaf's box
 * holds its triangle; counts the leaves each triangle has. */
static uint32_t check_subtree(const tb_bvh* bvh, const mesh* m, uint32_t node, uint32_t* seen,
                              uint32_t depth, uint32_t* deepest)
{
    assert_true(node < bvh->node_count);
    if (depth > *deepest) *deepest = depth;
    float lo[3], hi[3];
    tb_bvh_node_box(bvh, node, lo, hi);
    uint32_t w = bvh->nodes[node].q.w;
    if (w & TB_BVH_LEAF) {
        uint32_t t = w & ~TB_BVH_LEAF;
        assert_true(t < m->triangle_count);
        seen[t]++;
        float tlo[3], thi[3];
        triangle_box(m, t, tlo, thi);
        if (!box_inside(tlo, thi, lo, hi)) fail_msg("leaf %u's box misses triangle %u", node, t);
        return node + 1;
    }
    uint32_t second = check_subtree(bvh, m, node + 1, seen, depth + 1, deepest);
    float clo[3], chi[3];
    tb_bvh_node_box(bvh, node + 1, clo, chi);
    assert_true(box_inside(clo, chi, lo, hi));
    tb_bvh_node_box(bvh, second, clo, chi);
    assert_true(box_inside(clo, chi, lo, hi));
    uint32_t end = check_subtree(bvh, m, second, seen, depth + 1, deepest);
    assert_int_equal(w, end);
    return end;
}

static void check_structure(const tb_bvh* bvh, const mesh* m)
{
    assert_int_equal(bvh->triangle_count, m->triangle_count);
    assert_int_equal(bvh->node_count, 2 * m->triangle_count - 1);
    uint32_t* seen = calloc(m->triangle_count, sizeof *seen), deepest = 0;
    assert_non_null(seen);
    assert_int_equal(check_subtree(bvh, m, 0, seen, 0, &deepest), bvh->node_count);
    for (uint32_t t = 0; t < m->triangle_count; t++)
        if (seen[t] != 1) fail_msg("triangle %u is in %u leaves", t, seen[t]);
    /* Median splits: depth within one of ceil(log2 n). */
    assert_true(deepest <= (uint32_t)ceil(log2((double)m->triangle_count)) + 1);
    free(seen);
}

static void test_structure_of_random_soups(void** state)
{
    (void)state;
    const uint32_t sizes[] = { 1, 2, 3, 17, 1000, 5000 };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        mesh m = random_soup(sizes[i], 2.0f, 100 + i);
        tb_bvh bvh = build_or_fail(&m);
        check_structure(&bvh, &m);
        tb_bvh_free(&bvh);
        mesh_free(&m);
    }
}

/* ---- the walk --------------------------------------------------------------------------- */

typedef struct found {
    uint8_t* hit;
    uint32_t count;
} found;

static void mark(void* user, uint32_t t)
{
    found* f = user;
    f->hit[t]++;
    f->count++;
}

/* Every triangle whose box overlaps the query is found exactly once; anything else found
 * lies within a quantization step of it. Returns the nodes looked at. */
static uint32_t check_query(const tb_bvh* bvh, const mesh* m, const float lo[3], const float hi[3])
{
    found f = { calloc(m->triangle_count, 1), 0 };
    assert_non_null(f.hit);
    uint32_t looked = tb_bvh_query(bvh, lo, hi, mark, &f);
    float step[3], glo[3], ghi[3];
    for (int a = 0; a < 3; a++) {
        step[a] = (bvh->hi[a] - bvh->lo[a]) / 65535.0f;
        glo[a] = lo[a] - 2 * step[a];
        ghi[a] = hi[a] + 2 * step[a];
    }
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        float tlo[3], thi[3];
        triangle_box(m, t, tlo, thi);
        assert_true(f.hit[t] <= 1);
        if (box_overlap(tlo, thi, lo, hi) && !f.hit[t]) fail_msg("triangle %u missed", t);
        if (f.hit[t] && !box_overlap(tlo, thi, glo, ghi)) fail_msg("triangle %u found far away", t);
    }
    free(f.hit);
    return looked;
}

static void test_walk_matches_brute_force(void** state)
{
    (void)state;
    mesh m = random_soup(5000, 1.5f, 7);
    tb_bvh bvh = build_or_fail(&m);
    th_rng rng = th_rng_seed(8);
    double looked = 0;
    for (int q = 0; q < 300; q++) {
        float c[3], lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
            c[a] = th_rng_range(&rng, -60, 60);
            float half = th_rng_range(&rng, 0, q % 10 == 0 ? 30.0f : 3.0f);
            lo[a] = c[a] - half;
            hi[a] = c[a] + half;
        }
        uint32_t n = check_query(&bvh, &m, lo, hi);
        if (q % 10) looked += n;
    }
    /* Small boxes look at a small part of the tree (a full scan is 9,999 nodes). */
    looked /= 270;
    print_message("small queries: %.0f of %u nodes looked at on average\n", looked, bvh.node_count);
    assert_true(looked < 0.05 * bvh.node_count);
    /* A box beside the mesh looks at nothing. */
    const float lo[3] = { 200, 200, 200 }, hi[3] = { 201, 201, 201 };
    assert_int_equal(check_query(&bvh, &m, lo, hi), 0);
    tb_bvh_free(&bvh);
    mesh_free(&m);
}

/* A flat terrain of a million triangles (a 708 x 708 grid): built, flat along y (its
 * quantization has no height range), and walked under a falling box's footprint. */
static void test_million_triangle_terrain(void** state)
{
    (void)state;
    mesh m = flat_grid(708);
    assert_true(m.triangle_count > 1000000);
    tb_bvh bvh = build_or_fail(&m);
    assert_true(bvh.lo[1] == 0 && bvh.hi[1] == 0);
    const float lo[3] = { 100.2f, -0.5f, 300.7f }, hi[3] = { 101.4f, 0.5f, 301.1f };
    found f = { calloc(m.triangle_count, 1), 0 };
    assert_non_null(f.hit);
    uint32_t looked = tb_bvh_query(&bvh, lo, hi, mark, &f);
    /* x 100..102 (2 cells) times z 300..302 (2 cells), 2 triangles a cell; the shared
     * edges at x = 101 and z = 301 are inside the box, the cells beyond touch it only if
     * rounding widens it, which it may by one step. */
    assert_true(f.count >= 8 && f.count <= 18);
    assert_true(looked < 500);
    print_message("terrain: %u triangles found, %u of %u nodes looked at\n", f.count, looked,
                  bvh.node_count);
    free(f.hit);
    tb_bvh_free(&bvh);
    mesh_free(&m);
}

static void test_same_tree_every_build(void** state)
{
    (void)state;
    mesh m = random_soup(3000, 1.0f, 3);
    tb_bvh a = build_or_fail(&m), b = build_or_fail(&m);
    assert_int_equal(a.node_count, b.node_count);
    assert_memory_equal(a.nodes, b.nodes, a.node_count * sizeof *a.nodes);
    tb_bvh_free(&a);
    tb_bvh_free(&b);
    mesh_free(&m);
}

/* ---- bad input -------------------------------------------------------------------------- */

static void expect_refused(const float* xyz, uint32_t vertices, const uint32_t* indices,
                           uint32_t triangles, const char* words)
{
    tb_bvh out;
    memset(&out, 0xab, sizeof out);
    tb_bvh before = out;
    char error[256] = "";
    assert_int_equal(tb_bvh_build(xyz, vertices, indices, triangles, &out, error, sizeof error), -1);
    assert_memory_equal(&out, &before, sizeof out);
    if (!strstr(error, words)) fail_msg("error \"%s\" does not say \"%s\"", error, words);
}

static void test_bad_input_refused(void** state)
{
    (void)state;
    float xyz[9] = { 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    uint32_t tri[3] = { 0, 1, 2 };
    expect_refused(xyz, 3, tri, 0, "at least one triangle");
    expect_refused(NULL, 3, tri, 1, "at least one triangle");
    expect_refused(xyz, 3, NULL, 1, "at least one triangle");
    uint32_t far[3] = { 0, 1, 3 };
    expect_refused(xyz, 3, far, 1, "triangle 0 uses vertex 3 of 3");
    xyz[4] = NAN;
    expect_refused(xyz, 3, tri, 1, "vertex 1 is not finite");
    xyz[4] = INFINITY;
    expect_refused(xyz, 3, tri, 1, "vertex 1 is not finite");
    xyz[4] = 0;
    expect_refused(xyz, 3, tri, TB_BVH_MAX_TRIANGLES + 1, "at most");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_structure_of_random_soups),
        cmocka_unit_test(test_walk_matches_brute_force),
        cmocka_unit_test(test_million_triangle_terrain),
        cmocka_unit_test(test_same_tree_every_build),
        cmocka_unit_test(test_bad_input_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
