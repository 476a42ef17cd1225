/* Contact physics with analytic answers (DESIGN.md §7), through the public API on the whole
 * GPU step: resting contact, restitution, friction on an incline, a pile that settles, and
 * determinism. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

#define DT (1.0f / 60.0f)
#define G 9.81
#define PI 3.14159265358979323846

static tb_world* world_with_gravity(void)
{
    tb_world_def def = tb_default_world_def();
    return th_world_create(&def);
}

static tb_body_id ground_plane(tb_world* w, float restitution)
{
    tb_shape_def sd = tb_default_shape_def();
    sd.restitution = restitution;
    tb_shape_id plane;
    th_assert_ok(tb_shape_create_plane(w, &sd, th_v3(0, 1, 0), 0.0f, &plane));
    tb_body_def d = th_static_def(plane, th_v3(0, 0, 0));
    return th_body(w, &d);
}

static tb_vec3 velocity_of(tb_world* w, tb_body_id id)
{
    tb_vec3 v, a;
    th_assert_ok(tb_body_get_velocity(w, id, &v, &a));
    return v;
}

static double length3(tb_vec3 v)
{
    return sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
}

/* A sphere resting on a plane stays put: drift < 1 mm and speed < 1 mm/s over 600 steps. */
static void test_sphere_rests_on_plane(void** state)
{
    (void)state;
    tb_world* w = world_with_gravity();
    ground_plane(w, 0.0f);
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 0.5f, 0));
    tb_body_id ball = th_body(w, &d);
    for (int i = 0; i < 6; i++) th_assert_ok(tb_world_step_n(w, DT, 100));
    tb_vec3 p;
    th_read_pose(w, ball, &p, NULL);
    assert_true(length3(th_v3(p.x, p.y - 0.5f, p.z)) < 1e-3);
    assert_true(length3(velocity_of(w, ball)) < 1e-3);
    uint32_t n = 0;
    tb_contact c[8];
    th_assert_ok(tb_world_read_contacts(w, c, 8, &n));
    assert_int_equal(n, 1);
    assert_int_equal(th_stats(w).contact_count, 1);
    th_assert_near(c[0].normal_impulse, 1000.0 * 4.0 / 3.0 * PI * 0.125 * G * DT, 0, 0.02);
    th_world_destroy(w);
}

/* Height of the apex after the first bounce, m (the sphere's lowest point above the plane). */
static double bounce_apex(float restitution, float drop)
{
    tb_world* w = world_with_gravity();
    double apex = th_bounce_apex(w, restitution, drop);
    th_world_destroy(w);
    return apex;
}

/* A ball dropped with restitution e bounces to e^2 of its drop height within 5 %. */
static void test_restitution_bounce_height(void** state)
{
    (void)state;
    const float es[] = { 0.5f, 0.8f };
    for (int i = 0; i < 2; i++) {
        double apex = bounce_apex(es[i], 2.0f);
        th_assert_near(apex, es[i] * es[i] * 2.0, 0, 0.05);
    }
}

/* A fast body does not tunnel: a sphere, a box and a hull at 100 m/s (1.7 m per step, 34
 * times the thickness of a 5 cm wall) stop on the wall's face. Speculative contacts reach as
 * far as a body moves in the step, so this holds at any speed along a straight path. */
static void test_fast_bodies_stop_at_thin_wall(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&wd);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id wall, ball, cube, rock = th_rock(w);
    th_assert_ok(tb_shape_create_box(w, &sd, th_v3(0.025f, 5, 5), &wall));
    th_assert_ok(tb_shape_create_sphere(w, &sd, 0.1f, &ball));
    th_assert_ok(tb_shape_create_box(w, &sd, th_v3(0.1f, 0.1f, 0.1f), &cube));
    tb_body_def d = th_static_def(wall, th_v3(0, 0, 0));
    th_body(w, &d);
    const tb_shape_id shapes[3] = { ball, cube, rock };
    tb_body_id ids[3];
    for (int i = 0; i < 3; i++) {
        d = th_dynamic_def(shapes[i], th_v3(-3.05f, -2.0f + 2.0f * i, 0));
        d.linear_velocity = th_v3(100, 0, 0);
        ids[i] = th_body(w, &d);
    }
    for (int step = 0; step < 10; step++) th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    for (int i = 0; i < 3; i++) {
        tb_vec3 x;
        th_read_pose(w, ids[i], &x, NULL);
        print_message("  body %d: x %.4f, vx %.4f\n", i, x.x, velocity_of(w, ids[i]).x);
        assert_true(x.x < -0.025f - 0.08f && x.x > -0.025f - 0.2f);
        assert_true(velocity_of(w, ids[i]).x <= 0.01f);
    }
    th_world_destroy(w);
}

typedef struct incline { tb_world* w; tb_body_id box; tb_vec3 down; } incline;

