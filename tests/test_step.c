/* The step as a whole: determinism, step_n, command-buffer reuse and growth, slot reuse,
 * stats and device info, bulk creation. */
#include "harness.h"
#include "scenes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)

/* ---- a mixed scene: spheres and boxes, random poses, spins, some damping ---------------- */

static void build_mixed(tb_world* w, uint32_t n, uint64_t seed, tb_body_id* ids)
{
    th_rng rng = th_rng_seed(seed);
    tb_shape_id s = th_sphere(w, 0.4f), b = th_box(w, th_v3(0.3f, 0.5f, 0.7f));
    tb_body_def* defs = malloc(n * sizeof *defs);
    assert_non_null(defs);
    for (uint32_t i = 0; i < n; i++) {
        tb_body_def d = th_dynamic_def(i % 2 ? b : s, th_v3(th_rng_range(&rng, -40, 40),
                                                              th_rng_range(&rng, 0, 40),
                                                              th_rng_range(&rng, -40, 40)));
        d.rotation = th_rng_quat(&rng);
        d.linear_velocity = th_v3(th_rng_range(&rng, -5, 5), th_rng_range(&rng, -5, 5), 0);
        d.angular_velocity = th_v3(th_rng_range(&rng, -9, 9), th_rng_range(&rng, -9, 9),
                                   th_rng_range(&rng, -90, 90)); /* some beyond the clamp */
        d.linear_damping = i % 3 ? 0.0f : 0.3f;
        d.angular_damping = i % 5 ? 0.0f : 1.0f;
        d.type = i % 17 ? TB_BODY_DYNAMIC : TB_BODY_STATIC;
        defs[i] = d;
    }
    th_assert_ok(tb_body_create_many(w, defs, n, ids));
    free(defs);
}

/* Everything the GPU computes for these bodies, as bytes. */
typedef struct state_dump {
    tb_vec3* p;
    tb_quat* q;
    tb_vec3* v;
    tb_vec3* av;
} state_dump;

static state_dump dump(tb_world* w, const tb_body_id* ids, uint32_t n)
{
    state_dump s = { calloc(n, sizeof(tb_vec3)), calloc(n, sizeof(tb_quat)),
                     calloc(n, sizeof(tb_vec3)), calloc(n, sizeof(tb_vec3)) };
    assert_true(s.p && s.q && s.v && s.av);
    th_assert_ok(tb_world_read_transforms(w, ids, n, s.p, s.q));
    for (uint32_t i = 0; i < n; i++)
        th_assert_ok(tb_body_get_velocity(w, ids[i], &s.v[i], &s.av[i]));
    return s;
}

static void dump_free(state_dump* s)
{
    free(s->p); free(s->q); free(s->v); free(s->av);
}

static void assert_same_state(tb_world* a, const tb_body_id* ia, tb_world* b,
                              const tb_body_id* ib, uint32_t n)
{
    state_dump x = dump(a, ia, n), y = dump(b, ib, n);
    assert_memory_equal(x.p, y.p, n * sizeof(tb_vec3));
    assert_memory_equal(x.q, y.q, n * sizeof(tb_quat));
    assert_memory_equal(x.v, y.v, n * sizeof(tb_vec3));
    assert_memory_equal(x.av, y.av, n * sizeof(tb_vec3));
    dump_free(&x);
    dump_free(&y);
}

/* Two worlds, same scene, same calls: bit-identical results. */
static void test_determinism_mixed(void** state)
{
    (void)state;
    enum { N = 300 };
    tb_body_id ia[N], ib[N];
    tb_world* a = th_world_create(NULL);
    tb_world* b = th_world_create(NULL);
    build_mixed(a, N, 99, ia);
    build_mixed(b, N, 99, ib);
    for (int k = 0; k < 3; k++) {
        th_assert_ok(tb_world_step_n(a, DT, 20));
        th_assert_ok(tb_world_step_n(b, DT, 20));
        assert_same_state(a, ia, b, ib, N);
    }
    /* ...and the scene actually moved (a frozen world is trivially deterministic):
     * body 1 is an undamped dynamic box with vy0 <= 5 after 1 s of gravity. */
    state_dump s = dump(a, ia, 2);
    assert_true(s.v[1].y < 5.0f - 9.81f + 0.01f);
    dump_free(&s);
    th_world_destroy(a);
    th_world_destroy(b);
}

