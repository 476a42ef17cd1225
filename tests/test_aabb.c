/* World AABBs computed by broadphase/world_aabb: they must contain the shape (never miss
 * a contact) and be tight (no needless pairs). Zero gravity and velocity, so the pose the
 * AABB is computed from is exactly the pose given. */
#include "harness.h"

#include <math.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define N_BODIES 64

static tb_world* zero_gravity_world(void)
{
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    return th_world_create(&wd);
}

/* Corner `c` (bit i = sign on axis i) of box `he` at pose (p, q), in world space. */
static void box_corner(tb_vec3 p, tb_quat q, tb_vec3 he, int c, double out[3])
{
    double local[3] = { (c & 1) ? he.x : -he.x, (c & 2) ? he.y : -he.y,
                        (c & 4) ? he.z : -he.z };
    th_quat_rotate(q, local, out);
    out[0] += p.x; out[1] += p.y; out[2] += p.z;
}

/* All 8 corners inside [mn, mx] (1e-4 slack), and every face touched by a corner (1e-3). */
static void check_box_aabb(int body, tb_vec3 p, tb_quat q, tb_vec3 he, tb_vec3 mn, tb_vec3 mx)
{
    const double lo[3] = { mn.x, mn.y, mn.z }, hi[3] = { mx.x, mx.y, mx.z };
    double best_lo[3] = { INFINITY, INFINITY, INFINITY };
    double best_hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int c = 0; c < 8; c++) {
        double k[3];
        box_corner(p, q, he, c, k);
        for (int i = 0; i < 3; i++) {
            if (!(k[i] >= lo[i] - 1e-4 && k[i] <= hi[i] + 1e-4))
                fail_msg("box %d corner %d axis %d at %.7g outside [%.7g, %.7g]", body, c, i,
                         k[i], lo[i], hi[i]);
            best_lo[i] = fmin(best_lo[i], k[i]);
            best_hi[i] = fmax(best_hi[i], k[i]);
        }
    }
    for (int i = 0; i < 3; i++)
        if (!th_near(lo[i], best_lo[i], 1e-3, 0) || !th_near(hi[i], best_hi[i], 1e-3, 0))
            fail_msg("box %d axis %d: AABB [%.7g, %.7g], corners span [%.7g, %.7g]", body, i,
                     lo[i], hi[i], best_lo[i], best_hi[i]);
}

static void check_sphere_aabb(int body, tb_vec3 p, float r, tb_vec3 mn, tb_vec3 mx)
{
    const double c[3] = { p.x, p.y, p.z }, lo[3] = { mn.x, mn.y, mn.z };
    const double hi[3] = { mx.x, mx.y, mx.z };
    for (int i = 0; i < 3; i++)
        if (!th_near(lo[i], c[i] - r, 1e-4, 0) || !th_near(hi[i], c[i] + r, 1e-4, 0))
            fail_msg("sphere %d (r %.7g) axis %d: AABB [%.7g, %.7g], want [%.7g, %.7g]", body,
                     (double)r, i, lo[i], hi[i], c[i] - r, c[i] + r);
}

/* Random boxes or spheres (one shape each) at random poses, seeded; checks every AABB. */
static void check_random_poses(int boxes, uint64_t seed)
{
    tb_world* w = zero_gravity_world();
    th_rng rng = th_rng_seed(seed);
    tb_body_id ids[N_BODIES];
    tb_vec3 size[N_BODIES]; /* half extents, or radius in x */
    for (int i = 0; i < N_BODIES; i++) {
        size[i] = th_v3(th_rng_range(&rng, 0.05f, 3), th_rng_range(&rng, 0.05f, 3),
                        th_rng_range(&rng, 0.05f, 3));
        tb_shape_id s = boxes ? th_box(w, size[i]) : th_sphere(w, size[i].x);
        tb_body_def d = th_dynamic_def(s, th_v3(th_rng_range(&rng, -50, 50),
                                                th_rng_range(&rng, -50, 50),
                                                th_rng_range(&rng, -50, 50)));
        d.rotation = th_rng_quat(&rng);
        ids[i] = th_body(w, &d);
    }
    /* The header: zero before the first step that saw the body. */
    tb_vec3 mn[N_BODIES], mx[N_BODIES], p[N_BODIES];
    tb_quat q[N_BODIES];
    th_assert_ok(tb_world_read_aabbs(w, ids, N_BODIES, mn, mx));
    for (int i = 0; i < N_BODIES; i++) {
        th_assert_vec3_near(mn[i], th_v3(0, 0, 0), 0, 0);
        th_assert_vec3_near(mx[i], th_v3(0, 0, 0), 0, 0);
    }
    th_assert_ok(tb_world_step(w, DT));
    /* Compare with the pose after the step (identical to the given one: nothing moves). */
    th_assert_ok(tb_world_read_transforms(w, ids, N_BODIES, p, q));
    th_assert_ok(tb_world_read_aabbs(w, ids, N_BODIES, mn, mx));
    for (int i = 0; i < N_BODIES; i++) {
        if (boxes) check_box_aabb(i, p[i], q[i], size[i], mn[i], mx[i]);
        else check_sphere_aabb(i, p[i], size[i].x, mn[i], mx[i]);
    }
    /* Either output may be NULL. */
    tb_vec3 mx2[N_BODIES];
    th_assert_ok(tb_world_read_aabbs(w, ids, N_BODIES, NULL, mx2));
    assert_memory_equal(mx, mx2, sizeof mx);
    th_world_destroy(w);
}

