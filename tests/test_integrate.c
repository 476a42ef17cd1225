/* Integration on the GPU (lavapipe): gravity, damping, semi-implicit Euler, the orientation
 * update and its clamp, the gyroscopic term, static bodies, impulses, gravity scale. References are computed in
 * double with the same recurrence the engine documents, so the tolerances only have to
 * absorb float rounding, not a different scheme. */
#include "harness.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define PI 3.14159265358979323846

/* One body's reference state, advanced in double by the documented recurrence: per step
 * v = v / (1 + dt*c) (damping), then per substep of h = dt / substeps
 * v += g*scale*h; x += v*h   (semi-implicit Euler). */
typedef struct ref_body {
    double x[3], v[3];
} ref_body;

static ref_body ref_make(tb_vec3 x, tb_vec3 v)
{
    ref_body r = { { x.x, x.y, x.z }, { v.x, v.y, v.z } };
    return r;
}

static int substeps(void)
{
    return (int)tb_default_world_def().substeps;
}

static void ref_step(ref_body* r, tb_vec3 g, double scale, double damping, int steps)
{
    const double dt = DT, h = dt / substeps(), gv[3] = { g.x, g.y, g.z };
    for (int k = 0; k < steps; k++)
        for (int i = 0; i < 3; i++) {
            r->v[i] /= 1.0 + dt * damping;
            for (int s = 0; s < substeps(); s++) {
                r->v[i] += gv[i] * scale * h;
                r->x[i] += r->v[i] * h;
            }
        }
}

static void assert_matches_ref(tb_world* w, tb_body_id id, const ref_body* r, double x_tol,
                               double v_rel)
{
    tb_vec3 p, v, av;
    th_read_pose(w, id, &p, NULL);
    th_assert_ok(tb_body_get_velocity(w, id, &v, &av));
    th_assert_near(p.x, r->x[0], x_tol, 0);
    th_assert_near(p.y, r->x[1], x_tol, 0);
    th_assert_near(p.z, r->x[2], x_tol, 0);
    th_assert_near(v.x, r->v[0], 1e-5, v_rel);
    th_assert_near(v.y, r->v[1], 1e-5, v_rel);
    th_assert_near(v.z, r->v[2], 1e-5, v_rel);
}

/* A world of definition `def` (NULL: the defaults) for `solver`: "soft" the soft step,
 * "block" the block solver. */
static tb_world* world_of(const tb_world_def* def, const char* solver)
{
    tb_world* w = th_world_create(def);
    int block = strcmp(solver, "block") == 0;
    th_assert_ok(tb_world_set_solver(w, block ? TB_SOLVER_BLOCK : TB_SOLVER_SOFT_STEP, 0));
    return w;
}

/* (a) Free fall of spheres and boxes with initial velocity. After one step the position
 * must include g*h*dt (semi-implicit per substep of h: velocity first), which explicit Euler
 * would miss; after 120 steps, n = 120 * substeps substeps of h, the closed form
 * x0 + v0 n h + g h^2 n(n+1)/2. */
