/* Cone-twist and 6-dof joints, the springs of hinges and sliders, and soft joints
 * (lavapipe, validation on): a cone holds its swing and a twist limit its twist, a 6-dof
 * joint set up as a limited hinge or slider stops where a limit says, a hinge's spring
 * swings at its frequency and servoes to a target, a slider's spring and a soft joint sag
 * as far as Hooke says, and the API refuses what these kinds do not take. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define PI 3.14159265358979323846
#define G 9.81
#define DEGREE (PI / 180)

/* World direction of a body's local axis `axis`. */
static void body_axis(tb_world* w, tb_body_id b, const double axis[3], double out[3])
{
    tb_quat q;
    th_read_pose(w, b, NULL, &q);
    th_quat_rotate(q, axis, out);
}

/* A 1 m rod (along its x) held level at a post by one end, on a cone-twist joint whose axis
 * is the rod's: it falls until its swing reaches the cone's 0.5 rad, and hangs there
 * (within a degree), its end on the post within 1 mm. */
static void test_cone_swing(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.05f, 0.05f)), th_v3(0.5f, 2, 0));
    tb_body_id rod = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_CONE_TWIST, top, rod, th_v3(0, 2, 0),
                                  th_v3(1, 0, 0));
    j.cone_angle = 0.5f;
    tb_joint_id id = th_joint(w, &j);
    double most = 0, swing = 0, gap = 0;
    const double x[3] = { 1, 0, 0 };
    for (int s = 0; s < 90; s++) {
        th_assert_ok(tb_world_step(w, DT));
        double along[3];
        body_axis(w, rod, x, along);
        swing = acos(fmin(1.0, along[0]));
        if (swing > most) most = swing;
        gap = fmax(gap, th_joint_gap(w, id));
    }
    print_message("  cone 0.5 rad: swing ends at %.4f rad (most %.4f), anchors %.3f mm apart at "
                  "most\n", swing, most, 1000 * gap);
    th_assert_near(swing, 0.5, DEGREE, 0);
    assert_true(most < 0.5 + DEGREE);
    assert_true(gap < 1e-3);
    th_world_destroy(w);
}

/* A rod hanging straight down on a cone-twist joint (axis down the rod, cone 0.3 rad, twist
 * limit +-0.2 rad) is spun about its length at 5 rad/s: the twist stops at the limit
 * (never past it by more than a degree) and the rod still hangs within its cone. */
static void test_cone_twist_limit(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.05f, 0.5f, 0.05f)), th_v3(0, 1.5f, 0));
    d.angular_velocity = th_v3(0, 5, 0);
    tb_body_id rod = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_CONE_TWIST, top, rod, th_v3(0, 2, 0),
                                  th_v3(0, -1, 0));
    j.cone_angle = 0.3f;
    j.enable_limit = 1;
    j.lower = -0.2f;
    j.upper = 0.2f;
    th_joint(w, &j);
    double most = 0, twist = 0, swing = 0;
    for (int s = 0; s < 60; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_quat q;
        th_read_pose(w, rod, NULL, &q);
        twist = 2 * atan2(q.y, q.w);   /* the turn about the rod's length (swing-twist) */
        if (fabs(twist) > most) most = fabs(twist);
        const double down[3] = { 0, -1, 0 };
        double along[3];
        th_quat_rotate(q, down, along);
        swing = acos(fmin(1.0, -along[1]));
    }
    print_message("  cone twist limit 0.2 rad: twist ends at %.4f, most %.4f; swing %.4f\n",
                  twist, most, swing);
    assert_true(most < 0.2 + DEGREE);
    th_assert_near(fabs(twist), 0.2, DEGREE, 0);
    assert_true(swing < 0.3 + DEGREE);
    th_world_destroy(w);
}

/* A 6-dof joint set as a hinge: offsets and the turns about x and y locked, the turn about
 * z limited to +-0.5 rad. A level rod falls to the lower limit (within a degree), turns
 * only about z, and its end stays on the post within 1 mm. */
