/* Joints on the GPU (lavapipe, validation on): a pendulum against its analytic period and
 * energy (and let go level, its swing), a weld, a chain with a heavy end, a hinge's limit
 * and motor, a slider, breaking, collide_connected, distance ropes and springs, repeatability, and the
 * API's refusals. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define PI 3.14159265358979323846
#define G 9.81

/* A ball of radius 0.1 m and `mass` kg at `at`, hung from a static post at `pivot` by a
 * ball joint there: the joint's def, which the caller makes (th_joint) once it is set. */
static tb_joint_def ball_on_post(tb_world* w, tb_vec3 pivot, tb_vec3 at, float mass,
                                 tb_body_id* bob)
{
    tb_body_id top = th_post(w, pivot);
    tb_body_def bd = th_dynamic_def(th_sphere(w, 0.1f), at);
    bd.mass = mass;
    *bob = th_body(w, &bd);
    return th_joint_def_at(w, TB_JOINT_BALL, top, *bob, pivot, th_v3(0, 0, 1));
}

/* A ball of radius r and mass m hung by a ball joint L below a post, pulled aside by
 * theta0 about z, let go: over ten periods its swing's period matches the physical
 * pendulum's (with the ball's own inertia, and the amplitude's correction) within 1 %, and
 * its energy stays within 2 % of the swing's: at each turning point, where its energy is
 * all potential, the ball rises as high as it began within 2 % of its height above the
 * bottom. */
static void test_pendulum(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    const double L = 1.0, r = 0.1, m = 1.0, theta0 = 0.1;   /* r: ball_on_post's ball */
    tb_body_id bob;
    tb_joint_def jd = ball_on_post(w, th_v3(0, 0, 0),
                                   th_v3((float)(L * sin(theta0)), (float)(-L * cos(theta0)), 0),
                                   (float)m, &bob);
    th_joint(w, &jd);
    double inertia = m * L * L + 0.4 * m * r * r;
    double period = 2 * PI * sqrt(inertia / (m * G * L)) * (1 + theta0 * theta0 / 16);
    double rise = L * (1 - cos(theta0));
    int steps = (int)(10.5 * period / DT);
    double x0 = L * sin(theta0), last_x = x0, last_dx = -1, first_cross = -1, last_cross = -1;
    double worst = 0, last_y = -L * cos(theta0);
    int crossings = 0, turns = 0;
    for (int s = 1; s <= steps; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 p;
        th_read_pose(w, bob, &p, NULL);
        if ((last_x > 0) != (p.x > 0)) {
            double t = (s - 1 + last_x / (last_x - p.x)) * DT;
            if (first_cross < 0) first_cross = t;
            last_cross = t;
            crossings++;
        }
        double dx = p.x - last_x;
        if ((dx > 0) != (last_dx > 0)) {   /* turned at the step before */
            double drift = fabs((last_y + L) / rise - 1);
            if (drift > worst) worst = drift;
            turns++;
        }
        last_dx = dx;
        last_x = p.x;
        last_y = p.y;
    }
    double measured = 2 * (last_cross - first_cross) / (crossings - 1);
    print_message("  pendulum: period %.4f s (analytic %.4f), %d crossings, %d turns, the swing's "
                  "energy at the turns within %.2f %% of its start\n", measured, period,
                  crossings, turns, 100 * worst);
    assert_true(crossings >= 20 && turns >= 20);
    th_assert_near(measured, period, 0, 0.01);
    assert_true(worst < 0.02);
    th_world_destroy(w);
}

/* A 1 m pendulum let go level swings back up within 1 cm of its start at each of its first
 * four turns: its rod's tension at the bottom, three times the bob's weight, does not stop
 * its prediction (block/joint_start; a bound of twice the weight had it lose its swing down
 * to 60 degrees, turning 24 cm low the first time). */