static void free_fall(const char* solver)
{
    tb_world* w = world_of(NULL, solver);
    const tb_vec3 g = tb_world_get_gravity(w);
    th_assert_near(g.y, -9.81, 1e-6, 0); /* the documented default */
    tb_shape_id sphere = th_sphere(w, 0.5f), box = th_box(w, th_v3(0.5f, 0.25f, 1.0f));
    th_rng rng = th_rng_seed(7);
    enum { N = 6 };
    tb_body_id ids[N];
    ref_body ref[N];
    tb_quat q0[N];
    tb_vec3 v0[N];
    for (int i = 0; i < N; i++) {
        tb_body_def d = th_dynamic_def(i % 2 ? box : sphere,
                                       th_v3(3.0f * i, 10.0f, -2.0f * i));
        d.linear_velocity = th_v3(th_rng_range(&rng, -3, 3), th_rng_range(&rng, 0, 8),
                                  th_rng_range(&rng, -3, 3));
        d.rotation = th_rng_quat(&rng);
        ids[i] = th_body(w, &d);
        ref[i] = ref_make(d.position, d.linear_velocity);
        v0[i] = d.linear_velocity;
    }
    th_assert_ok(tb_world_read_transforms(w, ids, N, NULL, q0));

    th_assert_ok(tb_world_step(w, DT));
    for (int i = 0; i < N; i++) {
        ref_step(&ref[i], g, 1, 0, 1);
        assert_matches_ref(w, ids[i], &ref[i], 1e-5, 1e-5);
    }
    /* 119 more steps, mixing step and step_n: both are documented as the same thing. */
    th_assert_ok(tb_world_step_n(w, DT, 59));
    for (int k = 0; k < 60; k++) th_assert_ok(tb_world_step(w, DT));
    const int k = 120;
    for (int i = 0; i < N; i++) {
        ref_step(&ref[i], g, 1, 0, k - 1);
        assert_matches_ref(w, ids[i], &ref[i], 1e-3, 1e-4);
        tb_quat q;
        th_read_pose(w, ids[i], NULL, &q);
        /* no angular velocity: the orientation must not drift */
        th_assert_near(q.x, q0[i].x, 1e-6, 0);
        th_assert_near(q.y, q0[i].y, 1e-6, 0);
        th_assert_near(q.z, q0[i].z, 1e-6, 0);
        th_assert_near(q.w, q0[i].w, 1e-6, 0);
    }
    /* The closed form itself, independent of ref_step:
     * x_n = x0 + v0 n h + g h^2 n(n+1)/2, v_n = v0 + g n h, n = k substeps. */
    for (int i = 0; i < N; i++) {
        tb_vec3 p, v, av;
        th_read_pose(w, ids[i], &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, ids[i], &v, &av));
        const double dt = DT, n = (double)k * substeps(), h = dt / substeps();
        const double c = h * h * n * (n + 1) / 2.0;
        th_assert_near(p.x, 3.0 * i + v0[i].x * k * dt + g.x * c, 1e-3, 0);
        th_assert_near(p.y, 10.0 + v0[i].y * k * dt + g.y * c, 1e-3, 0);
        th_assert_near(p.z, -2.0 * i + v0[i].z * k * dt + g.z * c, 1e-3, 0);
        th_assert_near(v.y, v0[i].y + g.y * k * dt, 1e-5, 1e-4);
    }
    tb_world_stats st = th_stats(w);
    assert_int_equal(st.steps, 120);
    th_world_destroy(w);
}

/* Both solvers: the block solver solves a step in one piece but a body without contacts
 * moves as the substeps would move it (block/end). */
static void test_free_fall(void** state)
{
    (void)state;
    free_fall("soft");
    free_fall("block");
}

/* Local axis `axis` of a body with rotation q, in world coordinates. */
static void body_axis(tb_quat q, int axis, double out[3])
{
    double e[3] = { 0, 0, 0 };
    e[axis] = 1;
    th_quat_rotate(q, e, out);
}

/* (b) Spin about a principal axis (the largest-inertia axis of a box with three different
 * half extents, a stable axis): no torque, so the angular velocity stays, the quaternion
 * stays unit, and the body turns by omega*t about the fixed world axis. */
static void test_principal_spin(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&wd);
    /* inertia ~ (hy^2+hz^2, hx^2+hz^2, hx^2+hy^2) = (5, 4.25, 1.25): x is the largest */
    tb_shape_id box = th_box(w, th_v3(0.5f, 1.0f, 2.0f));
    const double omega = 2.0;
    th_rng rng = th_rng_seed(3);
    tb_body_def d = th_dynamic_def(box, th_v3(1, 2, 3));
    d.rotation = th_rng_quat(&rng);
    double ax[3];
    body_axis(d.rotation, 0, ax); /* local x in world frame */
    d.angular_velocity = th_v3((float)(omega * ax[0]), (float)(omega * ax[1]),
                               (float)(omega * ax[2]));
    tb_body_id id = th_body(w, &d);
    tb_vec3 w0 = d.angular_velocity;
    double y0[3];
    body_axis(d.rotation, 1, y0);

    for (int chunk = 1; chunk <= 4; chunk++) {
        th_assert_ok(tb_world_step_n(w, DT, 250));
        tb_vec3 p, lv, av;
        tb_quat q;
        th_read_pose(w, id, &p, &q);
        th_assert_ok(tb_body_get_velocity(w, id, &lv, &av));
        th_assert_near(th_quat_length(q), 1.0, 1e-5, 0);
        th_assert_vec3_near(av, w0, 1e-5 * omega, 0); /* 1e-5 of |omega| */
        th_assert_vec3_near(p, d.position, 0, 0); /* no linear motion at all */
        /* analytic: local y rotated about the fixed spin axis by omega*t */
        double t = 250.0 * chunk * (double)DT, y_want[3], y_got[3];
        th_quat_rotate(th_quat_axis_angle(w0, omega * t), y0, y_want);
        body_axis(q, 1, y_got);
        for (int i = 0; i < 3; i++) th_assert_near(y_got[i], y_want[i], 1e-3, 0);
        /* the spin axis itself is carried along unchanged */
        double x_got[3];
        body_axis(q, 0, x_got);
        for (int i = 0; i < 3; i++) th_assert_near(x_got[i], ax[i], 1e-4, 0);
    }
    th_world_destroy(w);
}

