/* Every broadphase against brute force: after a step, the pairs the GPU found must be
 * exactly the pairs of AABBs (as that step computed them, grown by the contact margin)
 * that overlap, each once, none static-static. Scenes: empty, one body, uniform, mixed
 * sizes 1:1000, clusters far apart, all bodies in one place, duplicates, touching boxes,
 * planes and big static boxes, dead slots, and bodies moving over many steps while others
 * come and go. Each scene runs with each broadphase. */
#include "harness.h"

#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "world/world.h"
#include "broadphase/isap.h"

typedef struct pair { uint32_t a, b; } pair;

static int pair_order(const void* x, const void* y)
{
    const pair* p = x;
    const pair* q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

/* The pairs of the last step, as (lower slot, higher slot), sorted. */
static pair* gpu_pairs(tb_world* w, uint32_t* count)
{
    const tb_gpu_counters* c = tb_sim_counters(&w->sim);
    uint32_t n = c->state.z;
    assert_true(n <= w->sim.pair_capacity);
    uint32_t half = (uint32_t)((w->gpu_steps - 1) & 1);
    tb_transfer* t = &w->transfer;
    th_assert_ok(tb_transfer_begin(t, (VkDeviceSize)n * 16 + 64));
    const tb_gpu_uvec4* raw = tb_transfer_download(t, w->sim.pair[TB_SIM_PAIRS].buffer,
                                                   (VkDeviceSize)half * w->sim.pair_capacity * 16,
                                                   (VkDeviceSize)n * 16 + 16);
    th_assert_ok(tb_transfer_end(t));
    th_assert_ok(tb_gpu_submit_wait(&w->gpu, &t->cb, 1));
    pair* out = calloc(n + 1, sizeof *out);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a = raw[i].x, b = raw[i].y;
        out[i] = (pair){ a < b ? a : b, a < b ? b : a };
    }
    qsort(out, n, sizeof *out, pair_order);
    *count = n;
    return out;
}

static int touch(const tb_vec3* mn, const tb_vec3* mx, uint32_t i, uint32_t j, float m)
{
    return !(mn[i].x - m > mx[j].x || mn[j].x - m > mx[i].x || mn[i].y - m > mx[j].y ||
             mn[j].y - m > mx[i].y || mn[i].z - m > mx[j].z || mn[j].z - m > mx[i].z);
}

/* Brute force over the AABBs the step used (world_aabb runs first in the step). */
static pair* brute_pairs(tb_world* w, uint32_t* count)
{
    uint32_t slots = w->body_slots.used;
    tb_body_id* ids = calloc(slots + 1, sizeof *ids);
    tb_vec3* mn = calloc(slots + 1, sizeof *mn);
    tb_vec3* mx = calloc(slots + 1, sizeof *mx);
    tb_body_type* type = calloc(slots + 1, sizeof *type);
    uint32_t live = tb_world_body_ids(w, ids, slots);
    th_assert_ok(tb_world_read_aabbs(w, ids, live, mn, mx));
    for (uint32_t i = 0; i < live; i++) th_assert_ok(tb_body_get_type(w, ids[i], &type[i]));
    size_t cap = 1024, n = 0;
    pair* out = malloc(cap * sizeof *out);
    for (uint32_t i = 0; i < live; i++) {
        for (uint32_t j = i + 1; j < live; j++) {
            if (type[i] == TB_BODY_STATIC && type[j] == TB_BODY_STATIC) continue;
            if (!touch(mn, mx, i, j, w->contact_margin)) continue;
            if (n == cap) out = realloc(out, (cap *= 2) * sizeof *out);
            out[n++] = (pair){ ids[i].index1 - 1, ids[j].index1 - 1 };
        }
    }
    qsort(out, n, sizeof *out, pair_order);
    free(ids);
    free(type);
    free(mn);
    free(mx);
    *count = (uint32_t)n;
    return out;
}

/* The last step's pairs equal brute force's. */
static void expect_same_pairs(tb_world* w)
{
    uint32_t ng, nb;
    pair* g = gpu_pairs(w, &ng);
    pair* b = brute_pairs(w, &nb);
    for (uint32_t i = 0; i + 1 < ng; i++)
        if (g[i].a == g[i + 1].a && g[i].b == g[i + 1].b)
            fail_msg("pair (%u, %u) reported twice", g[i].a, g[i].b);
    uint32_t i = 0, j = 0;
    while (i < ng || j < nb) {
        int o = i < ng && j < nb ? pair_order(&g[i], &b[j]) : (i < ng ? -1 : 1);
        if (o < 0) fail_msg("GPU pair (%u, %u) does not overlap", g[i].a, g[i].b);
        if (o > 0) fail_msg("overlapping pair (%u, %u) missed", b[j].a, b[j].b);
        i++, j++;
    }
    assert_int_equal(th_stats(w).pair_count, nb);
    free(g);
    free(b);
}