static void test_wide_swing(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id bob;
    tb_joint_def jd = ball_on_post(w, th_v3(0, 3, 0), th_v3(1, 3, 0), 2, &bob);
    th_joint(w, &jd);
    double y[3] = { 3, 3, 3 }, turns[4];
    int found = 0;
    for (int s = 0; s < 600 && found < 4; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 p;
        th_read_pose(w, bob, &p, NULL);
        y[0] = y[1];
        y[1] = y[2];
        y[2] = p.y;
        if (s >= 2 && y[1] >= y[0] && y[1] > y[2]) turns[found++] = y[1];
    }
    assert_int_equal(found, 4);
    print_message("  pendulum let go level: turns at %.4f %.4f %.4f %.4f m (started at 3)\n",
                  turns[0], turns[1], turns[2], turns[3]);
    for (int i = 0; i < 4; i++) assert_true(turns[i] > 2.99 && turns[i] < 3.0005);
    th_world_destroy(w);
}

/* Angle of q about z (q a turn about z). */
static double angle_about_z(tb_quat q)
{
    return 2 * atan2(q.z, q.w);
}

/* b's position in a's frame, and the angle between their rotations. */
static void relative_pose(tb_world* w, tb_body_id a, tb_body_id b, double out[3], double* angle)
{
    tb_vec3 pa, pb;
    tb_quat qa, qb;
    th_read_pose(w, a, &pa, &qa);
    th_read_pose(w, b, &pb, &qb);
    tb_quat inv = { -qa.x, -qa.y, -qa.z, qa.w };
    double d[3] = { pb.x - pa.x, pb.y - pa.y, pb.z - pa.z };
    th_quat_rotate(inv, d, out);
    /* inv * qb */
    tb_quat rel = { inv.w * qb.x + inv.x * qb.w + inv.y * qb.z - inv.z * qb.y,
                    inv.w * qb.y - inv.x * qb.z + inv.y * qb.w + inv.z * qb.x,
                    inv.w * qb.z + inv.x * qb.y - inv.y * qb.x + inv.z * qb.w,
                    inv.w * qb.w - inv.x * qb.x - inv.y * qb.y - inv.z * qb.z };
    *angle = th_quat_angle(rel);
}

/* A box hung from a post by its corner swings, and a second box welded to its side swings
 * with it: over 1,000 steps b stays where it was in a's frame within 1 mm and 0.1 degree. */
static void test_weld(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_shape_id box = th_box(w, th_v3(0.25f, 0.25f, 0.25f));
    tb_body_def da = th_dynamic_def(box, th_v3(0.25f, 1.75f, 0.25f));
    tb_body_def db = th_dynamic_def(box, th_v3(0.75f, 1.75f, 0.25f));
    tb_body_id a = th_body(w, &da), b = th_body(w, &db);
    tb_joint_def hang = th_joint_def_at(w, TB_JOINT_BALL, top, a, th_v3(0, 2, 0), th_v3(1, 0, 0));
    tb_joint_def weld = th_joint_def_at(w, TB_JOINT_FIXED, a, b, th_v3(0.5f, 1.75f, 0.25f),
                                     th_v3(1, 0, 0));
    th_joint(w, &hang);
    th_joint(w, &weld);
    double start[3], angle, worst = 0, worst_angle = 0;
    relative_pose(w, a, b, start, &angle);
    for (int s = 0; s < 1000; s++) {
        th_assert_ok(tb_world_step(w, DT));
        if (s % 10) continue;
        double now[3];
        relative_pose(w, a, b, now, &angle);
        double d = sqrt((now[0] - start[0]) * (now[0] - start[0]) +
                        (now[1] - start[1]) * (now[1] - start[1]) +
                        (now[2] - start[2]) * (now[2] - start[2]));
        if (d > worst) worst = d;
        if (angle > worst_angle) worst_angle = angle;
    }
    tb_vec3 pa;
    th_read_pose(w, a, &pa, NULL);
    print_message("  weld: drift %.3f mm, %.4f degrees; a at (%.3f, %.3f, %.3f)\n", 1000 * worst,
                  worst_angle * 180 / PI, pa.x, pa.y, pa.z);
    assert_true(fabs(pa.x - 0.25f) + fabs(pa.z - 0.25f) > 0.1f);   /* it swung */
    assert_true(worst < 1e-3);
    assert_true(worst_angle < 0.1 * PI / 180);
    th_world_destroy(w);
}