/* A body's angular velocity in its own frame, its principal moments, and from them its
 * world angular momentum R I R^T w and kinetic energy of rotation, in double. */
typedef struct spin_state {
    double body_w[3], L[3], energy;
} spin_state;

static spin_state spin_of(tb_world* w, tb_body_id id)
{
    float mass;
    tb_vec3 I, lv, av;
    tb_quat q;
    th_assert_ok(tb_body_get_mass(w, id, &mass, &I));
    th_read_pose(w, id, NULL, &q);
    th_assert_ok(tb_body_get_velocity(w, id, &lv, &av));
    spin_state s;
    const double world_w[3] = { av.x, av.y, av.z };
    th_quat_rotate((tb_quat){ -q.x, -q.y, -q.z, q.w }, world_w, s.body_w);
    const double Iw[3] = { I.x * s.body_w[0], I.y * s.body_w[1], I.z * s.body_w[2] };
    th_quat_rotate(q, Iw, s.L);
    s.energy = 0.5 * (s.body_w[0] * Iw[0] + s.body_w[1] * Iw[1] + s.body_w[2] * Iw[2]);
    return s;
}

static double norm3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A world without gravity for `solver`. */
static tb_world* weightless_world(const char* solver)
{
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    return world_of(&wd, solver);
}

/* (b') A free 1 x 2 x 3 box spinning about a generic axis: no torque, so its world angular
 * momentum stays (within 1 % over 10 s at 60 Hz, though the angular velocity wanders among
 * the body axes) and its energy neither grows nor drains (within 1 %). Both solvers: the
 * block solver predicts the step's turn in the world's substeps as pieces (in one piece
 * the momentum drifted 1.6 %). */
static void torque_free_spin(const char* solver)
{
    tb_world* w = weightless_world(solver);
    tb_shape_id box = th_box(w, th_v3(0.5f, 1.0f, 1.5f));
    th_rng rng = th_rng_seed(11);
    tb_body_def d = th_dynamic_def(box, th_v3(0, 0, 0));
    d.rotation = th_rng_quat(&rng);
    d.angular_velocity = th_v3(2.0f, 3.0f, -1.0f);
    tb_body_id id = th_body(w, &d);
    spin_state start = spin_of(w, id);
    double turned = 0;   /* how far the angular velocity moved in the body frame */
    for (int second = 1; second <= 10; second++) {
        th_assert_ok(tb_world_step_n(w, DT, 60));
        spin_state now = spin_of(w, id);
        double dL[3] = { now.L[0] - start.L[0], now.L[1] - start.L[1], now.L[2] - start.L[2] };
        th_assert_near(norm3(dL) / norm3(start.L), 0, 0.01, 0);
        th_assert_near(now.energy / start.energy, 1, 0.01, 0);
        double dw[3] = { now.body_w[0] - start.body_w[0], now.body_w[1] - start.body_w[1],
                         now.body_w[2] - start.body_w[2] };
        if (norm3(dw) > turned) turned = norm3(dw);
    }
    /* Without the gyroscopic term w would stay fixed in the world; here it precesses. */
    assert_true(turned > 0.5 * norm3(start.body_w));
    th_world_destroy(w);
}

static void test_torque_free_spin(void** state)
{
    (void)state;
    torque_free_spin("soft");
    torque_free_spin("block");
}

/* (b'') The intermediate-axis (Dzhanibekov) flip: spun about its intermediate axis with a
 * hair of spin about the others, the box turns over again and again; the spin about that
 * axis, seen in the body frame, reverses within 10 s and the energy stays. Both solvers. */
