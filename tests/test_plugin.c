/* Plugins (abi/tumble_plugin.h): the example blast plugin's GPU stage pushes bodies as its
 * parameters say and nothing once unloaded; the contact logger's events match the contacts
 * read through the API; broken plugins are refused with a sentence and the world steps on. */
#include "harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../tools/plugins/blast.h"

#define DT (1.0f / 60.0f)
#define RING 8

static const char* plugin_path(const char* name)
{
    static char path[4096];
    snprintf(path, sizeof path, "%s/%s", TB_BUILD_DIR, name);
    return path;
}

static tb_world* weightless_world(uint32_t pair_capacity)
{
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    def.initial_pair_capacity = pair_capacity;
    return th_world_create_ex(&def, 1);   /* refusals are logged on purpose */
}

static int has_stage(tb_world* w, const char* name)
{
    tb_world_stats st = th_stats(w);
    for (uint32_t i = 0; i < st.stage_count; i++)
        if (strcmp(st.stages[i].name, name) == 0) return 1;
    return 0;
}

/* RING spheres at distance 2 around the origin, one at distance 6 (beyond the radius). */
static void ring(tb_world* w, tb_body_id* ids)
{
    tb_shape_id sphere = th_sphere(w, 0.25f);
    for (int i = 0; i <= RING; i++) {
        double a = 2 * 3.14159265358979 * i / RING;
        float d = i < RING ? 2.0f : 6.0f;
        tb_body_def def = th_dynamic_def(sphere, th_v3(d * (float)cos(a), 0.5f, d * (float)sin(a)));
        ids[i] = th_body(w, &def);
    }
}

static void set_blast(tb_world* w, tb_plugin_id blast, float strength, float radius)
{
    tb_blast_params p = { { 0, 0.5f, 0, strength }, { radius, 0, 0, 0 } };
    th_assert_ok(tb_world_set_plugin_param(w, blast, 0, &p, sizeof p));
}

/* Each ring body moves straight away from the centre at `speed`; the far one is still. */
static void assert_pushed(tb_world* w, const tb_body_id* ids, double speed)
{
    for (int i = 0; i <= RING; i++) {
        tb_vec3 p, v, av;
        th_read_pose(w, ids[i], &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, ids[i], &v, &av));
        double want = i < RING ? speed : 0.0;
        double r = sqrt((double)p.x * p.x + (double)p.z * p.z);
        th_assert_near(v.x, want * p.x / r, 1e-5, 1e-4);
        th_assert_near(v.y, 0.0, 1e-6, 0);
        th_assert_near(v.z, want * p.z / r, 1e-5, 1e-4);
    }
}

/* strength 12 m/s^2 at the centre, radius 4: at distance 2 a step adds 6 m/s^2 * DT. */
static void blast_pushes(const char* file)
{
    tb_world* w = weightless_world(0);
    tb_body_id ids[RING + 1];
    ring(w, ids);
    tb_plugin_id blast;
    th_assert_ok(tb_world_load_plugin(w, plugin_path(file), &blast));
    th_assert_ok(tb_world_step(w, DT));
    assert_pushed(w, ids, 0.0);                    /* default strength: 0 */
    assert_true(has_stage(w, "plugin/blast/push"));
    set_blast(w, blast, 12.0f, 4.0f);
    th_assert_ok(tb_world_step(w, DT));
    assert_pushed(w, ids, 6.0 * DT);
    th_assert_ok(tb_world_step(w, DT));            /* a field: it keeps pushing */
    /* It moved out by 6 DT^2 in the step before, where the field is 18 DT^2 weaker. */
    assert_pushed(w, ids, 12.0 * DT * (1 - 1.5 * DT * DT));
    th_assert_ok(tb_world_unload_plugin(w, blast));
    for (int i = 0; i <= RING; i++) th_assert_ok(tb_body_set_velocity(w, ids[i], th_v3(0, 0, 0), th_v3(0, 0, 0)));
    th_assert_ok(tb_world_step(w, DT));
    assert_pushed(w, ids, 0.0);
    assert_false(has_stage(w, "plugin/blast/push"));
    th_assert_result(tb_world_set_plugin_param(w, blast, 0, &blast, 4), TB_ERROR_STALE_ID);
    th_world_destroy(w);
}