/* A chain of `links` boxes 0.1 m long joined by ball joints at their ends, hung from a post
 * and let go level, its last link `heavy` times the others': the largest gap that opens
 * between joined anchors over `steps` steps, m, with `sweeps` a step (0: the default).
 * Poses to `out` (2 * links) if not NULL. */
static double swing_chain(int links, float heavy, int steps, uint32_t sweeps, float* out)
{
    tb_world* w = th_world_create(NULL);
    if (sweeps) th_assert_ok(tb_world_set_solver(w, TB_SOLVER_BLOCK, sweeps));
    tb_body_id prev = th_post(w, th_v3(0, 3, 0));
    tb_shape_id link = th_box(w, th_v3(0.05f, 0.02f, 0.02f));
    tb_body_id* bodies = malloc((size_t)links * sizeof *bodies);
    tb_joint_id* ids = malloc((size_t)links * sizeof *ids);
    for (int i = 0; i < links; i++) {
        tb_body_def d = th_dynamic_def(link, th_v3(0.05f + 0.1f * (float)i, 3, 0));
        d.mass = i == links - 1 ? heavy : 1.0f;
        bodies[i] = th_body(w, &d);
        tb_joint_def j = th_joint_def_at(w, TB_JOINT_BALL, prev, bodies[i],
                                      th_v3(0.1f * (float)i, 3, 0), th_v3(0, 0, 1));
        ids[i] = th_joint(w, &j);
        prev = bodies[i];
    }
    double worst = 0;
    for (int s = 0; s < steps; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 a[64], b[64];
        th_assert_ok(tb_joint_read_anchors(w, ids, (uint32_t)links, a, b));
        for (int i = 0; i < links; i++) {
            double dx = a[i].x - b[i].x, dy = a[i].y - b[i].y, dz = a[i].z - b[i].z;
            double gap = sqrt(dx * dx + dy * dy + dz * dz);
            if (gap > worst) worst = gap;
        }
    }
    for (int i = 0; out && i < links; i++) {
        tb_vec3 p;
        tb_quat q;
        th_read_pose(w, bodies[i], &p, &q);
        memcpy(out + 7 * i, &p, sizeof p);
        memcpy(out + 7 * i + 3, &q, sizeof q);
    }
    free(bodies);
    free(ids);
    th_world_destroy(w);
    return worst;
}

/* A 20-link chain whose last link is 100 times heavier falls from level and swings. At the
 * default 30 sweeps a step (15 of them holding the joints, tb_block_settings.joint_holds) no
 * joint opens by more than 1.5 % of a link (1.5 mm), so the chain keeps its length within
 * 1.5 %; at 40 sweeps (25 closing the joints) within 1 % (1 mm). */
static void test_heavy_chain(void** state)
{
    (void)state;
    double gap = swing_chain(20, 100.0f, 240, 0, NULL);
    print_message("  chain of 20, end 100 times heavier: largest gap %.3f mm\n", 1000 * gap);
    assert_true(gap < 1.5e-3);
    double finer = swing_chain(20, 100.0f, 240, 40, NULL);
    print_message("  the same at 40 sweeps a step: largest gap %.3f mm\n", 1000 * finer);
    assert_true(finer < 1e-3);
}

/* Ten links hung straight down from a post by ball joints stay still, and each joint
 * holds the weight of the links below it (within 1 %). (Ten read 335 N at the hook
 * instead of 98 while joints carried a contact's share of their multipliers.) */
