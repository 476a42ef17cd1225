/* The API contract for bad input: every fallible call rejects it with the documented code,
 * leaves the world exactly as it was, and leaves a message in tb_world_last_error. */
#include "harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tumble_vulkan.h"

#define DT (1.0f / 60.0f)
#define FX_BODIES 3

/* A small world with a body of each kind, stepped once so its state lives on the GPU. */
typedef struct fixture {
    tb_world* w;
    tb_shape_id sphere, box, plane, light; /* light: density 0 */
    tb_body_id ids[FX_BODIES];
} fixture;

static int fx_setup(void** state)
{
    fixture* fx = calloc(1, sizeof *fx);
    assert_non_null(fx);
    fx->w = th_world_create_ex(NULL, 1); /* the library may log the rejections */
    fx->sphere = th_sphere(fx->w, 0.5f);
    fx->box = th_box(fx->w, th_v3(0.5f, 1, 1.5f));
    fx->plane = th_plane(fx->w, th_v3(0, 1, 0), 0);
    tb_shape_def sd = tb_default_shape_def();
    sd.density = 0;
    th_assert_ok(tb_shape_create_sphere(fx->w, &sd, 1.0f, &fx->light));
    tb_body_def d = th_dynamic_def(fx->sphere, th_v3(0, 5, 0));
    d.linear_velocity = th_v3(1, 2, 3);
    d.angular_velocity = th_v3(0.5f, 0, 0);
    fx->ids[0] = th_body(fx->w, &d);
    d = th_dynamic_def(fx->box, th_v3(3, 5, 0));
    d.rotation = th_quat_axis_angle(th_v3(1, 1, 0), 0.7);
    fx->ids[1] = th_body(fx->w, &d);
    d = th_static_def(fx->plane, th_v3(0, 0, 0));
    fx->ids[2] = th_body(fx->w, &d);
    th_assert_ok(tb_world_step(fx->w, DT));
    *state = fx;
    return 0;
}

static int fx_teardown(void** state)
{
    fixture* fx = *state;
    th_world_destroy(fx->w);
    free(fx);
    return 0;
}

/* ---- "the world is unchanged" ------------------------------------------------------------ */

typedef struct snapshot {
    tb_world_stats st;
    tb_vec3 gravity;
    tb_vec3 p[FX_BODIES], v[FX_BODIES], av[FX_BODIES];
    tb_quat q[FX_BODIES];
} snapshot;

static snapshot snap_take(fixture* fx)
{
    snapshot s;
    memset(&s, 0, sizeof s);
    s.st = th_stats(fx->w);
    s.gravity = tb_world_get_gravity(fx->w);
    th_assert_ok(tb_world_read_transforms(fx->w, fx->ids, FX_BODIES, s.p, s.q));
    for (int i = 0; i < FX_BODIES; i++)
        th_assert_ok(tb_body_get_velocity(fx->w, fx->ids[i], &s.v[i], &s.av[i]));
    return s;
}

static void snap_check(fixture* fx, const snapshot* before, const char* what)
{
    snapshot now = snap_take(fx);
    if (now.st.body_count != before->st.body_count ||
        now.st.shape_count != before->st.shape_count || now.st.steps != before->st.steps)
        fail_msg("%s: counts changed (bodies %u->%u shapes %u->%u steps %llu->%llu)", what,
                 before->st.body_count, now.st.body_count, before->st.shape_count,
                 now.st.shape_count, (unsigned long long)before->st.steps,
                 (unsigned long long)now.st.steps);
    if (memcmp(&now.gravity, &before->gravity, sizeof now.gravity) ||
        memcmp(now.p, before->p, sizeof now.p) || memcmp(now.q, before->q, sizeof now.q) ||
        memcmp(now.v, before->v, sizeof now.v) || memcmp(now.av, before->av, sizeof now.av))
        fail_msg("%s: a failed call changed gravity, a pose or a velocity", what);
    for (int i = 0; i < FX_BODIES; i++) assert_true(tb_body_is_valid(fx->w, fx->ids[i]));
}

static void assert_has_error_text(const tb_world* w, const char* what)
{
    const char* e = tb_world_last_error(w);
    if (!e || !e[0]) fail_msg("%s: tb_world_last_error is empty after a failure", what);
}