static void test_six_dof_hinge(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.05f, 0.05f)), th_v3(0.5f, 2, 0));
    tb_body_id rod = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_SIX_DOF, top, rod, th_v3(0, 2, 0), th_v3(1, 0, 0));
    j.axes[5] = (tb_joint_axis){ TB_JOINT_AXIS_LIMITED, -0.5f, 0.5f };
    tb_joint_id id = th_joint(w, &j);
    double angle = 0, lowest = 0, off_plane = 0, gap = 0;
    for (int s = 0; s < 90; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_quat q;
        th_read_pose(w, rod, NULL, &q);
        angle = 2 * atan2(q.z, q.w);
        if (angle < lowest) lowest = angle;
        if (fabs(q.x) + fabs(q.y) > off_plane) off_plane = fabs(q.x) + fabs(q.y);
        gap = fmax(gap, th_joint_gap(w, id));
    }
    print_message("  6-dof as a hinge: ends at %.4f rad (lowest %.4f), off its plane %.5f, "
                  "anchors %.3f mm apart at most\n", angle, lowest, off_plane, 1000 * gap);
    th_assert_near(angle, -0.5, DEGREE, 0);
    assert_true(lowest > -0.5 - DEGREE);
    assert_true(off_plane < 1e-3);
    assert_true(gap < 1e-3);
    th_world_destroy(w);
}

/* A 6-dof joint set as a slider: x free within [-0.3, 0.3] m, the rest locked, its x axis
 * leaning down at 45 degrees. A box slides down it and stops at 0.3 m (within 1 mm), off
 * the axis by less than 1 mm and turned by less than 0.1 degree. */
static void test_six_dof_slider(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 5, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.2f, 0.2f, 0.2f)), th_v3(0, 5, 0));
    tb_body_id box = th_body(w, &d);
    const float c = 0.70710678f;
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_SIX_DOF, top, box, th_v3(0, 5, 0),
                                  th_v3(c, -c, 0));
    j.axes[0] = (tb_joint_axis){ TB_JOINT_AXIS_LIMITED, -0.3f, 0.3f };
    th_joint(w, &j);
    double worst = 0, worst_angle = 0, along = 0, most = 0;
    for (int s = 0; s < 60; s++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 p;
        tb_quat q;
        th_read_pose(w, box, &p, &q);
        along = p.x * c - (p.y - 5) * c;
        double off = sqrt(pow(p.x - along * c, 2) + pow(p.y - 5 + along * c, 2) + p.z * p.z);
        if (off > worst) worst = off;
        if (along > most) most = along;
        if (th_quat_angle(q) > worst_angle) worst_angle = th_quat_angle(q);
    }
    print_message("  6-dof as a slider: stops at %.4f m (most %.4f), off the axis %.3f mm, "
                  "turned %.4f degrees\n", along, most, 1000 * worst, worst_angle / DEGREE);
    th_assert_near(along, 0.3, 1e-3, 0);
    assert_true(most < 0.3 + 1e-3);
    assert_true(worst < 1e-3);
    assert_true(worst_angle < 0.1 * DEGREE);
    th_world_destroy(w);
}

/* Angle about z of body b (turned about z only). */
static double angle_about_z(tb_world* w, tb_body_id b)
{
    tb_quat q;
    th_read_pose(w, b, NULL, &q);
    return 2 * atan2(q.z, q.w);
}

/* A 1 kg cube hinged about z through its centre (gravity has no lever there) on a 1 Hz
 * undamped spring to 0.4 rad, let go at 0: it swings about 0.4 rad with a period of 1 s
 * (within 3 %); then, its spring moved to 1 rad and critically damped (a servo), it comes
 * to rest at 1 rad within a degree. */