/* A box of mu 0.5 at rest on a static slab tilted by `degrees` about z. */
static incline make_incline(double degrees)
{
    incline s;
    s.w = world_with_gravity();
    double t = degrees * PI / 180.0;
    tb_quat q = th_quat_axis_angle(th_v3(0, 0, 1), t);
    tb_shape_def sd = tb_default_shape_def();
    sd.friction = 0.5f;
    tb_shape_id slab, cube;
    th_assert_ok(tb_shape_create_box(s.w, &sd, th_v3(20, 0.5f, 5), &slab));
    th_assert_ok(tb_shape_create_box(s.w, &sd, th_v3(0.25f, 0.25f, 0.25f), &cube));
    tb_body_def d = th_static_def(slab, th_v3(0, 0, 0));
    d.rotation = q;
    th_body(s.w, &d);
    /* The slab's top face is at local y = 0.5; the cube's centre 0.25 above it. */
    double up[3] = { 0, 0.75, 0 }, at[3];
    th_quat_rotate(q, up, at);
    tb_body_def b = th_dynamic_def(cube, th_v3((float)at[0], (float)at[1], (float)at[2]));
    b.rotation = q;
    s.box = th_body(s.w, &b);
    double x[3] = { -1, 0, 0 }, down[3];
    th_quat_rotate(q, x, down);   /* downhill along the slope */
    s.down = th_v3((float)down[0], (float)down[1], (float)down[2]);
    return s;
}

static double along(tb_vec3 v, tb_vec3 d)
{
    return (double)v.x * d.x + (double)v.y * d.y + (double)v.z * d.z;
}

static void test_incline_sticks_below_atan_mu(void** state)
{
    (void)state;
    incline s = make_incline(20.0);
    tb_vec3 p0, p1;
    th_read_pose(s.w, s.box, &p0, NULL);
    th_assert_ok(tb_world_step_n(s.w, DT, 120));
    th_read_pose(s.w, s.box, &p1, NULL);
    assert_true(length3(th_v3(p1.x - p0.x, p1.y - p0.y, p1.z - p0.z)) < 0.01);
    th_world_destroy(s.w);
}

static void test_incline_slides_above_atan_mu(void** state)
{
    (void)state;
    double t = 35.0 * PI / 180.0;
    incline s = make_incline(35.0);
    th_assert_ok(tb_world_step_n(s.w, DT, 30));
    double v1 = along(velocity_of(s.w, s.box), s.down);
    th_assert_ok(tb_world_step_n(s.w, DT, 60));
    double v2 = along(velocity_of(s.w, s.box), s.down);
    double a = (v2 - v1) / (60 * DT);
    th_assert_near(a, G * (sin(t) - 0.5 * cos(t)), 0, 0.05);
    th_world_destroy(s.w);
}

typedef struct pile_result { tb_vec3* pos; tb_quat* rot; uint32_t n; } pile_result;

/* 1000 spheres poured into the bench's container: their poses after `first` steps; then,
 * when `settle` is not 0, `settle` steps more and the scene's checks (no NaN, none
 * escaped, less than 1 cm of penetration). */
static pile_result pour_spheres(uint32_t first, uint32_t settle)
{
    tb_world* w = world_with_gravity();
    const scene* sc = scene_find("spheres");
    assert_non_null(sc);
    scene_params params = { 1000, 1 };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    th_assert_ok(tb_world_step_n(w, sc->dt, first));
    pile_result r;
    const tb_body_id* ids = scene_body_ids(inst, &r.n);
    r.pos = calloc(r.n, sizeof *r.pos);
    r.rot = calloc(r.n, sizeof *r.rot);
    th_assert_ok(tb_world_read_transforms(w, ids, r.n, r.pos, r.rot));
    if (settle) {
        th_assert_ok(tb_world_step_n(w, sc->dt, settle));
        scene_checks checks = { 0 };
        th_assert_ok(sc->check(w, inst, first + settle, sc->dt, &checks));
        for (uint32_t i = 0; i < checks.count; i++) {
            const char* k = checks.items[i].key;
            double v = checks.items[i].value;
            print_message("  %s %g\n", k, v);
            if (!strcmp(k, "nan") || !strcmp(k, "escaped")) assert_true(v == 0);
            if (!strcmp(k, "max_penetration")) assert_true(v < 0.01);
        }
    }
    sc->destroy(inst);
    th_world_destroy(w);
    return r;
}

/* 1000 spheres poured into a box: no NaN, no escape, max penetration < 1 cm once settled
 * (420 steps); the same pour twice is bit-identical through its first 150 steps, where
 * they fall, land and pile up (after 150 steps of 1000 colliding spheres any difference
 * in any step has long spread; test_golden follows a pile of every shape to its end). */
static void test_pour_spheres_settles_deterministically(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the sphere pour", "256")) skip();
    pile_result a = pour_spheres(150, 270);
    pile_result b = pour_spheres(150, 0);
    assert_int_equal(a.n, b.n);
    assert_memory_equal(a.pos, b.pos, a.n * sizeof *a.pos);
    assert_memory_equal(a.rot, b.rot, a.n * sizeof *a.rot);
    free(a.pos); free(a.rot); free(b.pos); free(b.rot);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_rests_on_plane),
        cmocka_unit_test(test_restitution_bounce_height),
        cmocka_unit_test(test_fast_bodies_stop_at_thin_wall),
        cmocka_unit_test(test_incline_sticks_below_atan_mu),
        cmocka_unit_test(test_incline_slides_above_atan_mu),
        cmocka_unit_test(test_pour_spheres_settles_deterministically),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