#define HANGING_LINKS 10
static void test_hanging_chain(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id prev = th_post(w, th_v3(0, 3, 0));
    tb_shape_id link = th_box(w, th_v3(0.02f, 0.05f, 0.02f));
    tb_joint_id ids[HANGING_LINKS];
    tb_body_id last = prev;
    for (int i = 0; i < HANGING_LINKS; i++) {
        tb_body_def d = th_dynamic_def(link, th_v3(0, 2.95f - 0.1f * (float)i, 0));
        d.mass = 1;
        last = th_body(w, &d);
        tb_joint_def j = th_joint_def_at(w, TB_JOINT_BALL, prev, last,
                                      th_v3(0, 3 - 0.1f * (float)i, 0), th_v3(0, 0, 1));
        ids[i] = th_joint(w, &j);
        prev = last;
    }
    for (int s = 0; s < 200; s++) th_assert_ok(tb_world_step(w, DT));
    tb_vec3 f[HANGING_LINKS], p;
    th_assert_ok(tb_joint_read_forces(w, ids, HANGING_LINKS, f, NULL, NULL));
    th_read_pose(w, last, &p, NULL);
    print_message("  hanging chain of %d: forces %.3f %.3f ... %.3f %.3f N, end at (%.5f, %.5f)\n",
                  HANGING_LINKS, f[0].y, f[1].y, f[HANGING_LINKS - 2].y, f[HANGING_LINKS - 1].y,
                  p.x, p.y);
    for (int i = 0; i < HANGING_LINKS; i++) th_assert_near(f[i].y, (HANGING_LINKS - i) * G, 0, 0.01);
    th_assert_near(p.x, 0, 1e-3, 0);
    th_assert_near(p.y, 3 - 0.1 * HANGING_LINKS + 0.05, 1e-3, 0);
    th_world_destroy(w);
}

/* The same joint scene twice ends bit for bit the same. */
static void test_repeatable(void** state)
{
    (void)state;
    float first[7 * 8], second[7 * 8];
    swing_chain(8, 10.0f, 60, 0, first);
    swing_chain(8, 10.0f, 60, 0, second);
    assert_memory_equal(first, second, sizeof first);
}

/* A rod hinged at one end about z, held level at first, falls until its limit: it stops
 * at the lower limit within a degree (and never passes it by more). */
static void test_hinge_limit(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.05f, 0.05f)), th_v3(0.5f, 2, 0));
    tb_body_id rod = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_HINGE, top, rod, th_v3(0, 2, 0), th_v3(0, 0, 1));
    j.enable_limit = 1;
    j.lower = -0.5f;
    j.upper = 0.5f;
    th_joint(w, &j);
    double lowest = 0, angle = 0;
    for (int s = 0; s < 150; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_quat q;
        th_read_pose(w, rod, NULL, &q);
        angle = angle_about_z(q);
        if (angle < lowest) lowest = angle;
    }
    print_message("  hinge limit -0.5 rad: ends at %.4f rad, lowest %.4f\n", angle, lowest);
    assert_true(fabs(angle + 0.5) < PI / 180);
    assert_true(lowest > -0.5 - PI / 180);
    th_world_destroy(w);
}

/* The same rod on a motor of 3 rad/s with 50 N m to spare turns round and round against
 * gravity's torque (up to 4.9 N m) at the motor's speed within 2 %. */
static void test_hinge_motor(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.05f, 0.05f)), th_v3(0.5f, 2, 0));
    d.mass = 1;
    tb_body_id rod = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_HINGE, top, rod, th_v3(0, 2, 0), th_v3(0, 0, 1));
    j.enable_motor = 1;
    j.motor_speed = 3;
    j.max_motor_force = 50;
    tb_joint_id id = th_joint(w, &j);
    double worst = 0;
    for (int s = 0; s < 180; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 v, av;
        th_assert_ok(tb_body_get_velocity(w, rod, &v, &av));
        if (s >= 10 && fabs(av.z / 3 - 1) > worst) worst = fabs(av.z / 3 - 1);
    }
    print_message("  hinge motor 3 rad/s: speed within %.2f %%\n", 100 * worst);
    assert_true(worst < 0.02);
    /* A weak motor cannot hold the rod up: braking it at 0.5 N m against gravity's 4.9, it
     * swings down and settles hanging within 10 s (8 s in an exact integration of the rod;
     * at 3 s it still swings, its centre at y 1.76). */
    th_assert_ok(tb_joint_set_motor(w, id, 1, 0, 0.5f));
    for (int s = 0; s < 600; s++) th_assert_ok(tb_world_step(w, DT));
    tb_vec3 p;
    th_read_pose(w, rod, &p, NULL);
    print_message("  weak motor: rod centre at y %.3f\n", p.y);
    assert_true(p.y < 1.6f);
    th_world_destroy(w);
}

/* A box on a slider whose axis leans 45 degrees slides down along it under gravity: its
 * anchor stays on the axis line within 1 mm and it does not turn (0.1 degree). */