static void expect_brute_force_pairs(tb_world* w)
{
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    expect_same_pairs(w);
}

/* The broadphase under test (each test runs once per kind; cmocka's initial state). */
static tb_broadphase kind_of(void** state)
{
    return *(const tb_broadphase*)*state;
}

static tb_world* kind_world(void** state, tb_world_def* def)
{
    def->broadphase = kind_of(state);
    def->substeps = 1;   /* the pairs are under test, not the solver: keep the step short */
    tb_world* w = th_world_create(def);
    assert_string_equal(th_stats(w).broadphase, tb_broadphase_name(kind_of(state)));
    return w;
}

static tb_world* zero_gravity_world(void** state)
{
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    def.initial_body_capacity = 64;
    def.initial_pair_capacity = 16;   /* small on purpose: the pair buffer must grow */
    return kind_world(state, &def);
}

static void random_bodies(tb_world* w, th_rng* rng, uint32_t n, float extent, float lo, float hi,
                          float static_share)
{
    for (uint32_t i = 0; i < n; i++) {
        float size = lo * powf(hi / lo, th_rng_range(rng, 0, 1));
        tb_shape_id s = (th_rng_u32(rng) & 1)
                            ? th_sphere(w, size)
                            : th_box(w, th_v3(size, size * th_rng_range(rng, 0.3f, 1), size));
        tb_vec3 p = th_v3(th_rng_range(rng, -extent, extent), th_rng_range(rng, -extent, extent),
                          th_rng_range(rng, -extent, extent));
        tb_body_def d = th_rng_range(rng, 0, 1) < static_share ? th_static_def(s, p)
                                                                : th_dynamic_def(s, p);
        d.rotation = th_rng_quat(rng);
        th_body(w, &d);
    }
}

/* Each dynamic body of `ids` gets linear and angular velocities up to `speed` per axis. */
static void random_velocities(tb_world* w, th_rng* rng, const tb_body_id* ids, uint32_t n,
                              float speed)
{
    for (uint32_t i = 0; i < n; i++) {
        tb_vec3 v = th_v3(th_rng_range(rng, -speed, speed), th_rng_range(rng, -speed, speed),
                          th_rng_range(rng, -speed, speed));
        tb_body_type t;
        th_assert_ok(tb_body_get_type(w, ids[i], &t));
        if (t == TB_BODY_DYNAMIC) th_assert_ok(tb_body_set_velocity(w, ids[i], v, v));
    }
}

static void test_uniform(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(1);
    random_bodies(w, &rng, 2000, 3.0f, 0.2f, 0.25f, 0.1f);
    expect_brute_force_pairs(w);
    assert_true(th_stats(w).steps_redone >= 1);   /* 16 pairs could not hold them */
    expect_brute_force_pairs(w);                  /* and again, after the bodies moved */
    th_world_destroy(w);
}

static void test_mixed_sizes(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(2);
    random_bodies(w, &rng, 800, 10.0f, 0.01f, 10.0f, 0.3f);
    expect_brute_force_pairs(w);
    th_world_destroy(w);
}

static void test_duplicates_and_touching(void** state)
{
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    def.contact_margin = 0.0f;   /* touching faces must still count */
    tb_world* w = kind_world(state, &def);
    tb_shape_id box = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
    for (int i = 0; i < 5; i++) {           /* five bodies in one place */
        tb_body_def d = th_dynamic_def(box, th_v3(0, 0, 0));
        th_body(w, &d);
    }
    for (int x = 0; x < 6; x++)             /* a row of boxes face to face */
        for (int y = 0; y < 3; y++) {
            tb_body_def d = th_dynamic_def(box, th_v3(5.0f + (float)x, (float)y, 0));
            th_body(w, &d);
        }
    expect_brute_force_pairs(w);
    th_world_destroy(w);
}

