/* The mesh BVH (src/geom/bvh.c): its structure (every triangle in one leaf, skip indices
 * that end each subtree, boxes that contain what lies below them), the stackless walk
 * against brute force on random soups and a flat terrain grid of a million triangles, the
 * same tree on every build, and bad input refused with a sentence, on the host; then the
 * same walk on the GPU (glsl/midphase/bvh.glsl, driven by midphase/bvh_query on lavapipe)
 * against the host's walk and brute force. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "gpu/prims.h"
#include "world/world.h"

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

/* ---- the walk on the GPU ---------------------------------------------------------------- */

#define GPU_QUERIES 512u
#define GPU_KEEP 256u

static tb_buffer storage(tb_world* w, VkDeviceSize bytes)
{
    tb_buffer b;
    th_assert_ok(tb_buffer_create(&w->memory, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, &b));
    return b;
}

/* 512 random boxes (some beside the mesh, some large) walked by midphase/bvh_query: each
 * finds every triangle the host's walk finds (the GPU rounds its query one step wider, so it
 * may find a little more, never anything far), nothing twice, and looks at about as many
 * nodes. */
static void test_gpu_walk_matches_host(void** state)
{
    (void)state;
    mesh m = random_soup(4000, 1.5f, 21);
    tb_bvh bvh = build_or_fail(&m);
    tb_world* w = th_world_create(NULL);
    VkPipeline pipeline;
    th_assert_ok(tb_pipeline_create(&w->pipelines, "midphase/bvh_query", 64, &pipeline));
    tb_buffer nodes = storage(w, bvh.node_count * sizeof *bvh.nodes);
    tb_buffer queries = storage(w, 2 * GPU_QUERIES * sizeof(tb_gpu_vec4));
    tb_buffer results = storage(w, GPU_QUERIES * (GPU_KEEP + 2) * sizeof(uint32_t));
    memcpy(nodes.mapped, bvh.nodes, bvh.node_count * sizeof *bvh.nodes);
    tb_gpu_vec4* box = queries.mapped;
    th_rng rng = th_rng_seed(22);
    for (uint32_t q = 0; q < GPU_QUERIES; q++) {
        float half = th_rng_range(&rng, 0, q % 16 == 0 ? 16.0f : 6.0f), c[3];
        for (int a = 0; a < 3; a++) c[a] = th_rng_range(&rng, -70, 70);
        box[2 * q] = (tb_gpu_vec4){ c[0] - half, c[1] - half, c[2] - half, 0 };
        box[2 * q + 1] = (tb_gpu_vec4){ c[0] + half, c[1] + half, c[2] + half, 0 };
    }
    tb_gpu_bvh_query_push push;
    memset(&push, 0, sizeof push);
    push.arrays = tb_gpu_addresses(nodes.address, queries.address);
    push.results = tb_gpu_addresses(results.address, 0);
    push.results.z = GPU_KEEP;
    push.results.w = GPU_QUERIES;
    uint32_t node_count = bvh.node_count;
    float count_bits;
    memcpy(&count_bits, &node_count, sizeof count_bits);
    double scale[3];
    tb_bvh_steps_per_metre(&bvh, scale);
    for (int a = 0; a < 3; a++) {
        (&push.mesh_lo.x)[a] = bvh.lo[a];
        (&push.mesh_hi.x)[a] = bvh.hi[a];
        (&push.scale.x)[a] = (float)scale[a];
    }
    push.mesh_lo.w = count_bits;
    tb_pass pass = { .pipeline = pipeline, .rule = TB_DISPATCH_FIXED,
                     .groups = { (GPU_QUERIES + 63) / 64, 1, 1 }, .push_size = sizeof push };
    memcpy(pass.push, &push, sizeof push);
    VkCommandBuffer cb;
    th_assert_ok(tb_gpu_command_buffer(&w->gpu, &cb));
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO };
    assert_int_equal(vkBeginCommandBuffer(cb, &begin), VK_SUCCESS);
    tb_passes_record(cb, w->pipelines.layout, &pass, 1, w->params_buffer.buffer);
    VkMemoryBarrier to_host = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT };
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                         1, &to_host, 0, NULL, 0, NULL);
    assert_int_equal(vkEndCommandBuffer(cb), VK_SUCCESS);
    th_assert_ok(tb_gpu_submit_wait(&w->gpu, &cb, 1));

    const uint32_t* got = results.mapped;
    found host = { malloc(m.triangle_count), 0 };
    uint8_t* on_gpu = calloc(m.triangle_count, 1);
    assert_non_null(host.hit);
    assert_non_null(on_gpu);
    uint32_t total = 0, empty = 0;
    for (uint32_t q = 0; q < GPU_QUERIES; q++) {
        const float lo[3] = { box[2 * q].x, box[2 * q].y, box[2 * q].z };
        const float hi[3] = { box[2 * q + 1].x, box[2 * q + 1].y, box[2 * q + 1].z };
        memset(host.hit, 0, m.triangle_count);
        host.count = 0;
        uint32_t looked = tb_bvh_query(&bvh, lo, hi, mark, &host);
        const uint32_t* row = got + q * (GPU_KEEP + 2);
        uint32_t n = row[0];
        assert_true(n >= host.count && n <= GPU_KEEP);
        /* The same walk: a step wider may look at a few more nodes, never many. */
        if (row[1] < looked || row[1] > looked + looked / 4 + 8)
            fail_msg("query %u: the GPU looked at %u nodes, the host at %u", q, row[1], looked);
        empty += n == 0;
        total += n;
        memset(on_gpu, 0, m.triangle_count);
        for (uint32_t k = 0; k < n; k++) {
            assert_true(row[2 + k] < m.triangle_count);
            assert_int_equal(on_gpu[row[2 + k]]++, 0);
            float tlo[3], thi[3], wide_lo[3], wide_hi[3];
            triangle_box(&m, row[2 + k], tlo, thi);
            for (int a = 0; a < 3; a++) {
                float step = (bvh.hi[a] - bvh.lo[a]) / 65535.0f;
                wide_lo[a] = lo[a] - 4 * step;
                wide_hi[a] = hi[a] + 4 * step;
            }
            if (!box_overlap(tlo, thi, wide_lo, wide_hi))
                fail_msg("query %u: the GPU found triangle %u far away", q, row[2 + k]);
        }
        for (uint32_t t = 0; t < m.triangle_count; t++)
            if (host.hit[t] && !on_gpu[t]) fail_msg("query %u: the GPU missed triangle %u", q, t);
    }
    print_message("GPU walk: %u triangles found by %u queries, %u found none\n", total,
                  GPU_QUERIES, empty);
    assert_true(total > GPU_QUERIES && empty > 0);
    free(host.hit);
    free(on_gpu);
    tb_buffer_destroy(&w->memory, &nodes);
    tb_buffer_destroy(&w->memory, &queries);
    tb_buffer_destroy(&w->memory, &results);
    tb_pipeline_destroy(&w->pipelines, pipeline);
    th_world_destroy(w);
    tb_bvh_free(&bvh);
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
        cmocka_unit_test(test_gpu_walk_matches_host),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