static void test_slider(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 5, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.2f, 0.2f, 0.2f)), th_v3(0, 5, 0));
    tb_body_id box = th_body(w, &d);
    const float c = 0.70710678f;
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_SLIDER, top, box, th_v3(0, 5, 0), th_v3(c, -c, 0));
    th_joint(w, &j);
    double worst = 0, worst_angle = 0;
    tb_vec3 p = { 0, 5, 0 };
    for (int s = 0; s < 120; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_quat q;
        th_read_pose(w, box, &p, &q);
        double along = p.x * c - (p.y - 5) * c;
        double off = sqrt(pow(p.x - along * c, 2) + pow(p.y - 5 + along * c, 2) + p.z * p.z);
        if (off > worst) worst = off;
        if (th_quat_angle(q) > worst_angle) worst_angle = th_quat_angle(q);
    }
    double t = 120 * DT, expected = 0.5 * G * c * t * t;
    double along = p.x * c - (p.y - 5) * c;
    print_message("  slider: slid %.3f m (free slide %.3f), off the axis %.3f mm, turned %.4f "
                  "degrees\n", along, expected, 1000 * worst, worst_angle * 180 / PI);
    assert_true(worst < 1e-3);
    assert_true(worst_angle < 0.1 * PI / 180);
    th_assert_near(along, expected, 0, 0.03);
    th_world_destroy(w);
}

/* A 2 kg weight on a ball joint holds (force about m g up) while its break force is above
 * its weight, and breaks and falls once it is set below: the joint reports it. */
static void test_break(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id weight;
    tb_joint_def strong = ball_on_post(w, th_v3(0, 2, 0), th_v3(0, 1.5f, 0), 2, &weight);
    strong.break_force = 40;
    tb_joint_def weak = strong;
    weak.break_force = 10;
    tb_joint_id id = th_joint(w, &strong);
    for (int s = 0; s < 30; s++) th_assert_ok(tb_world_step(w, DT));
    tb_vec3 f, t;
    int32_t broken;
    th_assert_ok(tb_joint_read_forces(w, &id, 1, &f, &t, &broken));
    print_message("  holding: force (%.3f, %.3f, %.3f) N, broken %d\n", f.x, f.y, f.z, broken);
    assert_int_equal(broken, 0);
    th_assert_near(f.y, 2 * G, 0, 0.01);
    th_assert_ok(tb_joint_destroy(w, id));
    id = th_joint(w, &weak);
    for (int s = 0; s < 30; s++) th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_joint_read_forces(w, &id, 1, &f, &t, &broken));
    tb_vec3 p;
    th_read_pose(w, weight, &p, NULL);
    print_message("  weak: broken %d, weight at y %.3f, force %.3f N\n", broken, p.y, f.y);
    assert_int_equal(broken, 1);
    assert_true(p.y < 1.0f);
    assert_true(f.x == 0 && f.y == 0 && f.z == 0);   /* a broken joint holds nothing */
    th_world_destroy(w);
}

/* Two boxes that overlap, joined: no contact between them unless collide_connected. */
static void test_collide_connected(void** state)
{
    (void)state;
    for (int collide = 0; collide < 2; collide++) {
        tb_world* w = th_world_create(NULL);
        tb_vec3 g = { 0, 0, 0 };
        th_assert_ok(tb_world_set_gravity(w, g));
        tb_shape_id box = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
        tb_body_def da = th_dynamic_def(box, th_v3(0, 0, 0));
        tb_body_def db = th_dynamic_def(box, th_v3(0.8f, 0, 0));
        tb_body_id a = th_body(w, &da), b = th_body(w, &db);
        tb_joint_def j = th_joint_def_at(w, TB_JOINT_FIXED, a, b, th_v3(0.4f, 0, 0), th_v3(1, 0, 0));
        j.collide_connected = collide;
        th_joint(w, &j);
        th_assert_ok(tb_world_step(w, DT));
        uint32_t count = 0;
        th_assert_ok(tb_world_read_contacts(w, NULL, 0, &count));
        print_message("  collide_connected %d: %u contact points\n", collide, count);
        assert_true(collide ? count > 0 : count == 0);
        th_world_destroy(w);
    }
}