static void test_large_statics_and_dead_slots(void** state)
{
    tb_world* w = zero_gravity_world(state);
    tb_shape_id ground = th_plane(w, th_v3(0, 1, 0), 0.0f);
    tb_shape_id wall = th_box(w, th_v3(20.0f, 5.0f, 0.5f));
    tb_body_def g = th_static_def(ground, th_v3(0, -1.0f, 0));
    th_body(w, &g);
    tb_body_def wd = th_static_def(wall, th_v3(0, 0, 3.0f));
    th_body(w, &wd);
    tb_body_def g2 = th_static_def(wall, th_v3(0, 0, -3.0f));   /* static-static overlap */
    g2.rotation = th_quat_axis_angle(th_v3(0, 1, 0), 1.2);
    th_body(w, &g2);
    th_rng rng = th_rng_seed(3);
    random_bodies(w, &rng, 800, 4.0f, 0.1f, 0.3f, 0.0f);
    tb_body_id ids[900];
    uint32_t n = tb_world_body_ids(w, ids, 900);
    for (uint32_t i = 3; i < n; i += 7) th_assert_ok(tb_body_destroy(w, ids[i]));
    expect_brute_force_pairs(w);
    th_world_destroy(w);
}

static void test_empty_and_single(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    assert_int_equal(th_stats(w).pair_count, 0);
    tb_body_def d = th_dynamic_def(th_sphere(w, 1.0f), th_v3(0, 0, 0));
    th_body(w, &d);
    expect_brute_force_pairs(w);
    assert_int_equal(th_stats(w).pair_count, 0);
    th_world_destroy(w);
}

/* Tight clusters a kilometre apart: dense overlaps in a huge, mostly empty world. */
static void test_clusters(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(4);
    tb_shape_id ball = th_sphere(w, 0.1f);
    for (int c = 0; c < 8; c++) {
        tb_vec3 at = th_v3(1000.0f * (float)(c % 2), 1000.0f * (float)((c / 2) % 2),
                           -1000.0f * (float)(c / 4));
        for (int i = 0; i < 120; i++) {
            tb_vec3 p = th_v3(at.x + th_rng_range(&rng, -0.6f, 0.6f),
                              at.y + th_rng_range(&rng, -0.6f, 0.6f),
                              at.z + th_rng_range(&rng, -0.6f, 0.6f));
            tb_body_def d = (i % 5) ? th_dynamic_def(ball, p) : th_static_def(ball, p);
            th_body(w, &d);
        }
    }
    expect_brute_force_pairs(w);
    th_world_destroy(w);
}

/* Every body in the same place: every pair overlaps (n (n - 1) / 2 of them). */
static void test_all_in_one_place(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(5);
    tb_shape_id box = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
    for (int i = 0; i < 200; i++) {
        tb_vec3 p = th_v3(th_rng_range(&rng, -0.01f, 0.01f), th_rng_range(&rng, -0.01f, 0.01f),
                          th_rng_range(&rng, -0.01f, 0.01f));
        tb_body_def d = th_dynamic_def(box, p);
        th_body(w, &d);
    }
    expect_brute_force_pairs(w);
    assert_int_equal(th_stats(w).pair_count, 200 * 199 / 2);
    th_world_destroy(w);
}

/* Bodies drifting through each other for many steps (the solver pushes overlapping ones
 * apart, so the order changes a little every step), with bodies destroyed and created in
 * between: every step's pairs must be right, not only the first's. */
static void test_moving_over_many_steps(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(6);
    random_bodies(w, &rng, 700, 4.0f, 0.1f, 0.5f, 0.05f);
    tb_body_id ids[1000];
    uint32_t n = tb_world_body_ids(w, ids, 1000);
    random_velocities(w, &rng, ids, n, 3.0f);
    for (int step = 0; step < 24; step++) {
        if (step == 8)
            for (uint32_t i = 0; i < n; i += 5) th_assert_ok(tb_body_destroy(w, ids[i]));
        if (step == 16) random_bodies(w, &rng, 150, 4.0f, 0.1f, 0.5f, 0.0f);
        expect_brute_force_pairs(w);
    }
    th_world_destroy(w);
}

/* The incremental sort and sweep's counts of searches run incrementally and from scratch. */
static tb_gpu_uvec4 isap_stats(tb_world* w)
{
    const tb_isap_state* s = w->bp.state;
    tb_transfer* t = &w->transfer;
    th_assert_ok(tb_transfer_begin(t, 64));
    const tb_gpu_uvec4* stats = tb_transfer_download(t, s->state.buffer, TB_ISAP_CONTROL_OFFSET +
                                                     offsetof(tb_gpu_isap_control, stats), 16);
    th_assert_ok(tb_transfer_end(t));
    th_assert_ok(tb_gpu_submit_wait(&w->gpu, &t->cb, 1));
    return *stats;
}