/* Run `call`, expect `code`, a message, and an unchanged world. */
#define EXPECT_REJECT(fx, call, code) do { \
        snapshot snap_ = snap_take(fx); \
        th_assert_result((call), (code)); \
        assert_has_error_text((fx)->w, #call); \
        snap_check((fx), &snap_, #call); \
    } while (0)

/* ---- result strings --------------------------------------------------------------------- */

/* The library's version is the header's (tests link the library they were built with), in
 * Vulkan's packing. */
static void test_version(void** state)
{
    (void)state;
    assert_int_equal(tb_version(), TB_VERSION);
    assert_int_equal(TB_VERSION >> 22, TB_VERSION_MAJOR);
    assert_int_equal((TB_VERSION >> 12) & 0x3ff, TB_VERSION_MINOR);
    assert_int_equal(TB_VERSION & 0xfff, TB_VERSION_PATCH);
}

static void test_result_strings(void** state)
{
    (void)state;
    const char* seen[9];
    for (int r = 0; r <= 8; r++) {
        seen[r] = tb_result_string((tb_result)r);
        assert_non_null(seen[r]);
        assert_true(seen[r][0] != '\0');
        for (int j = 0; j < r; j++) assert_string_not_equal(seen[r], seen[j]);
    }
    /* Codes from a newer library, or garbage, still get a string. */
    assert_non_null(tb_result_string((tb_result)9));
    assert_non_null(tb_result_string((tb_result)-1));
    assert_non_null(tb_result_string(TB_RESULT_FORCE_32));
}

/* ---- body defs -------------------------------------------------------------------------- */

/* Case k of a bad body def: sets *name and returns the def; k past the end: name NULL. */
static tb_body_def bad_body_def(const fixture* fx, int k, const char** name)
{
    const float nan = NAN, inf = INFINITY;
    tb_body_def d = th_dynamic_def(fx->sphere, th_v3(10, 10, 10));
    *name = NULL;
#define CASE(text, stmt) if (k-- == 0) { stmt; *name = text; return d; }
    CASE("position.x NaN", d.position.x = nan)
    CASE("position.y inf", d.position.y = inf)
    CASE("position.z -inf", d.position.z = -inf)
    CASE("rotation.x NaN", d.rotation.x = nan)
    CASE("rotation.w inf", d.rotation.w = inf)
    CASE("linear_velocity.y NaN", d.linear_velocity.y = nan)
    CASE("linear_velocity.x inf", d.linear_velocity.x = inf)
    CASE("angular_velocity.z NaN", d.angular_velocity.z = nan)
    CASE("angular_velocity.x -inf", d.angular_velocity.x = -inf)
    CASE("mass NaN", d.mass = nan)
    CASE("mass inf", d.mass = inf)
    CASE("mass negative", d.mass = -1)
    CASE("inertia NaN", d.inertia = th_v3(nan, 1, 1))
    CASE("inertia inf", d.inertia = th_v3(1, inf, 1))
    CASE("inertia partly zero", d.inertia = th_v3(1, 0, 1))
    CASE("inertia negative", d.inertia = th_v3(1, 1, -1))
    CASE("linear_damping negative", d.linear_damping = -1)
    CASE("linear_damping NaN", d.linear_damping = nan)
    CASE("angular_damping negative", d.angular_damping = -0.5f)
    CASE("angular_damping inf", d.angular_damping = inf)
    CASE("gravity_scale NaN", d.gravity_scale = nan)
    CASE("gravity_scale inf", d.gravity_scale = inf)
    CASE("rotation |q| = 1.01", d.rotation = th_q(0, 0, 0, 1.01f))
    CASE("rotation |q| = 0.99", d.rotation = th_q(0, 0, 0, 0.99f))
    CASE("rotation zero", d.rotation = th_q(0, 0, 0, 0))
    CASE("rotation (1,1,0,0)", d.rotation = th_q(1, 1, 0, 0))
    CASE("unknown body type", d.type = (tb_body_type)7)
    CASE("dynamic plane", d.shape = fx->plane)
    CASE("dynamic, density 0, mass 0", d.shape = fx->light)
    CASE("def not from tb_default_body_def", {
        memset(&d, 0, sizeof d);
        d.type = TB_BODY_DYNAMIC; d.shape = fx->sphere; d.rotation = th_q(0, 0, 0, 1);
        d.gravity_scale = 1;
    })
#undef CASE
    return d;
}

static void test_bad_body_defs(void** state)
{
    fixture* fx = *state;
    const char* name = NULL;
    int cases = 0;
    for (int k = 0;; k++) {
        tb_body_def d = bad_body_def(fx, k, &name);
        if (!name) break;
        cases++;
        tb_body_id id = tb_null_body;
        snapshot s = snap_take(fx);
        tb_result r = tb_body_create(fx->w, &d, &id);
        if (r != TB_ERROR_INVALID_ARGUMENT)
            fail_msg("tb_body_create, %s: got %s", name, tb_result_string(r));
        assert_has_error_text(fx->w, name);
        snap_check(fx, &s, name);
        r = tb_body_create_many(fx->w, &d, 1, &id);
        if (r != TB_ERROR_INVALID_ARGUMENT)
            fail_msg("tb_body_create_many, %s: got %s", name, tb_result_string(r));
        snap_check(fx, &s, name);
    }
    assert_true(cases >= 30);
    /* Controls: the same shapes are fine where the contract allows them. */
    tb_body_def d = th_static_def(fx->plane, th_v3(0, -3, 0));
    th_body(fx->w, &d);
    d = th_dynamic_def(fx->light, th_v3(0, 20, 0));
    d.mass = 1.0f; /* density 0 is fine when the mass is given */
    th_body(fx->w, &d);
    d = th_static_def(fx->light, th_v3(0, 30, 0));
    th_body(fx->w, &d);
}

/* Unit length within 1e-3 is accepted and normalised; the poses read back are unit. */
static void test_quaternion_tolerance(void** state)
{
    fixture* fx = *state;
    tb_body_def d = th_dynamic_def(fx->box, th_v3(0, 9, 0));
    d.rotation = th_q(0, 0, 0, 1.0004f); /* |q|^2 - 1 = 8e-4: inside either reading */
    tb_body_id a = th_body(fx->w, &d);
    d.rotation = th_q(0.6f, 0, 0, 0.8002f);
    tb_body_id b = th_body(fx->w, &d);
    tb_quat q;
    th_read_pose(fx->w, a, NULL, &q);
    th_assert_near(th_quat_length(q), 1.0, 1e-6, 0);
    th_read_pose(fx->w, b, NULL, &q);
    th_assert_near(th_quat_length(q), 1.0, 1e-6, 0);
    th_assert_near(q.x / q.w, 0.6 / 0.8002, 1e-6, 1e-6); /* same direction */
    th_assert_ok(tb_world_step(fx->w, DT));
    th_read_pose(fx->w, a, NULL, &q);
    th_assert_near(th_quat_length(q), 1.0, 1e-6, 0);

    /* set_pose has the same rule */
    EXPECT_REJECT(fx, tb_body_set_pose(fx->w, fx->ids[0], th_v3(0, 5, 0), th_q(0, 0, 0, 1.01f)),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_pose(fx->w, fx->ids[0], th_v3(0, NAN, 0), th_q(0, 0, 0, 1)),
                  TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_body_set_pose(fx->w, a, th_v3(1, 9, 0), th_q(0, 0.0004f, 0, 1)));
    th_read_pose(fx->w, a, NULL, &q);
    th_assert_near(th_quat_length(q), 1.0, 1e-6, 0);
    tb_vec3 p;
    th_assert_ok(tb_body_get_pose(fx->w, a, &p, &q));
    th_assert_near(th_quat_length(q), 1.0, 1e-6, 0);
    th_assert_vec3_near(p, th_v3(1, 9, 0), 0, 0);
}

/* set_velocity and apply_impulse reject non-finite input. */
static void test_bad_body_values(void** state)
{
    fixture* fx = *state;
    tb_body_id b = fx->ids[0];
    tb_vec3 ok = th_v3(1, 1, 1), nan3 = th_v3(0, NAN, 0), inf3 = th_v3(INFINITY, 0, 0);
    EXPECT_REJECT(fx, tb_body_set_velocity(fx->w, b, nan3, ok), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_velocity(fx->w, b, ok, inf3), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_apply_impulse(fx->w, b, nan3, ok), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_apply_impulse(fx->w, b, ok, inf3), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_pose(fx->w, b, inf3, th_q(0, 0, 0, 1)),
                  TB_ERROR_INVALID_ARGUMENT);
}

/* Finite values beyond the documented limits (tumble.h, TB_MAX_*) are refused like NaN: they
 * turned bodies into NaN a few steps later with every step TB_OK. At the limits, taken. */
static void test_extreme_values(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_body_id b = fx->ids[0];
    const float huge = 3.0e38f;
    tb_vec3 zero = th_v3(0, 0, 0);
    EXPECT_REJECT(fx, tb_world_step(w, huge), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_step_n(w, TB_MAX_DT * 1.01f, 2), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_set_gravity(w, th_v3(0, -huge, 0)), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_set_gravity(w, th_v3(800, -800, 0)), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_velocity(w, b, th_v3(huge, 0, 0), zero),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_velocity(w, b, zero, th_v3(0, 0, TB_MAX_SPIN * 1.01f)),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_body_set_pose(w, b, th_v3(0, 2e6f, 0), th_q(0, 0, 0, 1)),
                  TB_ERROR_INVALID_ARGUMENT);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id out = tb_null_shape;
    EXPECT_REJECT(fx, tb_shape_create_plane(w, &sd, th_v3(0, 1, 0), huge, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_sphere(w, &sd, 2e6f, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_box(w, &sd, th_v3(1, 2e6f, 1), &out),
                  TB_ERROR_INVALID_ARGUMENT);
    tb_body_def d = th_dynamic_def(fx->sphere, th_v3(0, 5, 0));
    tb_body_id id;
    tb_body_def bad[5] = { d, d, d, d, d };
    bad[0].linear_velocity = th_v3(0, huge, 0);
    bad[1].gravity_scale = huge;
    bad[2].position = th_v3(-huge, 0, 0);
    bad[3].inertia = th_v3(1e-12f, 1, 1);   /* flung a body to 1e13 m */
    bad[4].angular_velocity = th_v3(huge, 0, 0);
    for (int i = 0; i < 5; i++)
        EXPECT_REJECT(fx, tb_body_create(w, &bad[i], &id), TB_ERROR_INVALID_ARGUMENT);
    /* The limits themselves are taken. */
    th_assert_ok(tb_world_set_gravity(w, th_v3(0, -TB_MAX_GRAVITY, 0)));
    th_assert_ok(tb_body_set_velocity(w, b, th_v3(TB_MAX_SPEED, 0, 0), th_v3(0, TB_MAX_SPIN, 0)));
    d.gravity_scale = -TB_MAX_GRAVITY_SCALE;
    d.inertia = th_v3(1e-3f, 1e3f, 1e3f);
    th_assert_ok(tb_body_create(w, &d, &id));
    th_assert_ok(tb_world_step(w, TB_MAX_DT));
}

/* ---- shapes ----------------------------------------------------------------------------- */

static void test_bad_shapes(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id out = tb_null_shape;
    const float bad_r[] = { 0.0f, -1.0f, NAN, INFINITY, -0.0f };
    for (size_t i = 0; i < sizeof bad_r / sizeof bad_r[0]; i++)
        EXPECT_REJECT(fx, tb_shape_create_sphere(w, &sd, bad_r[i], &out),
                      TB_ERROR_INVALID_ARGUMENT);
    const tb_vec3 bad_he[] = { { 0, 1, 1 }, { 1, -1, 1 }, { NAN, 1, 1 }, { 1, 1, INFINITY } };
    for (size_t i = 0; i < sizeof bad_he / sizeof bad_he[0]; i++)
        EXPECT_REJECT(fx, tb_shape_create_box(w, &sd, bad_he[i], &out),
                      TB_ERROR_INVALID_ARGUMENT);
    const tb_vec3 bad_n[] = { { 0, 0, 0 }, { NAN, 1, 0 }, { 0, INFINITY, 0 } };
    for (size_t i = 0; i < sizeof bad_n / sizeof bad_n[0]; i++)
        EXPECT_REJECT(fx, tb_shape_create_plane(w, &sd, bad_n[i], 0, &out),
                      TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_plane(w, &sd, th_v3(0, 1, 0), NAN, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    /* material out of its documented range */
    tb_shape_def bad[6];
    for (int i = 0; i < 6; i++) bad[i] = tb_default_shape_def();
    bad[0].density = -1;
    bad[1].density = NAN;
    bad[2].friction = -0.1f;
    bad[3].restitution = 1.5f;
    bad[4].restitution = -0.1f;
    memset(&bad[5], 0, sizeof bad[5]); /* not from tb_default_shape_def */
    bad[5].density = 1000;
    bad[5].friction = 0.5f;
    for (int i = 0; i < 6; i++)
        EXPECT_REJECT(fx, tb_shape_create_sphere(w, &bad[i], 1, &out), TB_ERROR_INVALID_ARGUMENT);
    /* a non-unit plane normal is fine: it is normalised */
    tb_shape_id pl = th_plane(w, th_v3(0, 3, 0), 1);
    tb_shape_type t;
    th_assert_ok(tb_shape_get_type(w, pl, &t));
    assert_int_equal(t, TB_SHAPE_PLANE);
}

/* Hull input the builder must refuse: too few points, non-finite, flat, a line, one point. */
static void test_bad_hulls(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id out = tb_null_shape;
    tb_vec3 pts[16];
    for (int i = 0; i < 8; i++) pts[i] = th_v3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 3, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, NULL, 8, &out), TB_ERROR_INVALID_ARGUMENT);
    pts[5].y = NAN;
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 8, &out), TB_ERROR_INVALID_ARGUMENT);
    pts[5].y = INFINITY;
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 8, &out), TB_ERROR_INVALID_ARGUMENT);
    for (int i = 0; i < 16; i++) pts[i] = th_v3((float)(i % 4), 0.5f, (float)(i / 4)); /* flat */
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 16, &out), TB_ERROR_INVALID_ARGUMENT);
    for (int i = 0; i < 16; i++) pts[i] = th_v3((float)i, 2.0f * i, 0); /* a line */
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 16, &out), TB_ERROR_INVALID_ARGUMENT);
    for (int i = 0; i < 16; i++) pts[i] = th_v3(1, 2, 3);
    EXPECT_REJECT(fx, tb_shape_create_hull(w, &sd, pts, 16, &out), TB_ERROR_INVALID_ARGUMENT);
    tb_hull_info info;
    EXPECT_REJECT(fx, tb_shape_get_hull_info(w, fx->box, &info), TB_ERROR_INVALID_ARGUMENT);
}