static void intermediate_axis_flip(const char* solver)
{
    tb_world* w = weightless_world(solver);
    /* moments ~ (hy^2+hz^2, hx^2+hz^2, hx^2+hy^2) = (3.25, 2.5, 1.25): y is intermediate */
    tb_shape_id box = th_box(w, th_v3(0.5f, 1.0f, 1.5f));
    tb_body_def d = th_dynamic_def(box, th_v3(0, 0, 0));
    d.angular_velocity = th_v3(0.01f, 5.0f, 0.01f);
    tb_body_id id = th_body(w, &d);
    spin_state start = spin_of(w, id);
    double lowest = start.body_w[1];
    for (int k = 0; k < 60; k++) {
        th_assert_ok(tb_world_step_n(w, DT, 10));
        spin_state now = spin_of(w, id);
        if (now.body_w[1] < lowest) lowest = now.body_w[1];
        th_assert_near(now.energy / start.energy, 1, 0.01, 0);
    }
    assert_true(lowest < -0.9 * start.body_w[1]);
    th_world_destroy(w);
}

static void test_intermediate_axis_flip(void** state)
{
    (void)state;
    intermediate_axis_flip("soft");
    intermediate_axis_flip("block");
}

/* A spinning top: a double cone (a hull) standing on its tip on a plane with friction. */
typedef struct top {
    tb_body_id id;
    tb_quat to_input;   /* body frame -> the frame the points were given in (axis = y) */
    double mass, tip_to_centre, axial, transverse_at_tip;
} top;

static top top_create(tb_world* w, double tilt, double spin)
{
    enum { RING = 24 };
    tb_vec3 points[RING + 2];
    points[0] = th_v3(0, 0, 0);        /* the tip */
    points[1] = th_v3(0, 0.4f, 0);     /* the crown */
    for (int k = 0; k < RING; k++) {
        double a = 2 * PI * k / RING;
        points[2 + k] = th_v3((float)(0.4 * cos(a)), 0.25f, (float)(0.4 * sin(a)));
    }
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shape = tb_null_shape;
    th_assert_ok(tb_shape_create_hull(w, &sd, points, RING + 2, &shape));
    tb_hull_info info;
    th_assert_ok(tb_shape_get_hull_info(w, shape, &info));
    top t;
    t.to_input = info.principal_axes;
    /* The axis in the world: y tilted about x; the tip stays at the origin, on the plane. */
    tb_quat tilt_q = th_quat_axis_angle(th_v3(1, 0, 0), tilt);
    versor body, tq = { tilt_q.x, tilt_q.y, tilt_q.z, tilt_q.w },
                 pq = { info.principal_axes.x, info.principal_axes.y, info.principal_axes.z,
                        info.principal_axes.w };
    glm_quat_mul(tq, pq, body);
    const double com[3] = { info.center_of_mass.x, info.center_of_mass.y, info.center_of_mass.z };
    const double up[3] = { 0, 1, 0 };
    double at[3], axis[3];
    th_quat_rotate(tilt_q, com, at);
    th_quat_rotate(tilt_q, up, axis);
    tb_body_def d = th_dynamic_def(shape, th_v3((float)at[0], (float)at[1] + 1e-3f, (float)at[2]));
    d.rotation = th_q(body[0], body[1], body[2], body[3]);
    d.angular_velocity = th_v3((float)(spin * axis[0]), (float)(spin * axis[1]),
                               (float)(spin * axis[2]));
    t.id = th_body(w, &d);
    /* Moments about the symmetry axis and across it (the body axis the input y maps to). */
    float mass;
    tb_vec3 I;
    th_assert_ok(tb_body_get_mass(w, t.id, &mass, &I));
    const tb_quat back = { -info.principal_axes.x, -info.principal_axes.y, -info.principal_axes.z,
                           info.principal_axes.w };
    double y_body[3];
    th_quat_rotate(back, up, y_body);
    const double moments[3] = { I.x, I.y, I.z };
    int a = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(y_body[k]) > fabs(y_body[a])) a = k;
    t.mass = mass;
    t.tip_to_centre = info.center_of_mass.y;
    t.axial = moments[a];
    t.transverse_at_tip = moments[(a + 1) % 3] + mass * t.tip_to_centre * t.tip_to_centre;
    return t;
}