static void test_blast_spirv_pushes_bodies_away(void** state)
{
    (void)state;
    blast_pushes("plugins/tb_blast.so");
}

static void test_blast_glsl_pushes_bodies_away(void** state)
{
    (void)state;
    blast_pushes("plugins/tb_blast_glsl.so");
}

/* Without the plugin nothing pushes; bad parameters are refused and change nothing. */
static void test_blast_parameters(void** state)
{
    (void)state;
    tb_world* w = weightless_world(0);
    tb_body_id ids[RING + 1];
    ring(w, ids);
    th_assert_ok(tb_world_step(w, DT));
    assert_pushed(w, ids, 0.0);
    tb_plugin_id blast;
    th_assert_ok(tb_world_load_plugin(w, plugin_path("plugins/tb_blast.so"), &blast));
    set_blast(w, blast, 12.0f, 4.0f);
    tb_blast_params bad = { { 0, 0.5f, 0, NAN }, { 4, 0, 0, 0 } };
    th_assert_result(tb_world_set_plugin_param(w, blast, 0, &bad, sizeof bad), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "finite"));
    float radius = -1;
    th_assert_result(tb_world_set_plugin_param(w, blast, 16, &radius, 4), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_world_set_plugin_param(w, blast, 30, &radius, 4), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "beyond"));
    tb_plugin_id unknown = { 9, blast.world, 1 };
    th_assert_result(tb_world_set_plugin_param(w, unknown, 0, &radius, 4), TB_ERROR_INVALID_ID);
    th_assert_ok(tb_world_step(w, DT));
    assert_pushed(w, ids, 6.0 * DT);               /* the good parameters stayed */
    th_world_destroy(w);
}

/* A step that overflows the pair buffer is abandoned and run again: the pre-step blast
 * must push once, not twice. A tight cluster far away makes the pairs overflow. */
static void test_blast_once_in_a_redone_step(void** state)
{
    (void)state;
    tb_world* w = weightless_world(1);
    tb_body_id ids[RING + 1];
    ring(w, ids);
    tb_shape_id small = th_sphere(w, 0.3f);
    for (int i = 0; i < 64; i++) {
        tb_body_def def = th_dynamic_def(small, th_v3(40.0f + (float)(i % 4) * 0.5f,
                                                      (float)(i / 16) * 0.5f,
                                                      (float)(i / 4 % 4) * 0.5f));
        th_body(w, &def);
    }
    tb_plugin_id blast;
    th_assert_ok(tb_world_load_plugin(w, plugin_path("plugins/tb_blast.so"), &blast));
    set_blast(w, blast, 12.0f, 4.0f);
    th_assert_ok(tb_world_step(w, DT));
    assert_true(th_stats(w).steps_redone > 0);
    assert_pushed(w, ids, 6.0 * DT);
    th_world_destroy(w);
}

/* At most 16 plugin stages a world: the 17th blast is refused. */
static void test_plugin_capacity(void** state)
{
    (void)state;
    tb_world* w = weightless_world(0);
    tb_plugin_id ids[16];
    for (int i = 0; i < 16; i++)
        th_assert_ok(tb_world_load_plugin(w, plugin_path("plugins/tb_blast.so"), &ids[i]));
    tb_plugin_id more;
    th_assert_result(tb_world_load_plugin(w, plugin_path("plugins/tb_blast.so"), &more), TB_ERROR_CAPACITY);
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_unload_plugin(w, ids[3]));
    th_assert_result(tb_world_unload_plugin(w, ids[3]), TB_ERROR_STALE_ID);
    th_assert_ok(tb_world_load_plugin(w, plugin_path("plugins/tb_blast.so"), &more));
    th_assert_ok(tb_world_step(w, DT));
    th_world_destroy(w);
}

/* ---- refusals ------------------------------------------------------------------------- */