/* The shared "freefall" scene (n 500, seed 1) twice: bit-identical, and on its curve. */
static void test_determinism_freefall_scene(void** state)
{
    (void)state;
    const scene* sc = scene_find("freefall");
    assert_non_null(sc);
    scene_params params = { 500, 1 };
    tb_world* w[2];
    scene_instance* inst[2];
    for (int i = 0; i < 2; i++) {
        w[i] = th_world_create(NULL);
        th_assert_ok(sc->build(w[i], &params, &inst[i]));
        th_assert_ok(tb_world_step_n(w[i], sc->dt, 30));
    }
    uint32_t na, nb;
    const tb_body_id* ia = scene_body_ids(inst[0], &na);
    const tb_body_id* ib = scene_body_ids(inst[1], &nb);
    assert_int_equal(na, 500);
    assert_int_equal(nb, 500);
    assert_same_state(w[0], ia, w[1], ib, na);
    scene_checks checks;
    memset(&checks, 0, sizeof checks);
    th_assert_ok(sc->check(w[0], inst[0], 30, sc->dt, &checks));
    for (uint32_t i = 0; i < checks.count; i++) {
        if (strcmp(checks.items[i].key, "nan") == 0) assert_true(checks.items[i].value == 0);
        if (strcmp(checks.items[i].key, "max_error") == 0)
            assert_true(checks.items[i].value < 1e-3);
    }
    for (int i = 0; i < 2; i++) {
        sc->destroy(inst[i]);
        th_world_destroy(w[i]);
    }
}

/* step_n(10) is ten step() calls, bit for bit, in one submission. */
static void test_step_n_equals_steps(void** state)
{
    (void)state;
    enum { N = 100 };
    tb_body_id ia[N], ib[N];
    tb_world* a = th_world_create(NULL);
    tb_world* b = th_world_create(NULL);
    build_mixed(a, N, 5, ia);
    build_mixed(b, N, 5, ib);
    tb_world_stats sa0 = th_stats(a), sb0 = th_stats(b);
    th_assert_ok(tb_world_step_n(a, DT, 10));
    for (int k = 0; k < 10; k++) th_assert_ok(tb_world_step(b, DT));
    assert_same_state(a, ia, b, ib, N);
    tb_world_stats sa = th_stats(a), sb = th_stats(b);
    assert_int_equal(sa.steps - sa0.steps, 10);
    assert_int_equal(sb.steps - sb0.steps, 10);
    assert_int_equal(sa.submits - sa0.submits, 1);
    assert_int_equal(sb.submits - sb0.submits, 10);
    th_world_destroy(a);
    th_world_destroy(b);
}

/* tb_world_step_n's steps go in batches of 4096 a submission (a submission lists every
 * step's command buffer: 2^32 steps asked for 32 GiB of them); TUMBLE_STEPS_PER_SUBMIT=4
 * makes the batches small enough to see here. 10 steps: three submissions, and the same
 * state as one submission of 10. */
static void test_step_n_in_batches(void** state)
{
    (void)state;
    enum { N = 20 };
    tb_body_id ia[N], ib[N];
    tb_world* a = th_world_create(NULL);
    setenv("TUMBLE_STEPS_PER_SUBMIT", "4", 1);
    tb_world* b = th_world_create(NULL);
    unsetenv("TUMBLE_STEPS_PER_SUBMIT");
    build_mixed(a, N, 5, ia);
    build_mixed(b, N, 5, ib);
    tb_world_stats before = th_stats(b);
    th_assert_ok(tb_world_step_n(a, DT, 10));
    th_assert_ok(tb_world_step_n(b, DT, 10));
    assert_same_state(a, ia, b, ib, N);
    tb_world_stats after = th_stats(b);
    assert_int_equal(after.steps - before.steps, 10);
    assert_int_equal(after.submits - before.submits, 3);
    th_world_destroy(a);
    th_world_destroy(b);
}