/* The top's symmetry axis in the world. */
static void top_axis(tb_world* w, const top* t, double axis[3])
{
    tb_quat q;
    th_read_pose(w, t->id, NULL, &q);
    versor world = { q.x, q.y, q.z, q.w }, input,
           back = { -t->to_input.x, -t->to_input.y, -t->to_input.z, t->to_input.w };
    glm_quat_mul(world, back, input);
    const double up[3] = { 0, 1, 0 };
    th_quat_rotate(th_q(input[0], input[1], input[2], input[3]), up, axis);
}

/* (b3) A spinning top precesses: spun on its tip at 40 rad/s (below the step's rotation
 * clamp, which would slow the turning of a faster one), tilted 20 degrees, it neither falls
 * nor stays put but its axis turns about the vertical at the slow rate of the heavy top,
 * the root of I1 W^2 cos(tilt) - I3 s W + m g l = 0 (I1 about the tip, I3 about the axis,
 * s the spin, l the tip-to-centre distance), within 5 % over 2 s (lavapipe: 1.21 rad/s
 * against 1.22), and the tilt stays within 8 degrees. It creeps by 5 in 2 s at 60 Hz, the
 * energy growing 0.35 %: an error of what is computed once a step (such as the contact, its
 * arms, the world inverse inertia), since at the same substep rate it shrinks with the step
 * (24 substeps at 60 Hz: 3.7 degrees; 6 at 240 Hz: 2.0, most of it the top's own nutation).
 * Without the gyroscopic term the spin stays fixed in the world and the top topples within
 * a second. */
static void test_spinning_top_precesses(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    tb_world* w = th_world_create(&wd);
    tb_shape_id ground = th_plane(w, th_v3(0, 1, 0), 0);
    tb_body_def gd = th_static_def(ground, th_v3(0, 0, 0));
    th_body(w, &gd);
    const double tilt = 20 * PI / 180, spin = 40;
    top t = top_create(w, tilt, spin);
    const double g = -wd.gravity.y, c = cos(tilt), a = t.transverse_at_tip * c;
    const double b = t.axial * spin, disc = b * b - 4 * a * t.mass * g * t.tip_to_centre;
    assert_true(disc > 0);   /* a fast top */
    const double expected = (b - sqrt(disc)) / (2 * a);
    double axis[3], turned = 0, last = 0, worst = 0;
    for (int k = 1; k <= 120; k++) {
        th_assert_ok(tb_world_step(w, DT));
        top_axis(w, &t, axis);
        double off = fabs(acos(axis[1]) - tilt);
        if (off > worst) worst = off;
        double azimuth = atan2(axis[0], axis[2]), d = azimuth - last;
        if (d > PI) d -= 2 * PI;
        if (d < -PI) d += 2 * PI;
        turned += d;
        last = azimuth;
    }
    print_message("top: precession %.4f rad/s (expected %.4f), tilt off by %.2f deg at most\n",
                  turned / 2.0, expected, worst * 180 / PI);
    th_assert_near(worst, 0, 8 * PI / 180, 0);
    th_assert_near(turned / 2.0, expected, 0, 0.05);
    th_world_destroy(w);
}

/* Rotation between two unit quaternions' frames, measured on the body axes: angle of q. */
static void assert_rotation(tb_quat q, double angle, tb_vec3 axis)
{
    th_assert_near(th_quat_length(q), 1.0, 1e-5, 0);
    th_assert_near(th_quat_angle(q), angle, 1e-5, 0);
    /* vector part parallel to +axis (sign: q and -q are the same rotation) */
    double s = q.w < 0 ? -1 : 1, half = sin(angle / 2);
    th_assert_near(s * q.x, axis.x * half, 1e-5, 0);
    th_assert_near(s * q.y, axis.y * half, 1e-5, 0);
    th_assert_near(s * q.z, axis.z * half, 1e-5, 0);
}

/* (c) A spin faster than max_rotation_per_step (default pi/4) turns the body by exactly the
 * limit per step; the stored angular velocity is kept. A slow body beside it is not
 * clamped. A world with a custom limit uses that limit. */