static void assert_refused(tb_world* w, const char* path, const char* says)
{
    tb_world_stats before = th_stats(w);
    tb_plugin_id id = { 0, 0, 0 };
    th_assert_result(tb_world_load_plugin(w, path, &id), TB_ERROR_INVALID_ARGUMENT);
    if (!strstr(tb_world_last_error(w), says))
        fail_msg("loading %s said \"%s\", not \"%s\"", path, tb_world_last_error(w), says);
    assert_int_equal(id.index1, 0);
    assert_int_equal(th_stats(w).stage_count, before.stage_count);
    th_assert_ok(tb_world_step(w, DT));
}

static void test_broken_plugins_are_refused(void** state)
{
    (void)state;
    tb_world_def def = tb_default_world_def();
    tb_world* w = th_world_create_ex(&def, 1);
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 10, 0));
    tb_body_id ball = th_body(w, &d);
    const struct { const char* file; const char* says; } cases[] = {
        { "tests/plugins/refused_newer.so", "built for plugin ABI version 2" },
        { "tests/plugins/refused_no_entry.so", "exports no tb_plugin_entry" },
        { "tests/plugins/refused_not_spirv.so", "is not SPIR-V" },
        { "tests/plugins/refused_bad_spirv.so", "is not valid SPIR-V" },
        { "tests/plugins/refused_bad_glsl.so", "broken.comp:5: error" },
        { "tests/plugins/refused_pairs_early.so", "per-pair stage" },
        { "tests/plugins/refused_huge_stage.so", "2147483647 bytes" },
        { "tests/plugins/refused_glsl_dir.so", "cannot read shader" },
        { "tests/plugins/no_such_plugin.so", "cannot load plugin" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        assert_refused(w, plugin_path(cases[i].file), cases[i].says);
    tb_plugin_id id;
    th_assert_result(tb_world_load_plugin(w, NULL, &id), TB_ERROR_INVALID_ARGUMENT);
    /* The world stepped on as if nothing had happened: free fall from rest. */
    tb_vec3 v, av;
    th_assert_ok(tb_body_get_velocity(w, ball, &v, &av));
    th_assert_near(v.y, -9.81 * (double)th_stats(w).steps * DT, 1e-4, 1e-4);
    th_world_destroy(w);
}

/* ---- contact events ------------------------------------------------------------------- */

typedef struct pair_state { tb_body_id a, b; uint32_t points; double impulse; } pair_state;

/* The pairs in contact after a step, from the API (points of a pair are consecutive). */
static uint32_t api_pairs(tb_world* w, pair_state* out, uint32_t room)
{
    tb_contact contacts[256];
    uint32_t count = 0, n = 0;
    th_assert_ok(tb_world_read_contacts(w, contacts, 256, &count));
    assert_true(count <= 256);
    for (uint32_t i = 0; i < count; i++) {
        if (!n || memcmp(&out[n - 1].a, &contacts[i].a, sizeof contacts[i].a) != 0 ||
            memcmp(&out[n - 1].b, &contacts[i].b, sizeof contacts[i].b) != 0) {
            assert_true(n < room);
            out[n++] = (pair_state){ contacts[i].a, contacts[i].b, 0, 0 };
        }
        out[n - 1].points++;
        out[n - 1].impulse += contacts[i].normal_impulse;
    }
    return n;
}

/* The logger's order within a step: by the bodies' slots, as the library sorts them. */
static int by_slots(const void* x, const void* y)
{
    const pair_state *p = x, *q = y;
    if (p->a.index1 != q->a.index1) return p->a.index1 < q->a.index1 ? -1 : 1;
    return p->b.index1 < q->b.index1 ? -1 : p->b.index1 > q->b.index1;
}

static int find_pair(const pair_state* list, uint32_t n, const pair_state* p)
{
    for (uint32_t i = 0; i < n; i++)
        if (memcmp(&list[i].a, &p->a, sizeof p->a) == 0 && memcmp(&list[i].b, &p->b, sizeof p->b) == 0)
            return 1;
    return 0;
}

typedef struct event_line { unsigned long long step; char kind[8]; pair_state pair; } event_line;

/* Append the events the API implies for this step: begins first, then ends. */
static uint32_t expect_events(unsigned long long step, const pair_state* now, uint32_t n,
                              const pair_state* before, uint32_t m, event_line* out)
{
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++)
        if (!find_pair(before, m, &now[i])) out[k++] = (event_line){ step, "begin", now[i] };
    for (uint32_t i = 0; i < m; i++)
        if (!find_pair(now, n, &before[i])) out[k++] = (event_line){ step, "end", before[i] };
    return k;
}