/* Mesh and heightfield input the builders must refuse, and their getters' bad arguments. */
static void test_bad_meshes_and_heightfields(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id out = tb_null_shape;
    tb_vec3 v[4] = { th_v3(0, 0, 0), th_v3(0, 0, 1), th_v3(1, 0, 0), th_v3(1, 0, 1) };
    uint32_t tri[6] = { 0, 1, 2, 2, 1, 3 }, far[3] = { 0, 1, 7 }, same[3] = { 1, 1, 1 };
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, NULL, 4, tri, 2, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, NULL, 2, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, tri, 0, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, far, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, same, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, tri, 2, NULL), TB_ERROR_INVALID_ARGUMENT);
    v[2].x = 2.0e6f;
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, tri, 2, &out), TB_ERROR_INVALID_ARGUMENT);
    v[2].x = NAN;
    EXPECT_REJECT(fx, tb_shape_create_mesh(w, &sd, v, 4, tri, 2, &out), TB_ERROR_INVALID_ARGUMENT);
    float h[6] = { 0, 0, 0, 0, 0, 0 };
    EXPECT_REJECT(fx, tb_shape_create_heightfield(w, &sd, NULL, 3, 2, 1, 1, NULL, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_heightfield(w, &sd, h, 6, 1, 1, 1, NULL, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_heightfield(w, &sd, h, 3, 2, -1, 1, NULL, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_create_heightfield(w, &sd, h, 3, 2, 1, INFINITY, NULL, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    h[3] = NAN;
    EXPECT_REJECT(fx, tb_shape_create_heightfield(w, &sd, h, 3, 2, 1, 1, NULL, &out),
                  TB_ERROR_INVALID_ARGUMENT);
    tb_mesh_info info;
    uint32_t nv, nt;
    EXPECT_REJECT(fx, tb_shape_get_mesh_info(w, fx->box, &info), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_shape_get_mesh_geometry(w, fx->box, NULL, 0, NULL, 0, &nv, &nt),
                  TB_ERROR_INVALID_ARGUMENT);
}

/* A cube given off-centre with points inside and on its faces: the hull is the cube, its
 * body frame sits at the cube's centre, and it can be used, stepped and destroyed. */
static void test_hull_shape(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_vec3 pts[8 + 9];
    for (int i = 0; i < 8; i++)
        pts[i] = th_v3(i & 1 ? 3 : 1, i & 2 ? 2 : 0, i & 4 ? 1 : -1);   /* centre (2, 1, 0) */
    for (int i = 0; i < 9; i++) pts[8 + i] = th_v3(1.5f + 0.5f * (i % 3), 2.0f, -0.5f + 0.5f * (i / 3));
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id hull;
    th_assert_ok(tb_shape_create_hull(w, &sd, pts, 17, &hull));
    tb_shape_type type;
    th_assert_ok(tb_shape_get_type(w, hull, &type));
    assert_int_equal(type, TB_SHAPE_HULL);
    tb_hull_info info;
    th_assert_ok(tb_shape_get_hull_info(w, hull, &info));
    assert_int_equal(info.vertex_count, 8);
    assert_int_equal(info.face_count, 6);
    assert_int_equal(info.edge_count, 12);
    assert_float_equal(info.volume, 8.0f, 1e-4f);
    assert_float_equal(info.center_of_mass.x, 2.0f, 1e-5f);
    assert_float_equal(info.center_of_mass.y, 1.0f, 1e-5f);
    assert_float_equal(info.center_of_mass.z, 0.0f, 1e-5f);
    assert_float_equal(info.unit_inertia.x, 2.0f / 3.0f, 1e-4f);
    tb_vec3 verts[8];
    uint32_t count = 0;
    th_assert_ok(tb_shape_get_hull_vertices(w, hull, verts, 8, &count));
    assert_int_equal(count, 8);
    for (int i = 0; i < 8; i++) {   /* every corner is 1 from the centre on every axis */
        assert_float_equal(fabsf(verts[i].x), 1.0f, 1e-5f);
        assert_float_equal(fabsf(verts[i].y), 1.0f, 1e-5f);
        assert_float_equal(fabsf(verts[i].z), 1.0f, 1e-5f);
    }
    tb_body_def d = th_dynamic_def(hull, th_v3(0, 10, 5));
    tb_body_id body = th_body(w, &d);
    float mass;
    tb_vec3 inertia;
    th_assert_ok(tb_body_get_mass(w, body, &mass, &inertia));
    assert_float_equal(mass, 8000.0f, 0.1f);
    th_assert_ok(tb_world_step(w, DT));
    th_assert_result(tb_shape_destroy(w, hull), TB_ERROR_IN_USE);
    th_assert_ok(tb_body_destroy(w, body));
    th_assert_ok(tb_shape_destroy(w, hull));
    th_assert_result(tb_shape_get_hull_info(w, hull, &info), TB_ERROR_STALE_ID);
    th_assert_ok(tb_world_step(w, DT));
}

/* ---- world-level values ----------------------------------------------------------------- */

static void test_bad_step_and_gravity(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    const float bad_dt[] = { 0.0f, -DT, NAN, INFINITY, -INFINITY };
    for (size_t i = 0; i < sizeof bad_dt / sizeof bad_dt[0]; i++) {
        EXPECT_REJECT(fx, tb_world_step(w, bad_dt[i]), TB_ERROR_INVALID_ARGUMENT);
        EXPECT_REJECT(fx, tb_world_step_n(w, bad_dt[i], 3), TB_ERROR_INVALID_ARGUMENT);
    }
    EXPECT_REJECT(fx, tb_world_set_gravity(w, th_v3(0, NAN, 0)), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_set_gravity(w, th_v3(INFINITY, 0, 0)), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_set_solver(w, (tb_solver_kind)2, 0), TB_ERROR_INVALID_ARGUMENT);
    EXPECT_REJECT(fx, tb_world_set_solver(w, TB_SOLVER_BLOCK, 1001), TB_ERROR_INVALID_ARGUMENT);
    /* The solver is chosen before the first step only. */
    th_assert_ok(tb_world_step(w, DT));
    EXPECT_REJECT(fx, tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 0), TB_ERROR_INVALID_ARGUMENT);
    assert_int_equal(tb_world_get_solver(w, NULL), TB_SOLVER_BLOCK);
    /* step_n equals n calls of step: n = 0 is a successful no-op (nothing moves). */
    snapshot s = snap_take(fx);
    th_assert_ok(tb_world_step_n(w, DT, 0));
    snap_check(fx, &s, "tb_world_step_n(n = 0)");
}

static void test_world_create_errors(void** state)
{
    (void)state;
    th_log log;
    memset(&log, 0, sizeof log);
    tb_world_def def = tb_default_world_def();
    def.log = th_log_fn;
    def.log_user = &log;
    const char* devices[] = { "no-such-device", "99" };
    for (int i = 0; i < 2; i++) {
        def.device = devices[i];
        tb_world* w = (tb_world*)&log; /* non-NULL: the call must clear it */
        tb_result r = tb_world_create(&def, &w);
        if (r == TB_OK) tb_world_destroy(w);
        th_assert_result(r, TB_ERROR_NO_DEVICE);
        assert_null(w);
        assert_true(tb_world_last_error(NULL)[0] != '\0');
    }
    def.device = NULL;
    tb_world_def bad[5] = { def, def, def, def, def };
    bad[0].gravity.y = NAN;
    bad[1].max_rotation_per_step = NAN;
    memset(&bad[2], 0, sizeof bad[2]); /* not from tb_default_world_def */
    bad[3].broadphase = (tb_broadphase)99;
    bad[4].broadphase = (tb_broadphase)-1;
    for (int i = 0; i < 5; i++) {
        tb_world* w = (tb_world*)&log;
        tb_result r = tb_world_create(&bad[i], &w);
        if (r == TB_OK) tb_world_destroy(w);
        th_assert_result(r, TB_ERROR_INVALID_ARGUMENT);
        assert_null(w);
        assert_true(tb_world_last_error(NULL)[0] != '\0');
    }
    tb_world_destroy(NULL); /* documented: ignored */
}

/* The broadphase is chosen by the def, else by TUMBLE_BROADPHASE, and named in the stats. */
static void test_broadphase_choice(void** state)
{
    (void)state;
    assert_string_equal(tb_broadphase_name(TB_BROADPHASE_GRID), "grid");
    assert_string_equal(tb_broadphase_name(TB_BROADPHASE_SAP), "sap");
    assert_string_equal(tb_broadphase_name(TB_BROADPHASE_LBVH), "lbvh");
    assert_string_equal(tb_broadphase_name(TB_BROADPHASE_ISAP), "isap");
    assert_null(tb_broadphase_name((tb_broadphase)5));
    char* saved = getenv("TUMBLE_BROADPHASE") ? strdup(getenv("TUMBLE_BROADPHASE")) : NULL;
    tb_world_def def = tb_default_world_def();
    setenv("TUMBLE_BROADPHASE", "no-such-broadphase", 1);
    tb_world* w = NULL;
    th_assert_result(tb_world_create(&def, &w), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(NULL), "TUMBLE_BROADPHASE"));
    setenv("TUMBLE_BROADPHASE", "GRID", 1);   /* any case */
    w = th_world_create(&def);
    assert_string_equal(th_stats(w).broadphase, "grid");
    th_world_destroy(w);
    def.broadphase = TB_BROADPHASE_GRID;   /* the def wins over the environment */
    setenv("TUMBLE_BROADPHASE", "no-such-broadphase", 1);
    w = th_world_create(&def);
    assert_string_equal(th_stats(w).broadphase, "grid");
    th_world_destroy(w);
    if (saved) setenv("TUMBLE_BROADPHASE", saved, 1);
    else unsetenv("TUMBLE_BROADPHASE");
    free(saved);
}

/* ---- ids -------------------------------------------------------------------------------- */

/* Every call that takes a body id must answer `code` for `bad` and change nothing. */
static void check_body_calls(fixture* fx, tb_body_id bad, tb_result code)
{
    tb_world* w = fx->w;
    tb_vec3 p, v;
    tb_quat q;
    float m;
    tb_body_type t;
    tb_body_id two[2] = { fx->ids[0], bad };
    tb_vec3 pp[2], mn[2], mx[2];
    tb_quat qq[2];
    assert_false(tb_body_is_valid(w, bad));
    assert_null(tb_body_get_user_data(w, bad));
    EXPECT_REJECT(fx, tb_body_set_pose(w, bad, th_v3(0, 0, 0), th_q(0, 0, 0, 1)), code);
    EXPECT_REJECT(fx, tb_body_get_pose(w, bad, &p, &q), code);
    EXPECT_REJECT(fx, tb_body_set_velocity(w, bad, th_v3(1, 0, 0), th_v3(0, 0, 0)), code);
    EXPECT_REJECT(fx, tb_body_get_velocity(w, bad, &p, &v), code);
    EXPECT_REJECT(fx, tb_body_apply_impulse(w, bad, th_v3(1, 0, 0), th_v3(0, 0, 0)), code);
    EXPECT_REJECT(fx, tb_body_get_mass(w, bad, &m, &v), code);
    EXPECT_REJECT(fx, tb_body_get_type(w, bad, &t), code);
    EXPECT_REJECT(fx, tb_world_read_transforms(w, two, 2, pp, qq), code);
    EXPECT_REJECT(fx, tb_world_read_aabbs(w, two, 2, mn, mx), code);
    EXPECT_REJECT(fx, tb_body_destroy(w, bad), code);
}

static void test_null_and_unknown_body_ids(void** state)
{
    fixture* fx = *state;
    check_body_calls(fx, tb_null_body, TB_ERROR_INVALID_ID);
    tb_body_id unknown = fx->ids[0];
    unknown.index1 = 1000; /* never allocated */
    check_body_calls(fx, unknown, TB_ERROR_INVALID_ID);
    unknown.index1 = 0xffffffffu;
    check_body_calls(fx, unknown, TB_ERROR_INVALID_ID);
}

/* A NULL output is refused with a sentence of its own, not an older failure's. */
static void expect_null_out(fixture* fx, tb_result r, const char* name)
{
    th_assert_result(r, TB_ERROR_INVALID_ARGUMENT);
    if (!strstr(tb_world_last_error(fx->w), name))
        fail_msg("%s: last error \"%s\" does not name it", name, tb_world_last_error(fx->w));
    th_assert_result(tb_world_step(fx->w, -1.0f), TB_ERROR_INVALID_ARGUMENT); /* an older one */
}

static void test_null_outputs(void** state)
{
    fixture* fx = *state;
    uint32_t count;
    th_assert_result(tb_world_step(fx->w, -1.0f), TB_ERROR_INVALID_ARGUMENT);
    expect_null_out(fx, tb_world_read_contacts(fx->w, NULL, 4, &count), "tb_world_read_contacts");
    expect_null_out(fx, tb_world_read_contacts(fx->w, NULL, 0, NULL), "tb_world_read_contacts");
    expect_null_out(fx, tb_world_get_stats(fx->w, NULL), "tb_world_get_stats");
    expect_null_out(fx, tb_world_device_info(fx->w, NULL), "tb_world_device_info");
    expect_null_out(fx, tb_world_vulkan_device(fx->w, NULL), "tb_world_vulkan_device");
    expect_null_out(fx, tb_world_vulkan_bodies(fx->w, NULL), "tb_world_vulkan_bodies");
    expect_null_out(fx, tb_world_vulkan_contacts(fx->w, NULL), "tb_world_vulkan_contacts");
    expect_null_out(fx, tb_body_get_type(fx->w, fx->ids[0], NULL), "tb_body_get_type");
    expect_null_out(fx, tb_shape_get_type(fx->w, fx->sphere, NULL), "tb_shape_get_type");
    /* No room, no writes: a NULL array with capacity 0 only counts. */
    th_assert_ok(tb_world_read_contacts(fx->w, NULL, 0, &count));
    assert_int_equal(tb_world_body_ids(fx->w, NULL, 8), 0);
}

/* An id from another world never existed in this one. */
static void test_foreign_body_id(void** state)
{
    fixture* fx = *state;
    tb_world* other = th_world_create(NULL);
    tb_shape_id s = th_sphere(other, 1);
    tb_body_def d = th_dynamic_def(s, th_v3(0, 0, 0));
    tb_body_id foreign = tb_null_body;
    /* make the foreign index one that is live in fx->w too */
    for (int i = 0; i < FX_BODIES; i++) foreign = th_body(other, &d);
    check_body_calls(fx, foreign, TB_ERROR_INVALID_ID);
    th_world_destroy(other);
}

static void test_stale_body_ids(void** state)
{
    fixture* fx = *state;
    tb_body_def d = th_dynamic_def(fx->sphere, th_v3(-5, 5, 0));
    tb_body_id victim = th_body(fx->w, &d);
    th_assert_ok(tb_world_step(fx->w, DT));
    th_assert_ok(tb_body_destroy(fx->w, victim));
    check_body_calls(fx, victim, TB_ERROR_STALE_ID);
    /* The slot may be reused; the old id stays stale whatever the new body is. */
    tb_body_id fresh = th_body(fx->w, &d);
    assert_false(fresh.index1 == victim.index1 && fresh.generation == victim.generation);
    check_body_calls(fx, victim, TB_ERROR_STALE_ID);
    assert_true(tb_body_is_valid(fx->w, fresh));
}

static void test_shape_ids(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_type t;
    tb_shape_id unknown = fx->sphere;
    unknown.index1 = 1000;
    const tb_shape_id bad[2] = { tb_null_shape, unknown };
    for (int i = 0; i < 2; i++) {
        assert_false(tb_shape_is_valid(w, bad[i]));
        EXPECT_REJECT(fx, tb_shape_get_type(w, bad[i], &t), TB_ERROR_INVALID_ID);
        EXPECT_REJECT(fx, tb_shape_destroy(w, bad[i]), TB_ERROR_INVALID_ID);
        tb_body_def d = th_dynamic_def(bad[i], th_v3(0, 0, 0));
        tb_body_id out;
        EXPECT_REJECT(fx, tb_body_create(w, &d, &out), TB_ERROR_INVALID_ID);
    }
    tb_shape_id gone = th_sphere(w, 2);
    th_assert_ok(tb_shape_destroy(w, gone));
    assert_false(tb_shape_is_valid(w, gone));
    EXPECT_REJECT(fx, tb_shape_get_type(w, gone, &t), TB_ERROR_STALE_ID);
    EXPECT_REJECT(fx, tb_shape_destroy(w, gone), TB_ERROR_STALE_ID);
    tb_body_def d = th_dynamic_def(gone, th_v3(0, 0, 0));
    tb_body_id out;
    EXPECT_REJECT(fx, tb_body_create(w, &d, &out), TB_ERROR_STALE_ID);
    /* a new shape in the freed slot does not revive the old id */
    tb_shape_id again = th_sphere(w, 2);
    assert_true(tb_shape_is_valid(w, again));
    assert_false(tb_shape_is_valid(w, gone));
    th_assert_ok(tb_shape_get_type(w, fx->box, &t));
    assert_int_equal(t, TB_SHAPE_BOX);
}

/* tb_world_shape_ids: the live shapes in slot order, a freed slot skipped until reused (then
 * with its new generation), at most `capacity`, nothing for a NULL output or world. */
static void test_world_shape_ids(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_id ids[16];
    uint32_t before = tb_world_shape_ids(w, ids, 16);
    assert_true(before >= 2 && before < 14);
    for (uint32_t i = 0; i < before; i++) {
        assert_true(tb_shape_is_valid(w, ids[i]));
        if (i) assert_true(ids[i].index1 > ids[i - 1].index1);
    }
    tb_shape_id a = th_sphere(w, 1), b = th_sphere(w, 2), c = th_sphere(w, 3);
    th_assert_ok(tb_shape_destroy(w, b));
    assert_int_equal(tb_world_shape_ids(w, ids, 16), before + 2);
    assert_memory_equal(&ids[before], &a, sizeof a);
    assert_memory_equal(&ids[before + 1], &c, sizeof c);
    tb_shape_id again = th_sphere(w, 2);
    assert_int_equal(again.index1, b.index1);
    assert_int_equal(tb_world_shape_ids(w, ids, 16), before + 3);
    assert_memory_equal(&ids[before + 1], &again, sizeof again);
    assert_int_equal(tb_world_shape_ids(w, ids, 1), 1);
    assert_int_equal(tb_world_shape_ids(w, NULL, 16), 0);
    assert_int_equal(tb_world_shape_ids(NULL, ids, 16), 0);
}

/* ---- all-or-none, in use, capacity ------------------------------------------------------ */

static void test_create_many_all_or_none(void** state)
{
    fixture* fx = *state;
    enum { N = 10, BAD = 7 };
    tb_body_def defs[N];
    tb_body_id ids[N];
    for (int i = 0; i < N; i++) defs[i] = th_dynamic_def(fx->box, th_v3(2.0f * i, 20, 0));
    defs[BAD].position.y = NAN;
    EXPECT_REJECT(fx, tb_body_create_many(fx->w, defs, N, ids), TB_ERROR_INVALID_ARGUMENT);
    /* "the error names the first bad index" */
    if (!strstr(tb_world_last_error(fx->w), "7"))
        fail_msg("last error does not name index 7: %s", tb_world_last_error(fx->w));
    defs[BAD].position.y = 20;
    uint32_t before = th_stats(fx->w).body_count;
    th_assert_ok(tb_body_create_many(fx->w, defs, N, ids));
    assert_int_equal(th_stats(fx->w).body_count, before + N);
    for (int i = 0; i < N; i++) {
        assert_true(tb_body_is_valid(fx->w, ids[i]));
        for (int j = 0; j < i; j++) assert_false(ids[i].index1 == ids[j].index1);
    }
}

static void test_shape_in_use(void** state)
{
    fixture* fx = *state;
    tb_world* w = fx->w;
    tb_shape_id s = th_sphere(w, 0.3f);
    tb_body_def d = th_dynamic_def(s, th_v3(0, 40, 0));
    tb_body_id a = th_body(w, &d), b = th_body(w, &d);
    EXPECT_REJECT(fx, tb_shape_destroy(w, s), TB_ERROR_IN_USE);
    th_assert_ok(tb_body_destroy(w, a));
    EXPECT_REJECT(fx, tb_shape_destroy(w, s), TB_ERROR_IN_USE); /* b still uses it */
    assert_true(tb_shape_is_valid(w, s));
    th_assert_ok(tb_body_destroy(w, b));
    uint32_t shapes = th_stats(w).shape_count;
    th_assert_ok(tb_shape_destroy(w, s));
    assert_int_equal(th_stats(w).shape_count, shapes - 1);
    /* stepping after destroys is fine */
    th_assert_ok(tb_world_step(w, DT));
}

static void test_capacity(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.max_bodies = 4;
    wd.max_shapes = 2;
    fixture fx;
    memset(&fx, 0, sizeof fx);
    fx.w = th_world_create_ex(&wd, 1);
    fx.sphere = th_sphere(fx.w, 1);
    fx.box = th_box(fx.w, th_v3(1, 1, 1));
    tb_shape_id extra;
    tb_shape_def sd = tb_default_shape_def();
    th_assert_result(tb_shape_create_sphere(fx.w, &sd, 1, &extra), TB_ERROR_CAPACITY);
    tb_body_def d = th_dynamic_def(fx.sphere, th_v3(0, 0, 0));
    for (int i = 0; i < FX_BODIES; i++) fx.ids[i] = th_body(fx.w, &d);
    tb_body_id fourth = th_body(fx.w, &d), out;
    EXPECT_REJECT(&fx, tb_body_create(fx.w, &d, &out), TB_ERROR_CAPACITY);
    th_assert_ok(tb_body_destroy(fx.w, fourth));
    tb_body_def two[2] = { d, d };
    tb_body_id two_ids[2];
    EXPECT_REJECT(&fx, tb_body_create_many(fx.w, two, 2, two_ids), TB_ERROR_CAPACITY);
    th_body(fx.w, &d); /* one fits again */
    EXPECT_REJECT(&fx, tb_body_create(fx.w, &d, &out), TB_ERROR_CAPACITY);
    th_assert_ok(tb_world_step(fx.w, DT));
    th_world_destroy(fx.w);
}

int main(void)
{
#define T(f) cmocka_unit_test_setup_teardown(f, fx_setup, fx_teardown)
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_result_strings),
        T(test_bad_body_defs),
        T(test_quaternion_tolerance),
        T(test_bad_body_values),
        T(test_extreme_values),
        T(test_bad_shapes),
        T(test_bad_step_and_gravity),
        cmocka_unit_test(test_world_create_errors),
        cmocka_unit_test(test_broadphase_choice),
        T(test_null_and_unknown_body_ids),
        T(test_null_outputs),
        T(test_foreign_body_id),
        T(test_stale_body_ids),
        T(test_shape_ids),
        T(test_world_shape_ids),
        T(test_create_many_all_or_none),
        T(test_shape_in_use),
        cmocka_unit_test(test_capacity),
        T(test_bad_hulls),
        T(test_bad_meshes_and_heightfields),
        T(test_hull_shape),
    };
#undef T
    return cmocka_run_group_tests(tests, NULL, NULL);
}