static void test_hinge_spring(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.2f, 0.2f, 0.2f)), th_v3(0, 2, 0));
    d.mass = 1;
    tb_body_id cube = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_HINGE, top, cube, th_v3(0, 2, 0), th_v3(0, 0, 1));
    j.enable_spring = 1;
    j.spring_hertz = 1;
    j.spring_target = 0.4f;
    tb_joint_id id = th_joint(w, &j);
    double last = -0.4, first_cross = -1, last_cross = -1;
    int crossings = 0;
    for (int s = 1; s <= 150; s++) {
        th_assert_ok(tb_world_step(w, DT));
        double off = angle_about_z(w, cube) - 0.4;
        if ((last > 0) != (off > 0)) {
            double t = (s - 1 + last / (last - off)) * DT;
            if (first_cross < 0) first_cross = t;
            last_cross = t;
            crossings++;
        }
        last = off;
    }
    double period = 2 * (last_cross - first_cross) / (crossings - 1);
    th_assert_ok(tb_joint_set_spring(w, id, 1, 2, 1, 1.0f));
    for (int s = 0; s < 90; s++) th_assert_ok(tb_world_step(w, DT));
    double held = angle_about_z(w, cube);
    print_message("  hinge spring 1 Hz: period %.4f s over %d crossings; servo to 1 rad: at "
                  "%.4f\n", period, crossings, held);
    assert_true(crossings >= 4);
    th_assert_near(period, 1.0, 0, 0.03);
    th_assert_near(held, 1.0, DEGREE, 0);
    th_world_destroy(w);
}

/* A 2 kg box on a vertical slider with a critically damped 2 Hz spring to offset 0 sags
 * under its weight to g / (2 pi 2)^2 below (within 2 %) and rests there. */
static void test_slider_spring(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_id top = th_post(w, th_v3(0, 3, 0));
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.2f, 0.2f, 0.2f)), th_v3(0, 3, 0));
    d.mass = 2;
    tb_body_id box = th_body(w, &d);
    tb_joint_def j = th_joint_def_at(w, TB_JOINT_SLIDER, top, box, th_v3(0, 3, 0), th_v3(0, 1, 0));
    j.enable_spring = 1;
    j.spring_hertz = 2;
    j.spring_damping_ratio = 1;
    th_joint(w, &j);
    for (int s = 0; s < 60; s++) th_assert_ok(tb_world_step(w, DT));
    tb_vec3 p, v;
    th_read_pose(w, box, &p, NULL);
    th_assert_ok(tb_body_get_velocity(w, box, &v, NULL));
    double want = G / pow(2 * PI * 2, 2);
    print_message("  slider spring 2 Hz: sags %.4f m (Hooke %.4f), moving %.5f m/s\n",
                  3 - p.y, want, fabs(v.y));
    th_assert_near(3 - p.y, want, 0, 0.02);
    assert_true(fabs(v.y) < 1e-3);
    th_world_destroy(w);
}

/* A 2 kg box hung by its top from a post on a soft ball joint (2 Hz, critically damped)
 * sags below the post as a spring of that frequency on its mass would, g / (2 pi 2)^2
 * (within 2 %), and rests there; its weld twin on a soft fixed joint sags the same. */
static void test_soft_joint(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_joint_kind kinds[2] = { TB_JOINT_BALL, TB_JOINT_FIXED };
    tb_body_id boxes[2];
    for (int i = 0; i < 2; i++) {
        float x = 2.0f * (float)i;
        tb_body_id top = th_post(w, th_v3(x, 3, 0));
        tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.1f, 0.1f, 0.1f)), th_v3(x, 2.9f, 0));
        d.mass = 2;
        boxes[i] = th_body(w, &d);
        tb_joint_def j = th_joint_def_at(w, kinds[i], top, boxes[i], th_v3(x, 3, 0), th_v3(1, 0, 0));
        j.constraint_hertz = 2;
        j.constraint_damping_ratio = 1;
        th_joint(w, &j);
    }
    for (int s = 0; s < 90; s++) th_assert_ok(tb_world_step(w, DT));
    double want = G / pow(2 * PI * 2, 2);
    for (int i = 0; i < 2; i++) {
        tb_vec3 p, v;
        th_read_pose(w, boxes[i], &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, boxes[i], &v, NULL));
        print_message("  soft %s 2 Hz: sags %.4f m (a spring: %.4f), moving %.5f m/s\n",
                      i ? "weld" : "ball", 2.9 - p.y, want, fabs(v.y));
        th_assert_near(2.9 - p.y, want, 0, 0.02);
        assert_true(fabs(v.y) < 1e-3);
    }
    th_world_destroy(w);
}