/* Two boxes side by side on a static slab, hinged together without collide_connected,
 * under every broadphase: each keeps its own contact with the slab and rests on it, and
 * no contact joins the two boxes or a body to itself (a broadphase that cached the pair
 * the joint drops once left a body paired with itself, and the box fell through). */
static void test_jointed_on_ground(void** state)
{
    (void)state;
    const tb_broadphase kinds[] = { TB_BROADPHASE_GRID, TB_BROADPHASE_SAP, TB_BROADPHASE_LBVH,
                                    TB_BROADPHASE_ISAP };
    for (int k = 0; k < 4; k++) {
        tb_world_def def = tb_default_world_def();
        def.broadphase = kinds[k];
        tb_world* w = th_world_create(&def);
        tb_body_def slab = th_static_def(th_box(w, th_v3(3, 0.5f, 3)), th_v3(0, -0.5f, 0));
        th_body(w, &slab);
        tb_shape_id box = th_box(w, th_v3(0.25f, 0.1f, 0.25f));
        tb_body_def da = th_dynamic_def(box, th_v3(-0.25f, 0.1f, 0));
        tb_body_def db = th_dynamic_def(box, th_v3(0.25f, 0.1f, 0));
        tb_body_id a = th_body(w, &da), b = th_body(w, &db);
        tb_joint_def j = th_joint_def_at(w, TB_JOINT_HINGE, a, b, th_v3(0, 0.1f, 0), th_v3(0, 0, 1));
        th_joint(w, &j);
        for (int s = 0; s < 60; s++) th_assert_ok(tb_world_step(w, DT));
        tb_contact c[64];
        uint32_t n = 0;
        th_assert_ok(tb_world_read_contacts(w, c, 64, &n));
        tb_vec3 pa, pb;
        th_read_pose(w, a, &pa, NULL);
        th_read_pose(w, b, &pb, NULL);
        print_message("  %s: %u contact points, boxes at y %.4f and %.4f\n",
                      tb_broadphase_name(kinds[k]), n, pa.y, pb.y);
        for (uint32_t i = 0; i < n && i < 64; i++) {
            assert_true(c[i].a.index1 != c[i].b.index1);
            int ab = (c[i].a.index1 == a.index1 && c[i].b.index1 == b.index1) ||
                     (c[i].a.index1 == b.index1 && c[i].b.index1 == a.index1);
            assert_false(ab);
        }
        assert_int_equal(n, 8);
        th_assert_near(pa.y, 0.1, 2e-3, 0);
        th_assert_near(pb.y, 0.1, 2e-3, 0);
        th_world_destroy(w);
    }
}

/* A weight on a distance joint made a spring of 2 Hz settles where the spring holds its
 * weight (k = m (2 pi f)^2), within 2 %; as a rope (limit 0 to 1 m) it hangs at 1 m. */
static void test_distance(void** state)
{
    (void)state;
    for (int spring = 0; spring < 2; spring++) {
        tb_world* w = th_world_create(NULL);
        tb_body_id top = th_post(w, th_v3(0, 3, 0));
        tb_body_def d = th_dynamic_def(th_sphere(w, 0.1f), th_v3(0, 2, 0));
        d.mass = 1;
        d.linear_damping = 2;
        tb_body_id weight = th_body(w, &d);
        tb_joint_def j = tb_default_joint_def();
        j.kind = TB_JOINT_DISTANCE;
        j.body_a = top;
        j.body_b = weight;
        j.length = 1;
        j.enable_spring = spring;
        j.spring_hertz = 2;
        j.spring_damping_ratio = 0.5f;
        j.enable_limit = !spring;
        j.lower = 0;
        j.upper = 1;
        th_joint(w, &j);
        for (int s = 0; s < 200; s++) th_assert_ok(tb_world_step(w, DT));
        tb_vec3 p;
        th_read_pose(w, weight, &p, NULL);
        double k = 1 * pow(2 * PI * 2, 2), want = 1 + (spring ? G / k : 0);
        print_message("  distance (%s): hangs %.4f m below (analytic %.4f)\n",
                      spring ? "spring" : "rope", 3 - p.y, want);
        th_assert_near(3 - p.y, want, spring ? 0 : 1e-3, spring ? 0.02 : 0);
        th_world_destroy(w);
    }
}