static void test_spin_clamp(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    th_assert_near(wd.max_rotation_per_step, PI / 4, 1e-6, 0);
    tb_world* w = th_world_create(&wd);
    tb_shape_id s = th_sphere(w, 0.5f);
    tb_body_def d = th_dynamic_def(s, th_v3(0, 0, 0));
    d.angular_velocity = th_v3(0, 0, 100); /* 100/60 = 1.67 rad per step > pi/4 */
    tb_body_id fast = th_body(w, &d);
    d.position = th_v3(5, 0, 0);
    d.angular_velocity = th_v3(0, 1, 0); /* 0.0167 rad per step: unclamped */
    tb_body_id slow = th_body(w, &d);

    th_assert_ok(tb_world_step(w, DT));
    tb_quat q;
    th_read_pose(w, fast, NULL, &q);
    assert_rotation(q, PI / 4, th_v3(0, 0, 1));
    th_read_pose(w, slow, NULL, &q);
    assert_rotation(q, 1.0 * DT, th_v3(0, 1, 0));

    th_assert_ok(tb_world_step_n(w, DT, 2));
    th_read_pose(w, fast, NULL, &q);
    assert_rotation(q, 3 * PI / 4, th_v3(0, 0, 1));
    tb_vec3 lv, av;
    th_assert_ok(tb_body_get_velocity(w, fast, &lv, &av));
    th_assert_vec3_near(av, th_v3(0, 0, 100), 0, 1e-6);
    th_world_destroy(w);

    wd.max_rotation_per_step = 0.1f;
    w = th_world_create(&wd);
    s = th_sphere(w, 0.5f);
    d = th_dynamic_def(s, th_v3(0, 0, 0));
    d.angular_velocity = th_v3(-30, 0, 0); /* 0.5 rad per step > 0.1 */
    fast = th_body(w, &d);
    th_assert_ok(tb_world_step(w, DT));
    th_read_pose(w, fast, NULL, &q);
    assert_rotation(q, 0.1, th_v3(-1, 0, 0));
    th_world_destroy(w);
}

/* (d) Static bodies never move, whatever velocity they were given and with gravity on. */
static void test_static_never_moves(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    th_rng rng = th_rng_seed(11);
    tb_shape_id s = th_sphere(w, 1.0f), b = th_box(w, th_v3(1, 2, 3));
    enum { N = 4 };
    tb_body_id ids[N];
    for (int i = 0; i < N; i++) {
        tb_body_def d = th_static_def(i % 2 ? b : s, th_v3(1.0f + i, 2, 3));
        d.rotation = th_rng_quat(&rng);
        d.linear_velocity = th_v3(5, -1, 2);
        d.angular_velocity = th_v3(0, 3, 1);
        ids[i] = th_body(w, &d);
    }
    tb_vec3 p0[N], p1[N];
    tb_quat q0[N], q1[N];
    th_assert_ok(tb_world_read_transforms(w, ids, N, p0, q0));
    th_assert_ok(tb_world_step_n(w, DT, 30));
    th_assert_ok(tb_body_apply_impulse(w, ids[0], th_v3(100, 100, 100), th_v3(1, 3, 3)));
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_read_transforms(w, ids, N, p1, q1));
    /* bit for bit: nothing may even be re-normalised */
    assert_memory_equal(p0, p1, sizeof p0);
    assert_memory_equal(q0, q1, sizeof q0);
    float m = -1;
    tb_vec3 inertia;
    th_assert_ok(tb_body_get_mass(w, ids[0], &m, &inertia));
    assert_true(m == 0.0f); /* "0 for static" */
    tb_body_type t;
    th_assert_ok(tb_body_get_type(w, ids[1], &t));
    assert_int_equal(t, TB_BODY_STATIC);
    th_world_destroy(w);
}

/* (e) Damping: v = v / (1 + dt c) each step, before the substeps add gravity; the same
 * for angular velocity with its own rate (a sphere, so no gyroscopic coupling). */