static int read_event(FILE* f, event_line* e)
{
    unsigned a, ag, b, bg, points;
    double impulse;
    if (fscanf(f, "step %llu %7s %u:%u %u:%u points %u normal_impulse %lf%*[^\n]\n", &e->step,
               e->kind, &a, &ag, &b, &bg, &points, &impulse) != 8)
        return 0;
    e->pair.a = (tb_body_id){ a, 0, (uint16_t)ag };
    e->pair.b = (tb_body_id){ b, 0, (uint16_t)bg };
    e->pair.points = points;
    e->pair.impulse = impulse;
    return 1;
}

static void assert_same_event(const event_line* got, const event_line* want)
{
    assert_int_equal(got->step, want->step);
    assert_string_equal(got->kind, want->kind);
    assert_int_equal(got->pair.a.index1, want->pair.a.index1);
    assert_int_equal(got->pair.a.generation, want->pair.a.generation);
    assert_int_equal(got->pair.b.index1, want->pair.b.index1);
    assert_int_equal(got->pair.b.generation, want->pair.b.generation);
    assert_int_equal(got->pair.points, want->pair.points);
    th_assert_near(got->pair.impulse, want->pair.impulse, 1e-6, 1e-5);
}

/* Balls bounce on the ground (restitution 0.9), so contacts begin and end again and again. */
static void bouncing_balls(tb_world* w)
{
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_def sd = tb_default_shape_def();
    sd.restitution = 0.9f;
    tb_shape_id ball;
    th_assert_ok(tb_shape_create_sphere(w, &sd, 0.25f, &ball));
    for (int i = 0; i < 4; i++) {
        tb_body_def d = th_dynamic_def(ball, th_v3((float)i, 0.6f + 0.4f * (float)i, 0));
        th_body(w, &d);
    }
}

/* A logger writing to a fresh temporary file (its name in `path`, PATH_SIZE bytes). */
#define PATH_SIZE 64
static tb_plugin_id load_logger(tb_world* w, char* path)
{
    snprintf(path, PATH_SIZE, "/tmp/tumble-contact-log-XXXXXX");
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    setenv("TB_CONTACT_LOG", path, 1);
    tb_plugin_id logger;
    th_assert_ok(tb_world_load_plugin(w, plugin_path("plugins/tb_contact_logger.so"), &logger));
    return logger;
}

#define LOG_STEPS 150
#define MAX_EVENTS 512

static void test_logger_events_match_contacts(void** state)
{
    (void)state;
    char log_path[PATH_SIZE];
    tb_world* w = th_world_create(NULL);
    bouncing_balls(w);
    tb_plugin_id logger = load_logger(w, log_path);
    static event_line expected[MAX_EVENTS];
    pair_state before[64], now[64];
    uint32_t m = 0, total = 0, begins = 0, ends = 0;
    for (int s = 1; s <= LOG_STEPS; s++) {
        th_assert_ok(tb_world_step(w, DT));
        uint32_t n = api_pairs(w, now, 64);
        qsort(now, n, sizeof *now, by_slots);
        assert_true(total + n + m <= MAX_EVENTS);
        uint32_t k = expect_events((unsigned long long)s, now, n, before, m, expected + total);
        for (uint32_t i = 0; i < k; i++) {
            begins += strcmp(expected[total + i].kind, "begin") == 0;
            ends += strcmp(expected[total + i].kind, "end") == 0;
        }
        total += k;
        memcpy(before, now, n * sizeof *now);
        m = n;
    }
    th_assert_ok(tb_world_unload_plugin(w, logger));   /* closes the log */
    assert_true(begins >= 8 && ends >= 4);             /* the balls did bounce */
    FILE* f = fopen(log_path, "r");
    assert_non_null(f);
    event_line got;
    uint32_t lines = 0;
    while (read_event(f, &got)) {
        assert_true(lines < total);
        assert_same_event(&got, &expected[lines]);
        lines++;
    }
    assert_int_equal(lines, total);
    fclose(f);
    unlink(log_path);
    th_world_destroy(w);
}