/* ---- adding bodies: no re-record within capacity, growth keeps state --------------------- */

typedef struct faller {
    tb_body_id id;
    double x[3], v[3];
} faller;

static void add_fallers(tb_world* w, tb_shape_id s, faller* f, int first, int count)
{
    for (int i = first; i < first + count; i++) {
        tb_body_def d = th_dynamic_def(s, th_v3((float)(i % 20) * 2.0f, 100.0f + (float)(i / 20),
                                                (float)i * 0.1f));
        d.linear_velocity = th_v3(0, (float)(i % 7) - 3.0f, 0.5f);
        f[i].id = th_body(w, &d);
        f[i].x[0] = d.position.x; f[i].x[1] = d.position.y; f[i].x[2] = d.position.z;
        f[i].v[0] = d.linear_velocity.x; f[i].v[1] = d.linear_velocity.y;
        f[i].v[2] = d.linear_velocity.z;
    }
}

/* Step the GPU and the double reference of the first `count` fallers together. */
static void step_fallers(tb_world* w, faller* f, int count, int steps)
{
    const tb_vec3 g = tb_world_get_gravity(w);
    const int substeps = (int)tb_default_world_def().substeps;
    const double gv[3] = { g.x, g.y, g.z }, h = (double)DT / substeps;
    th_assert_ok(tb_world_step_n(w, DT, (uint32_t)steps));
    for (int i = 0; i < count; i++)
        for (int k = 0; k < steps * substeps; k++)
            for (int a = 0; a < 3; a++) {
                f[i].v[a] += gv[a] * h;
                f[i].x[a] += f[i].v[a] * h;
            }
}

static void check_fallers(tb_world* w, const faller* f, int count)
{
    for (int i = 0; i < count; i++) {
        tb_vec3 p, v, av;
        th_read_pose(w, f[i].id, &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, f[i].id, &v, &av));
        th_assert_vec3_near(p, th_v3((float)f[i].x[0], (float)f[i].x[1], (float)f[i].x[2]),
                            1e-4, 1e-6);
        th_assert_vec3_near(v, th_v3((float)f[i].v[0], (float)f[i].v[1], (float)f[i].v[2]),
                            1e-5, 1e-5);
    }
}

static void test_growth_and_records(void** state)
{
    (void)state;
    enum { CAP = 64, TOTAL = 220 };
    tb_world_def wd = tb_default_world_def();
    wd.initial_body_capacity = CAP;
    tb_world* w = th_world_create(&wd);
    tb_shape_id s = th_sphere(w, 0.2f);
    static faller f[TOTAL];
    add_fallers(w, s, f, 0, 10);
    step_fallers(w, f, 10, 5);
    /* The first submission fits the recorded colouring rounds to the colours the scene uses
     * (no contacts here: the fewest); the step records once more, then never again. */
    step_fallers(w, f, 10, 1);
    tb_world_stats st0 = th_stats(w);
    assert_true(st0.body_capacity >= CAP && st0.body_capacity < TOTAL);

    /* Within capacity: the same command buffer (indirect dispatch) serves more bodies. */
    add_fallers(w, s, f, 10, 10);
    step_fallers(w, f, 20, 5);
    tb_world_stats st1 = th_stats(w);
    assert_int_equal(st1.records, st0.records);
    assert_int_equal(st1.buffer_growths, st0.buffer_growths);
    assert_int_equal(st1.body_count, 20);
    check_fallers(w, f, 20);

    /* Past capacity: the buffers grow and the step is re-recorded; old bodies keep state. */
    add_fallers(w, s, f, 20, TOTAL - 20);
    step_fallers(w, f, TOTAL, 5);
    tb_world_stats st2 = th_stats(w);
    assert_true(st2.buffer_growths > st1.buffer_growths);
    assert_true(st2.records > st1.records);
    assert_true(st2.body_capacity >= TOTAL);
    assert_int_equal(st2.body_count, TOTAL);
    check_fallers(w, f, TOTAL);

    /* And after growing, adding within the new capacity re-records nothing again. */
    step_fallers(w, f, TOTAL, 1);
    tb_world_stats st3 = th_stats(w);
    assert_int_equal(st3.records, st2.records);
    th_world_destroy(w);
}