static void test_damping(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    const tb_vec3 g = tb_world_get_gravity(w);
    tb_shape_id s = th_sphere(w, 0.5f);
    tb_body_def d = th_dynamic_def(s, th_v3(0, 50, 0));
    d.linear_velocity = th_v3(3, 1, -2);
    d.angular_velocity = th_v3(0, 0, 4);
    d.linear_damping = 2.0f;
    d.angular_damping = 3.0f;
    tb_body_id id = th_body(w, &d);
    ref_body ref = ref_make(d.position, d.linear_velocity);

    /* One step: damping-before-gravity differs from damping-after by 5 mm/s in y. */
    th_assert_ok(tb_world_step(w, DT));
    ref_step(&ref, g, 1, 2.0, 1);
    assert_matches_ref(w, id, &ref, 1e-5, 1e-5);
    tb_vec3 lv, av;
    th_assert_ok(tb_body_get_velocity(w, id, &lv, &av));
    th_assert_near(av.z, 4.0 / (1.0 + DT * 3.0), 0, 1e-5);

    th_assert_ok(tb_world_step_n(w, DT, 59));
    ref_step(&ref, g, 1, 2.0, 59);
    assert_matches_ref(w, id, &ref, 1e-3, 1e-4);
    th_assert_ok(tb_body_get_velocity(w, id, &lv, &av));
    th_assert_near(av.z, 4.0 / pow(1.0 + DT * 3.0, 60), 0, 1e-4);
    th_assert_near(av.x, 0, 1e-7, 0);
    th_assert_near(av.y, 0, 1e-7, 0);
    th_world_destroy(w);
}

static tb_vec3 cross3(tb_vec3 a, tb_vec3 b)
{
    return th_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static tb_vec3 sub3(tb_vec3 a, tb_vec3 b) { return th_v3(a.x - b.x, a.y - b.y, a.z - b.z); }

/* (f) An impulse J at world point p changes v by J/m and omega by I^-1 (r x J), r = p - x.
 * Identity rotation, so the world inertia is the principal one. Checked on a sphere with
 * the inertia from its shape and on a box with explicit, different moments. */
static void test_apply_impulse(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&wd);
    tb_shape_id s = th_sphere(w, 0.5f), b = th_box(w, th_v3(1, 1, 1));
    tb_body_def d = th_dynamic_def(s, th_v3(1, 2, 3));
    d.mass = 2.0f; /* inertia from the shape: 2/5 m r^2 = 0.2 */
    d.linear_velocity = th_v3(0.5f, 0, 0);
    tb_body_id sph = th_body(w, &d);
    d = th_dynamic_def(b, th_v3(-4, 0, 1));
    d.mass = 3.0f;
    d.inertia = th_v3(1, 2, 4);
    tb_body_id box = th_body(w, &d);

    float m;
    tb_vec3 inertia;
    th_assert_ok(tb_body_get_mass(w, sph, &m, &inertia));
    th_assert_near(m, 2.0, 0, 1e-6);
    th_assert_vec3_near(inertia, th_v3(0.2f, 0.2f, 0.2f), 0, 1e-5);

    /* Step once first so the bodies live on the GPU: the impulse must reach them there. */
    th_assert_ok(tb_world_step(w, DT));
    const tb_vec3 J = th_v3(1, 2, -0.5f);
    tb_vec3 x, v, av;
    th_read_pose(w, sph, &x, NULL);
    tb_vec3 p = th_v3(x.x + 0.3f, x.y - 0.2f, x.z + 0.4f);
    th_assert_ok(tb_body_apply_impulse(w, sph, J, p));
    th_assert_ok(tb_body_get_velocity(w, sph, &v, &av));
    th_assert_vec3_near(v, th_v3(0.5f + J.x / 2, J.y / 2, J.z / 2), 1e-6, 1e-5);
    tb_vec3 L = cross3(sub3(p, x), J);
    th_assert_vec3_near(av, th_v3(L.x / 0.2f, L.y / 0.2f, L.z / 0.2f), 1e-5, 1e-4);

    th_read_pose(w, box, &x, NULL);
    p = th_v3(x.x + 0.5f, x.y + 0.7f, x.z - 0.9f);
    th_assert_ok(tb_body_apply_impulse(w, box, J, p));
    th_assert_ok(tb_body_get_velocity(w, box, &v, &av));
    th_assert_vec3_near(v, th_v3(J.x / 3, J.y / 3, J.z / 3), 1e-6, 1e-5);
    L = cross3(sub3(p, x), J);
    th_assert_vec3_near(av, th_v3(L.x / 1, L.y / 2, L.z / 4), 1e-5, 1e-4);

    /* The next step moves the sphere with the new velocity. */
    tb_vec3 x1;
    th_read_pose(w, sph, &x, NULL);
    th_assert_ok(tb_world_step(w, DT));
    th_read_pose(w, sph, &x1, NULL);
    th_assert_vec3_near(x1, th_v3(x.x + (0.5f + J.x / 2) * DT, x.y + J.y / 2 * DT,
                                  x.z + J.z / 2 * DT), 1e-6, 1e-6);
    th_world_destroy(w);
}