/* Bad input is refused with nothing changed; destroying a body destroys its joints; a
 * stale joint id is refused. */
static void test_bad_input(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_id other_static = th_post(w, th_v3(1, 2, 0));
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.1f), th_v3(0, 1, 0));
    tb_body_id bob = th_body(w, &d);
    tb_joint_def good = th_joint_def_at(w, TB_JOINT_HINGE, top, bob, th_v3(0, 2, 0), th_v3(0, 0, 1));
    tb_joint_id id;
    tb_joint_def bad = good;
    bad.body_b = top;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.body_b = other_static;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.anchor_a.x = NAN;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.enable_limit = 1;
    bad.lower = 0.5f;
    bad.upper = -0.5f;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.kind = (tb_joint_kind)42;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.kind = TB_JOINT_BALL;
    bad.enable_motor = 1;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = good;
    bad.frame_a = (tb_quat){ 0, 0, 0, 2 };
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = tb_default_joint_def();
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    tb_joint_def many[2] = { good, good };
    many[1].max_motor_force = -1;
    tb_joint_id ids[2];
    th_assert_result(tb_joint_create_many(w, many, 2, ids), TB_ERROR_INVALID_ARGUMENT);
    assert_int_equal(tb_world_joint_ids(w, NULL, 0), 0);
    /* Good ones, then the body goes and takes them along. */
    many[1] = good;
    th_assert_ok(tb_joint_create_many(w, many, 2, ids));
    assert_int_equal(tb_world_joint_ids(w, ids, 2), 2);
    th_assert_result(tb_joint_set_limit(w, ids[0], 1, 1, -1), TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_joint_set_limit(w, ids[0], 1, -1, 1));
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_body_destroy(w, bob));
    assert_false(tb_joint_is_valid(w, ids[0]));
    th_assert_result(tb_joint_destroy(w, ids[1]), TB_ERROR_STALE_ID);
    tb_vec3 f;
    th_assert_result(tb_joint_read_forces(w, ids, 1, &f, NULL, NULL), TB_ERROR_STALE_ID);
    assert_int_equal(tb_world_joint_ids(w, NULL, 0), 0);
    th_assert_ok(tb_world_step(w, DT));
    th_world_destroy(w);
    /* The soft step refuses joints, and a world with joints refuses the soft step. */
    tb_world* soft = th_world_create_ex(NULL, 1);
    th_assert_ok(tb_world_set_solver(soft, TB_SOLVER_SOFT_STEP, 0));
    top = th_post(soft, th_v3(0, 2, 0));
    tb_body_def sd = th_dynamic_def(th_sphere(soft, 0.1f), th_v3(0, 1, 0));
    bob = th_body(soft, &sd);
    good.body_a = top;
    good.body_b = bob;
    th_assert_result(tb_joint_create(soft, &good, &id), TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_world_set_solver(soft, TB_SOLVER_BLOCK, 0));
    th_assert_ok(tb_joint_create(soft, &good, &id));
    th_assert_result(tb_world_set_solver(soft, TB_SOLVER_SOFT_STEP, 0), TB_ERROR_INVALID_ARGUMENT);
    th_world_destroy(soft);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pendulum),
        cmocka_unit_test(test_wide_swing),
        cmocka_unit_test(test_weld),
        cmocka_unit_test(test_heavy_chain),
        cmocka_unit_test(test_hanging_chain),
        cmocka_unit_test(test_repeatable),
        cmocka_unit_test(test_hinge_limit),
        cmocka_unit_test(test_hinge_motor),
        cmocka_unit_test(test_slider),
        cmocka_unit_test(test_break),
        cmocka_unit_test(test_collide_connected),
        cmocka_unit_test(test_jointed_on_ground),
        cmocka_unit_test(test_distance),
        cmocka_unit_test(test_bad_input),
    };
    const char* only = getenv("TUMBLE_TEST_FILTER");
    if (only) cmocka_set_test_filter(only);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