static char* read_all(const char* path)
{
    FILE* f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char* text = calloc(1, (size_t)n + 1);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    return text;
}

/* tb_world_step_n(w, dt, 10) reports every step's events, as ten single steps do. */
static void test_events_of_every_step_in_step_n(void** state)
{
    (void)state;
    char paths[2][PATH_SIZE];
    tb_world* w[2];
    tb_plugin_id logger[2];
    for (int k = 0; k < 2; k++) {
        w[k] = th_world_create(NULL);
        bouncing_balls(w[k]);
        logger[k] = load_logger(w[k], paths[k]);
    }
    for (int s = 0; s < LOG_STEPS; s++) th_assert_ok(tb_world_step(w[0], DT));
    for (int s = 0; s < LOG_STEPS; s += 10) th_assert_ok(tb_world_step_n(w[1], DT, 10));
    for (int k = 0; k < 2; k++) th_assert_ok(tb_world_unload_plugin(w[k], logger[k]));
    char* one = read_all(paths[0]);
    char* ten = read_all(paths[1]);
    assert_true(strlen(one) > 1000);
    assert_string_equal(one, ten);
    free(one);
    free(ten);
    for (int k = 0; k < 2; k++) {
        unlink(paths[k]);
        th_world_destroy(w[k]);
    }
}

/* 1500 balls land on the ground in the first step: more events than the event buffer
 * first holds, so the step is run again with a bigger one, and each event comes once. */
static void test_many_events_grow_the_buffer(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id ball = th_sphere(w, 0.2f);
    for (int i = 0; i < 1500; i++) {
        tb_body_def d = th_dynamic_def(ball, th_v3(0.5f * (float)(i % 50), 0.2f, 0.5f * (float)(i / 50)));
        th_body(w, &d);
    }
    char path[PATH_SIZE];
    tb_plugin_id logger = load_logger(w, path);
    th_assert_ok(tb_world_step(w, DT));
    assert_true(th_stats(w).steps_redone >= 1);
    th_assert_ok(tb_world_unload_plugin(w, logger));
    FILE* f = fopen(path, "r");
    assert_non_null(f);
    event_line e;
    uint32_t begins = 0;
    unsigned previous = 0;
    while (read_event(f, &e)) {
        assert_int_equal(e.step, 1);
        assert_string_equal(e.kind, "begin");
        assert_int_equal(e.pair.a.index1, 1);                 /* the ground, then each ball */
        assert_true(e.pair.b.index1 > previous);              /* once, in order */
        previous = e.pair.b.index1;
        begins++;
    }
    assert_int_equal(begins, 1500);
    fclose(f);
    unlink(path);
    th_world_destroy(w);
}

/* A contact callback that steps its world or destroys it is refused (the ABI forbids
 * both; the destroyed world was freed under the step), and only the outer steps are
 * taken. */
static void test_callbacks_cannot_step(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    bouncing_balls(w);
    tb_plugin_id nested;
    th_assert_ok(tb_world_load_plugin(w, plugin_path("tests/plugins/nested_step.so"), &nested));
    for (int s = 0; s < 30; s++) th_assert_ok(tb_world_step(w, DT));
    assert_int_equal(th_stats(w).steps, 30);
    assert_non_null(strstr(tb_world_last_error(w), "contact callback"));
    th_assert_ok(tb_world_unload_plugin(w, nested));
    th_world_destroy(w);
}

static int pose_finite(tb_vec3 p, tb_quat q)
{
    return isfinite(p.x) && isfinite(p.y) && isfinite(p.z) && isfinite(q.x) && isfinite(q.y) &&
           isfinite(q.z) && isfinite(q.w);
}

#define PILE 18   /* boxes: two layers of three by three */