/* What cone-twist and 6-dof joints and springs refuse, with nothing made or changed. */
static void test_bad_input(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_body_id top = th_post(w, th_v3(0, 2, 0));
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.1f), th_v3(0, 1, 0));
    tb_body_id bob = th_body(w, &d);
    tb_joint_def cone = th_joint_def_at(w, TB_JOINT_CONE_TWIST, top, bob, th_v3(0, 2, 0),
                                     th_v3(0, -1, 0));
    tb_joint_def six = cone;
    six.kind = TB_JOINT_SIX_DOF;
    tb_joint_id id;
    tb_joint_def bad = cone;
    bad.cone_angle = -0.1f;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad.cone_angle = NAN;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.enable_motor = 1;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.enable_limit = 1;
    bad.lower = -4;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = six;
    bad.axes[2].mode = (tb_joint_axis_mode)9;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = six;
    bad.axes[1] = (tb_joint_axis){ TB_JOINT_AXIS_LIMITED, 0.2f, -0.2f };
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = six;
    bad.axes[4] = (tb_joint_axis){ TB_JOINT_AXIS_LIMITED, -4, 0 };
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = six;
    bad.axes[0] = (tb_joint_axis){ TB_JOINT_AXIS_LIMITED, 0, INFINITY };
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = six;
    bad.enable_limit = 1;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.enable_spring = 1;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.constraint_hertz = -1;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.constraint_damping_ratio = NAN;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    bad = cone;
    bad.kind = TB_JOINT_HINGE;
    bad.enable_spring = 1;
    bad.spring_target = 4;
    th_assert_result(tb_joint_create(w, &bad, &id), TB_ERROR_INVALID_ARGUMENT);
    assert_int_equal(tb_world_joint_ids(w, NULL, 0), 0);
    /* Good ones; a spring that a kind lacks or a bad spring is refused, the joint kept. */
    tb_joint_id ball, hinge;
    bad = cone;
    bad.kind = TB_JOINT_BALL;
    th_assert_ok(tb_joint_create(w, &bad, &ball));
    bad.kind = TB_JOINT_HINGE;
    th_assert_ok(tb_joint_create(w, &bad, &hinge));
    th_assert_ok(tb_joint_create(w, &six, &id));
    th_assert_ok(tb_joint_create(w, &cone, &id));
    th_assert_result(tb_joint_set_spring(w, ball, 1, 1, 0, 0), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_joint_set_spring(w, hinge, 1, 0, 0, 0), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_joint_set_spring(w, hinge, 1, 1, -1, 0), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_joint_set_spring(w, hinge, 1, 1, 0, NAN), TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_joint_set_spring(w, hinge, 1, 1, 0, 0.5f));
    assert_int_equal(tb_world_joint_ids(w, NULL, 0), 4);
    th_assert_ok(tb_world_step(w, DT));
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone_swing),
        cmocka_unit_test(test_cone_twist_limit),
        cmocka_unit_test(test_six_dof_hinge),
        cmocka_unit_test(test_six_dof_slider),
        cmocka_unit_test(test_hinge_spring),
        cmocka_unit_test(test_slider_spring),
        cmocka_unit_test(test_soft_joint),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