/* ---- slot reuse ------------------------------------------------------------------------- */

static void test_slot_reuse(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_shape_id s = th_sphere(w, 0.3f);
    static faller f[4];
    add_fallers(w, s, f, 0, 3);
    step_fallers(w, f, 3, 30);
    const tb_body_id old = f[1].id;
    th_assert_ok(tb_body_destroy(w, old));
    /* a new body, likely in the freed slot: it must not inherit the old one's velocity */
    add_fallers(w, s, f, 3, 1);
    const tb_body_id fresh = f[3].id;
    assert_false(fresh.index1 == old.index1 && fresh.generation == old.generation);
    assert_false(tb_body_is_valid(w, old));
    tb_vec3 p;
    tb_quat q;
    th_assert_result(tb_body_get_pose(w, old, &p, &q), TB_ERROR_STALE_ID);
    f[1] = f[3]; /* keep the reference list dense: 0, 3 (in place of 1), 2 */
    step_fallers(w, f, 3, 10);
    check_fallers(w, f, 3);
    tb_world_stats st = th_stats(w);
    assert_int_equal(st.body_count, 3);
    tb_body_id live[8];
    assert_int_equal(tb_world_body_ids(w, live, 8), 3);
    th_world_destroy(w);
}

/* ---- stats and device ------------------------------------------------------------------- */

static int stage_index(const tb_world_stats* st, const char* name)
{
    for (uint32_t i = 0; i < st->stage_count; i++)
        if (st->stages[i].name && strcmp(st->stages[i].name, name) == 0) return (int)i;
    return -1;
}

static void test_stats(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id ids[50];
    build_mixed(w, 50, 3, ids);
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_step_n(w, DT, 4));
    tb_world_stats st = th_stats(w);
    assert_int_equal(st.body_count, 50);
    assert_int_equal(st.shape_count, 2);
    assert_int_equal(st.steps, 5);
    assert_int_equal(st.submits, 2);
    assert_true(st.records >= 1);
    assert_true(st.body_capacity >= 50);
    assert_in_range(st.stage_count, 3, TB_MAX_STAGES);
    /* Listed in step order (DESIGN.md §1); the broadphase's stage is named after it
     * (TUMBLE_BROADPHASE may choose another than the default). */
    char broadphase[64];
    snprintf(broadphase, sizeof broadphase, "broadphase/%s", st.broadphase);
    const char* order[] = { "step/begin", "broadphase/world_aabb", broadphase,
                            "broadphase/pairs", "narrowphase/contacts", "solver/colour", "solver/prepare",
                            "integrate/apply_forces", "solver/solve", "integrate/integrate",
                            "step/end" };
    int last = -1;
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++) {
        int at = stage_index(&st, order[i]);
        if (at <= last) fail_msg("stage %s missing or out of order", order[i]);
        last = at;
    }
    assert_true(isfinite(st.gpu_ms) && st.gpu_ms >= 0);
    for (uint32_t i = 0; i < st.stage_count; i++)
        assert_true(isfinite(st.stages[i].ms) && st.stages[i].ms >= 0);
    th_world_destroy(w);
}