/* Box AABB = exact bounds of the 8 rotated corners. */
static void test_random_boxes(void** state)
{
    (void)state;
    check_random_poses(1, 1234);
}

/* Sphere AABB = centre +- r whatever the rotation (a rotated cube around it would be up to
 * sqrt(3) too wide and cost broadphase pairs). */
static void test_random_spheres(void** state)
{
    (void)state;
    check_random_poses(0, 4321);
}

/* A box rotated by 45 degrees about z: the AABB half width in x and y is (hx + hy)/sqrt 2,
 * a hand-computed case independent of th_quat_rotate. */
static void test_box_45_degrees(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    tb_shape_id b = th_box(w, th_v3(1, 2, 0.5f));
    tb_body_def d = th_dynamic_def(b, th_v3(10, -3, 4));
    d.rotation = th_quat_axis_angle(th_v3(0, 0, 1), 3.14159265358979 / 4);
    tb_body_id id = th_body(w, &d);
    th_assert_ok(tb_world_step(w, DT));
    tb_vec3 mn, mx;
    th_assert_ok(tb_world_read_aabbs(w, &id, 1, &mn, &mx));
    const double h = 3.0 / sqrt(2.0);
    th_assert_vec3_near(mn, th_v3((float)(10 - h), (float)(-3 - h), 3.5f), 1e-4, 0);
    th_assert_vec3_near(mx, th_v3((float)(10 + h), (float)(-3 + h), 4.5f), 1e-4, 0);
    th_world_destroy(w);
}

/* AABBs follow the body: after moving it by set_pose and a step, the AABB moves too. */
static void test_aabb_follows_pose(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    tb_shape_id s = th_sphere(w, 0.75f);
    tb_body_def d = th_dynamic_def(s, th_v3(1, 1, 1));
    tb_body_id id = th_body(w, &d);
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_body_set_pose(w, id, th_v3(-5, 7, 2), th_q(0, 0, 0, 1)));
    th_assert_ok(tb_world_step(w, DT));
    tb_vec3 mn, mx;
    th_assert_ok(tb_world_read_aabbs(w, &id, 1, &mn, &mx));
    check_sphere_aabb(0, th_v3(-5, 7, 2), 0.75f, mn, mx);
    th_world_destroy(w);
}

/* The world bounds of a capsule (kind 0), cylinder (1) or cone (2) of radius r and half
 * height h at pose (p, q), from its axis's ends and (a cylinder's or cone's) rims sampled
 * finely: the axis is the body's y; a cone's base lies h/2 below its origin, its apex 3h/2
 * above. */
static void round_bounds(int kind, float r, float h, tb_vec3 p, tb_quat q, double lo[3],
                         double hi[3])
{
    const double ends[2] = { kind == 2 ? -h / 2.0 : -h, kind == 2 ? 1.5 * h : h };
    for (int i = 0; i < 3; i++) lo[i] = INFINITY, hi[i] = -INFINITY;
    for (int e = 0; e < 2; e++) {
        int rim = kind == 1 || (kind == 2 && e == 0);
        for (int k = 0; k < (rim ? 4096 : 1); k++) {
            double t = 2 * 3.14159265358979 * k / 4096;
            double local[3] = { rim ? r * cos(t) : 0, ends[e], rim ? r * sin(t) : 0 }, v[3];
            th_quat_rotate(q, local, v);
            const double c[3] = { p.x, p.y, p.z }, ball = kind == 0 ? r : 0;
            for (int i = 0; i < 3; i++) {
                lo[i] = fmin(lo[i], c[i] + v[i] - ball);
                hi[i] = fmax(hi[i], c[i] + v[i] + ball);
            }
        }
    }
}