/* Mass and inertia from shape and density (default 1000 kg/m^3), and inertia scaled to a
 * given mass. */
static void test_mass_from_shape(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_shape_id s = th_sphere(w, 0.5f), b = th_box(w, th_v3(0.5f, 1, 2));
    tb_body_def d = th_dynamic_def(s, th_v3(0, 0, 0));
    tb_body_id sph = th_body(w, &d);
    d.shape = b;
    tb_body_id box = th_body(w, &d);
    d.mass = 6.0f;
    tb_body_id box6 = th_body(w, &d);
    float m;
    tb_vec3 I;
    th_assert_ok(tb_body_get_mass(w, sph, &m, &I));
    double ms = 4.0 / 3.0 * PI * 0.125 * 1000.0;
    th_assert_near(m, ms, 0, 1e-5);
    th_assert_vec3_near(I, th_v3((float)(0.4 * ms * 0.25), (float)(0.4 * ms * 0.25),
                                 (float)(0.4 * ms * 0.25)), 0, 1e-5);
    th_assert_ok(tb_body_get_mass(w, box, &m, &I));
    th_assert_near(m, 8 * 0.5 * 1 * 2 * 1000.0, 0, 1e-6);
    th_assert_vec3_near(I, th_v3(8000.f / 3 * 5, 8000.f / 3 * 4.25f, 8000.f / 3 * 1.25f), 0, 1e-5);
    th_assert_ok(tb_body_get_mass(w, box6, &m, &I));
    th_assert_near(m, 6.0, 0, 1e-7);
    th_assert_vec3_near(I, th_v3(2 * 5.0f, 2 * 4.25f, 2 * 1.25f), 0, 1e-5);
    th_world_destroy(w);
}

/* (g) gravity_scale multiplies gravity per body (0: weightless); tb_world_set_gravity is
 * used from the next step on. */
static void test_gravity_scale_and_set_gravity(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_vec3 g = tb_world_get_gravity(w);
    tb_shape_id s = th_sphere(w, 0.25f);
    const float scales[3] = { 0.0f, 1.0f, 0.5f };
    tb_body_id ids[3];
    ref_body ref[3];
    for (int i = 0; i < 3; i++) {
        tb_body_def d = th_dynamic_def(s, th_v3(2.0f * i, 0, 0));
        d.gravity_scale = scales[i];
        ids[i] = th_body(w, &d);
        ref[i] = ref_make(d.position, d.linear_velocity);
    }
    th_assert_ok(tb_world_step_n(w, DT, 30));
    for (int i = 0; i < 3; i++) {
        ref_step(&ref[i], g, scales[i], 0, 30);
        assert_matches_ref(w, ids[i], &ref[i], 1e-4, 1e-5);
    }
    tb_vec3 p, v, av;
    th_read_pose(w, ids[0], &p, NULL);
    th_assert_vec3_near(p, th_v3(0, 0, 0), 0, 0); /* exactly still */

    const tb_vec3 g2 = th_v3(2, 0, -1);
    th_assert_ok(tb_world_set_gravity(w, g2));
    g = tb_world_get_gravity(w);
    th_assert_vec3_near(g, g2, 0, 0);
    th_assert_ok(tb_world_step_n(w, DT, 10));
    for (int i = 0; i < 3; i++) {
        ref_step(&ref[i], g2, scales[i], 0, 10);
        assert_matches_ref(w, ids[i], &ref[i], 1e-4, 1e-5);
    }
    th_assert_ok(tb_body_get_velocity(w, ids[0], &v, &av));
    th_assert_vec3_near(v, th_v3(0, 0, 0), 0, 0);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_fall),
        cmocka_unit_test(test_principal_spin),
        cmocka_unit_test(test_torque_free_spin),
        cmocka_unit_test(test_intermediate_axis_flip),
        cmocka_unit_test(test_spinning_top_precesses),
        cmocka_unit_test(test_spin_clamp),
        cmocka_unit_test(test_static_never_moves),
        cmocka_unit_test(test_damping),
        cmocka_unit_test(test_apply_impulse),
        cmocka_unit_test(test_mass_from_shape),
        cmocka_unit_test(test_gravity_scale_and_set_gravity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