static void test_device_info(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_device_info info;
    memset(&info, 0x55, sizeof info); /* no terminator unless the library writes one */
    th_assert_ok(tb_world_device_info(w, &info));
    assert_true(memchr(info.name, 0, sizeof info.name) != NULL);
    assert_true(memchr(info.driver, 0, sizeof info.driver) != NULL);
    assert_true(info.name[0] != '\0');
    assert_true(info.api_version >= ((1u << 22) | (2u << 12))); /* Vulkan 1.2 */
    uint32_t sg = info.subgroup_size;
    assert_true(sg >= 1 && sg <= 128 && (sg & (sg - 1)) == 0);
    if (strstr(info.name, "llvmpipe")) {
        /* lavapipe: subgroup = native vector width / 32 bits */
        const char* width = getenv("LP_NATIVE_VECTOR_WIDTH");
        uint32_t want = (width && strcmp(width, "128") == 0) ? 4 : 8;
        assert_int_equal(sg, want);
        assert_int_equal(info.is_cpu, 1);
    }
    th_world_destroy(w);
}

/* ---- bulk creation ---------------------------------------------------------------------- */

static void test_bulk_create_read_back(void** state)
{
    (void)state;
    enum { N = 1500 };
    tb_world_def wd = tb_default_world_def();
    wd.initial_body_capacity = 256; /* also exercises growth inside one create_many */
    tb_world* w = th_world_create(&wd);
    tb_shape_id s = th_sphere(w, 0.5f), b = th_box(w, th_v3(0.5f, 0.2f, 0.9f));
    th_rng rng = th_rng_seed(2024);
    static tb_body_def defs[N];
    static tb_body_id ids[N], listed[N + 1];
    static tb_vec3 p[N];
    static tb_quat q[N];
    static int tags[N];
    for (int i = 0; i < N; i++) {
        defs[i] = th_dynamic_def(i % 2 ? s : b, th_v3(th_rng_range(&rng, -500, 500),
                                                      th_rng_range(&rng, -500, 500),
                                                      th_rng_range(&rng, -500, 500)));
        defs[i].rotation = th_rng_quat(&rng);
        defs[i].user_data = &tags[i];
    }
    th_assert_ok(tb_body_create_many(w, defs, N, ids));
    th_assert_ok(tb_world_read_transforms(w, ids, N, p, q));
    for (int i = 0; i < N; i++) {
        /* positions are stored as given; rotations only re-normalised */
        assert_memory_equal(&p[i], &defs[i].position, sizeof p[i]);
        th_assert_near(q[i].x, defs[i].rotation.x, 1e-6, 0);
        th_assert_near(q[i].y, defs[i].rotation.y, 1e-6, 0);
        th_assert_near(q[i].z, defs[i].rotation.z, 1e-6, 0);
        th_assert_near(q[i].w, defs[i].rotation.w, 1e-6, 0);
        assert_ptr_equal(tb_body_get_user_data(w, ids[i]), &tags[i]);
    }
    assert_int_equal(tb_world_body_ids(w, listed, N + 1), N);
    for (int i = 1; i < N; i++) assert_true(listed[i].index1 > listed[i - 1].index1);
    for (int i = 0; i < N; i++) assert_true(tb_body_is_valid(w, listed[i]));
    /* one step of S substeps later every body has fallen by g dt^2 (S + 1) / (2 S) */
    th_assert_ok(tb_world_step(w, DT));
    const tb_vec3 g = tb_world_get_gravity(w);
    const double subs = tb_default_world_def().substeps;
    th_assert_ok(tb_world_read_transforms(w, ids, N, p, NULL));
    for (int i = 0; i < N; i++)
        th_assert_near(p[i].y, defs[i].position.y + (double)g.y * DT * DT * (subs + 1) / (2 * subs),
                       1e-4, 0);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_determinism_mixed),
        cmocka_unit_test(test_determinism_freefall_scene),
        cmocka_unit_test(test_step_n_equals_steps),
        cmocka_unit_test(test_step_n_in_batches),
        cmocka_unit_test(test_growth_and_records),
        cmocka_unit_test(test_slot_reuse),
        cmocka_unit_test(test_stats),
        cmocka_unit_test(test_device_info),
        cmocka_unit_test(test_bulk_create_read_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