/* A dense crowd drifting slowly on a ground plane beside a large static box, for many
 * steps: the orders change a little every step, which the incremental search must follow
 * (and, for isap, really does: most steps are not searched from scratch). */
static void test_slow_drift(void** state)
{
    tb_world* w = zero_gravity_world(state);
    tb_body_def g = th_static_def(th_plane(w, th_v3(0, 1, 0), 0.0f), th_v3(0, -2.0f, 0));
    th_body(w, &g);
    tb_body_def wall = th_static_def(th_box(w, th_v3(6.0f, 0.5f, 0.5f)), th_v3(0, 0, 2.0f));
    th_body(w, &wall);
    th_rng rng = th_rng_seed(7);
    random_bodies(w, &rng, 500, 2.0f, 0.1f, 0.3f, 0.05f);
    tb_body_id ids[600];
    uint32_t n = tb_world_body_ids(w, ids, 600);
    random_velocities(w, &rng, ids, n, 0.6f);
    for (int step = 0; step < 40; step++) expect_brute_force_pairs(w);
    if (kind_of(state) == TB_BROADPHASE_ISAP) {
        tb_gpu_uvec4 runs = isap_stats(w);
        print_message("isap: %u incremental, %u from scratch\n", runs.x, runs.y);
        assert_true(runs.x >= 25);
    }
    th_world_destroy(w);
}

/* Every step every dynamic body jumps to a new place in the crowd: last step's orders tell
 * nothing, the incremental search would scan nearly everything, so isap must search from
 * scratch each step (the set of bodies never changes: the moves alone decide it). */
static void test_teleports(void** state)
{
    tb_world* w = zero_gravity_world(state);
    th_rng rng = th_rng_seed(8);
    random_bodies(w, &rng, 400, 2.0f, 0.1f, 0.3f, 0.1f);
    tb_body_id ids[400];
    uint32_t n = tb_world_body_ids(w, ids, 400);
    expect_brute_force_pairs(w);
    tb_gpu_uvec4 before = kind_of(state) == TB_BROADPHASE_ISAP ? isap_stats(w) : (tb_gpu_uvec4){ 0 };
    enum { JUMPS = 8 };
    for (int step = 0; step < JUMPS; step++) {
        for (uint32_t i = 0; i < n; i++) {
            tb_body_type t;
            th_assert_ok(tb_body_get_type(w, ids[i], &t));
            if (t != TB_BODY_DYNAMIC) continue;
            tb_vec3 p = th_v3(th_rng_range(&rng, -2, 2), th_rng_range(&rng, -2, 2),
                              th_rng_range(&rng, -2, 2));
            th_assert_ok(tb_body_set_pose(w, ids[i], p, th_rng_quat(&rng)));
        }
        expect_brute_force_pairs(w);
    }
    if (kind_of(state) == TB_BROADPHASE_ISAP) {
        tb_gpu_uvec4 after = isap_stats(w);
        print_message("isap: %u incremental, %u from scratch over %d jumps\n",
                      after.x - before.x, after.y - before.y, JUMPS);
        assert_true(after.y - before.y >= JUMPS);
    }
    th_world_destroy(w);
}

static const tb_broadphase kinds[] = {
    TB_BROADPHASE_GRID,
    TB_BROADPHASE_SAP,
    TB_BROADPHASE_LBVH,
    TB_BROADPHASE_ISAP,
};

#define SCENES(X) X(test_empty_and_single) X(test_uniform) X(test_mixed_sizes) \
    X(test_clusters) X(test_all_in_one_place) X(test_duplicates_and_touching) \
    X(test_large_statics_and_dead_slots) X(test_moving_over_many_steps) X(test_slow_drift) \
    X(test_teleports)
#define SCENE_COUNT 10

int main(void)
{
    enum { KINDS = sizeof kinds / sizeof kinds[0] };
    struct CMUnitTest tests[KINDS * SCENE_COUNT];
    char names[KINDS * SCENE_COUNT][96];
    uint32_t n = 0;
    for (uint32_t k = 0; k < KINDS; k++) {
#define ADD(fn)                                                                           \
        snprintf(names[n], sizeof names[n], "%s/%s", tb_broadphase_name(kinds[k]), #fn);    \
        tests[n] = (struct CMUnitTest){ names[n], fn, NULL, NULL, (void*)&kinds[k] };     \
        n++;
        SCENES(ADD)
#undef ADD
    }
    return _cmocka_run_group_tests("broadphase", tests, n, NULL, NULL);
}