/* Capsules, cylinders and cones: the AABB bounds the turned shape itself (its axis's ends
 * and rims), not its turned local box, which is up to 1.4 times wider on each axis. */
static void test_random_round_shapes(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    th_rng rng = th_rng_seed(777);
    tb_shape_def sd = tb_default_shape_def();
    tb_body_id ids[N_BODIES];
    float radius[N_BODIES], half[N_BODIES];
    for (int i = 0; i < N_BODIES; i++) {
        radius[i] = th_rng_range(&rng, 0.05f, 2);
        half[i] = th_rng_range(&rng, 0.05f, 3);
        tb_shape_id s;
        if (i % 3 == 0) th_assert_ok(tb_shape_create_capsule(w, &sd, radius[i], half[i], &s));
        if (i % 3 == 1) th_assert_ok(tb_shape_create_cylinder(w, &sd, radius[i], half[i], &s));
        if (i % 3 == 2) th_assert_ok(tb_shape_create_cone(w, &sd, radius[i], half[i], &s));
        tb_body_def d = th_dynamic_def(s, th_v3(th_rng_range(&rng, -50, 50),
                                                th_rng_range(&rng, -50, 50),
                                                th_rng_range(&rng, -50, 50)));
        d.rotation = th_rng_quat(&rng);
        ids[i] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step(w, DT));
    tb_vec3 mn[N_BODIES], mx[N_BODIES], p[N_BODIES];
    tb_quat q[N_BODIES];
    th_assert_ok(tb_world_read_transforms(w, ids, N_BODIES, p, q));
    th_assert_ok(tb_world_read_aabbs(w, ids, N_BODIES, mn, mx));
    for (int b = 0; b < N_BODIES; b++) {
        double lo[3], hi[3];
        round_bounds(b % 3, radius[b], half[b], p[b], q[b], lo, hi);
        const double got_lo[3] = { mn[b].x, mn[b].y, mn[b].z };
        const double got_hi[3] = { mx[b].x, mx[b].y, mx[b].z };
        for (int i = 0; i < 3; i++)
            if (!(got_lo[i] <= lo[i] + 1e-4 && got_hi[i] >= hi[i] - 1e-4) ||
                !th_near(got_lo[i], lo[i], 1e-3, 0) || !th_near(got_hi[i], hi[i], 1e-3, 0))
                fail_msg("round shape %d (kind %d) axis %d: AABB [%.7g, %.7g], shape spans "
                         "[%.7g, %.7g]", b, b % 3, i, got_lo[i], got_hi[i], lo[i], hi[i]);
    }
    th_world_destroy(w);
}

/* A static plane's AABB is unbounded in practice (>= 1e17 half width on every axis) but
 * finite, so later stages can do arithmetic on it. */
static void test_plane_aabb(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    const tb_vec3 normals[3] = { { 0, 1, 0 }, { 1, 1, 0 }, { -0.3f, 0.2f, 0.9f } };
    tb_body_id ids[3];
    for (int i = 0; i < 3; i++) {
        tb_shape_id pl = th_plane(w, normals[i], 0.5f);
        tb_body_def d = th_static_def(pl, th_v3(0, -1.0f * i, 0));
        ids[i] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step(w, DT));
    tb_vec3 mn[3], mx[3];
    th_assert_ok(tb_world_read_aabbs(w, ids, 3, mn, mx));
    for (int i = 0; i < 3; i++) {
        const float lo[3] = { mn[i].x, mn[i].y, mn[i].z }, hi[3] = { mx[i].x, mx[i].y, mx[i].z };
        const float origin[3] = { 0, -1.0f * i, 0 };
        for (int a = 0; a < 3; a++) {
            assert_true(isfinite(lo[a]) && isfinite(hi[a]));
            if (!((double)hi[a] - lo[a] >= 2e17))
                fail_msg("plane %d axis %d: AABB [%g, %g] is not unbounded", i, a, lo[a], hi[a]);
            /* it contains the body's origin, which lies in the half-space's closure */
            assert_true(lo[a] <= origin[a] && hi[a] >= origin[a]);
        }
    }
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_boxes),
        cmocka_unit_test(test_random_spheres),
        cmocka_unit_test(test_box_45_degrees),
        cmocka_unit_test(test_random_round_shapes),
        cmocka_unit_test(test_aabb_follows_pose),
        cmocka_unit_test(test_plane_aabb),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