/* The guard: a box in the middle of a settled pile whose velocity a plugin turns into NaN
 * is isolated by that step (reported, logged, its pose the last finite one, moving it
 * refused), and the other boxes stay finite and slow for a second of steps after. */
static void guard_isolates(const char* solver, int infinite)
{
    if (solver) setenv("TUMBLE_SOLVER", solver, 1);
    tb_world* w = th_world_create_ex(NULL, 1);   /* the guard logs a warning */
    unsetenv("TUMBLE_SOLVER");
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id box = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
    tb_body_id ids[PILE];
    for (int i = 0; i < PILE; i++) {
        tb_body_def d = th_dynamic_def(box, th_v3(1.02f * (float)(i % 3 - 1), 0.5f + (float)(i / 9),
                                                  1.02f * (float)(i / 3 % 3 - 1)));
        ids[i] = th_body(w, &d);
    }
    tb_plugin_id poison;
    th_assert_ok(tb_world_load_plugin(w, plugin_path("tests/plugins/poison.so"), &poison));
    th_assert_ok(tb_world_step_n(w, DT, 30));
    assert_int_equal(tb_world_isolated_bodies(w, NULL, 0), 0);
    tb_body_id victim = ids[4];   /* the middle of the lower layer, under ids[13] */
    tb_vec3 before;
    tb_quat turn_before;
    th_read_pose(w, victim, &before, &turn_before);
    float armed[4] = { 1, (float)(victim.index1 - 1), (float)infinite, 0 }, off[4] = { 0 };
    th_assert_ok(tb_world_set_plugin_param(w, poison, 0, armed, sizeof armed));
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_set_plugin_param(w, poison, 0, off, sizeof off));
    tb_body_id found[2];
    assert_int_equal(tb_world_isolated_bodies(w, found, 2), 1);
    assert_true(found[0].index1 == victim.index1 && found[0].generation == victim.generation);
    assert_non_null(strstr(th_world_log(w)->last_warning, "isolated"));
    th_assert_ok(tb_world_step_n(w, DT, 60));
    for (int i = 0; i < PILE; i++) {
        tb_vec3 p, v, av;
        tb_quat q;
        th_read_pose(w, ids[i], &p, &q);
        assert_true(pose_finite(p, q));
        th_assert_ok(tb_body_get_velocity(w, ids[i], &v, &av));
        if (i == 4) {
            assert_true(p.x == before.x && p.y == before.y && p.z == before.z);
            assert_true(q.x == turn_before.x && q.w == turn_before.w);
            assert_true(v.x == 0 && v.y == 0 && v.z == 0);
            continue;
        }
        assert_true(isfinite(v.x) && isfinite(v.y) && isfinite(v.z));
        assert_true(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < 10.0);
    }
    th_assert_result(tb_body_set_velocity(w, victim, th_v3(0, 1, 0), th_v3(0, 0, 0)),
                     TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "isolated"));
    th_assert_ok(tb_body_destroy(w, victim));
    assert_int_equal(tb_world_isolated_bodies(w, NULL, 0), 0);
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_unload_plugin(w, poison));
    th_world_destroy(w);
}

static void test_guard_isolates_a_broken_body(void** state)
{
    (void)state;
    guard_isolates(NULL, 0);
    guard_isolates(NULL, 1);
}

static void test_guard_isolates_with_the_soft_step(void** state)
{
    (void)state;
    guard_isolates("soft", 0);
    guard_isolates("soft", 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blast_spirv_pushes_bodies_away),
        cmocka_unit_test(test_blast_glsl_pushes_bodies_away),
        cmocka_unit_test(test_blast_parameters),
        cmocka_unit_test(test_blast_once_in_a_redone_step),
        cmocka_unit_test(test_plugin_capacity),
        cmocka_unit_test(test_broken_plugins_are_refused),
        cmocka_unit_test(test_logger_events_match_contacts),
        cmocka_unit_test(test_events_of_every_step_in_step_n),
        cmocka_unit_test(test_many_events_grow_the_buffer),
        cmocka_unit_test(test_callbacks_cannot_step),
        cmocka_unit_test(test_guard_isolates_a_broken_body),
        cmocka_unit_test(test_guard_isolates_with_the_soft_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
