/* The block solver (src/solver/block.h), the default (tb_world_set_solver chooses it
 * explicitly here): what it holds, so it keeps holding it while it is worked on. Measured
 * on lavapipe at its defaults (30 sweeps): the column of 20 sinks 4.6 mm in 1000
 * steps (the soft step: 27 mm), a tilted box dropped on the floor lands on a face and stays;
 * the sweeps' lanes a body (8, 16, 32) follow the world's bodies and contact points.
 */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "layout.h"
#include "scenes.h"
#include "solver/block.h"

static tb_world* block_world_of(const tb_world_def* def)
{
    tb_world* w = th_world_create(def);
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_BLOCK, 0));
    return w;
}

static tb_world* block_world(void)
{
    return block_world_of(NULL);
}

/* A sphere of radius r and restitution e. */
static tb_shape_id bouncy_sphere(tb_world* w, float r, float e)
{
    tb_shape_def sd = tb_default_shape_def();
    sd.restitution = e;
    tb_shape_id s;
    th_assert_ok(tb_shape_create_sphere(w, &sd, r, &s));
    return s;
}

/* Scene `name` with n bodies (its seed `seed`) built in w; its instance, and its bodies in
 * *ids and *count. */
static scene_instance* build_scene(tb_world* w, const scene* sc, uint32_t n, uint32_t seed,
                                   const tb_body_id** ids, uint32_t* count)
{
    assert_non_null(sc);
    scene_params params = { n, seed };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    *ids = scene_body_ids(inst, count);
    return inst;
}

/* A column of 20 unit boxes at rest on the floor: no box moves 5 mm from its start in 1000
 * steps, the bound (hard contacts do not sag under the load above them). */
static void test_column_of_20_holds(void** state)
{
    (void)state;
    tb_world* w = block_world();
    const scene* sc = scene_find("stack");
    const tb_body_id* ids;
    uint32_t count;
    scene_instance* inst = build_scene(w, sc, 20, 1, &ids, &count);
    assert_int_equal(count, 20);
    tb_vec3 x0[20], x[20];
    tb_quat q[20];
    th_assert_ok(tb_world_read_transforms(w, ids, count, x0, q));
    double worst = 0;
    for (int block = 0; block < 10; block++) {
        th_assert_ok(tb_world_step_n(w, sc->dt, 100));
        th_assert_ok(tb_world_read_transforms(w, ids, count, x, q));
        for (uint32_t i = 0; i < count; i++) {
            double dx = x[i].x - x0[i].x, dy = x[i].y - x0[i].y, dz = x[i].z - x0[i].z;
            double d = sqrt(dx * dx + dy * dy + dz * dz);
            if (!(d <= worst)) worst = isnan(d) ? INFINITY : d;
        }
    }
    print_message("  column of 20: largest drift %.5f m\n", worst);
    assert_true(worst < 0.005);
    sc->destroy(inst);
    th_world_destroy(w);
}

/* A box turned about a generic axis, dropped from 3 m onto the floor: it lands, tips onto a
 * face and rests there (centre 0.5 m up within 5 mm, still). Before the Hessian kept the
 * stiffness of contacts whose force had dropped to zero, this box sank through the floor
 * or was thrown off at 30 m/s. */
static void test_tilted_box_lands(void** state)
{
    (void)state;
    tb_world* w = block_world();
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_body_def def = th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), th_v3(0, 3, 0));
    def.rotation = th_quat_axis_angle(th_v3(0.4f, 0.8f, 0.2f), 0.5);
    tb_body_id box = th_body(w, &def);
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 180));
    tb_vec3 p, v, omega;
    tb_quat q;
    th_read_pose(w, box, &p, &q);
    th_assert_ok(tb_body_get_velocity(w, box, &v, &omega));
    print_message("  box at (%.4f, %.4f, %.4f), speed %.2e m/s, spin %.2e rad/s\n", p.x, p.y,
                  p.z, sqrt(v.x * v.x + v.y * v.y + v.z * v.z),
                  sqrt(omega.x * omega.x + omega.y * omega.y + omega.z * omega.z));
    assert_true(fabs(p.y - 0.5) < 0.005);
    assert_true(fabs(p.x) < 1.0 && fabs(p.z) < 1.0);
    assert_true(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < 0.01);
    th_world_destroy(w);
}

/* The same pile of boxes dropped twice ends bit for bit the same: the contact lists are
 * filled by atomics but sorted, the colouring depends on nothing but the graph, and bodies
 * of one colour do not touch. */
static void test_repeatable(void** state)
{
    (void)state;
    tb_vec3 end[2][64];
    for (int run = 0; run < 2; run++) {
        tb_world* w = block_world();
        const scene* sc = scene_find("boxes");
        const tb_body_id* ids;
        uint32_t count;
        scene_instance* inst = build_scene(w, sc, 64, 7, &ids, &count);
        assert_true(count >= 64);
        th_assert_ok(tb_world_step_n(w, sc->dt, 90));
        tb_quat q[64];
        th_assert_ok(tb_world_read_transforms(w, ids + count - 64, 64, end[run], q));
        sc->destroy(inst);
        th_world_destroy(w);
    }
    assert_memory_equal(end[0], end[1], sizeof end[0]);
}

/* Height of a ball's apex after its first bounce off the floor, m, dropped from `drop`. */
static double bounce_apex(float e, float drop)
{
    tb_world* w = block_world();
    double apex = th_bounce_apex(w, e, drop);
    th_world_destroy(w);
    return apex;
}

/* A ball dropped 2 m with restitution e leaves the floor at e times the speed it met it
 * with, and rises to e^2 of the drop within 5 %, as with the soft step. Without the bounce
 * pass the ball stayed on the floor; with the arc integrated in one piece a step it rose
 * 7.6 % short at e = 0.5; with the impact's force carried into the next step, 7 % high. */
static void test_bounce_height(void** state)
{
    (void)state;
    const float es[] = { 0.5f, 0.8f };
    for (int i = 0; i < 2; i++) {
        double apex = bounce_apex(es[i], 2.0f);
        print_message("  e = %.1f: apex %.4f m, e^2 drop %.4f m\n", es[i], apex,
                      es[i] * es[i] * 2.0);
        th_assert_near(apex, es[i] * es[i] * 2.0, 0, 0.05);
    }
}

/* Two equal balls meet head on without gravity, e = 1: they trade velocities (the one that
 * came stops, the one that waited leaves at its speed) and their momentum stays, although
 * each body changes only its own velocity in the bounce pass. */
static void test_head_on_bounce_trades_velocities(void** state)
{
    (void)state;
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    tb_world* w = block_world_of(&wd);
    tb_shape_id s = bouncy_sphere(w, 0.5f, 1.0f);
    tb_body_def a = th_dynamic_def(s, th_v3(-2, 1, 0)), b = th_dynamic_def(s, th_v3(2, 1, 0));
    a.linear_velocity = th_v3(3, 0, 0);
    tb_body_id ids[2] = { th_body(w, &a), th_body(w, &b) };
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 120));
    tb_vec3 v[2], omega;
    for (int i = 0; i < 2; i++) th_assert_ok(tb_body_get_velocity(w, ids[i], &v[i], &omega));
    print_message("  after: a %.4f m/s, b %.4f m/s\n", v[0].x, v[1].x);
    th_assert_near(v[0].x + v[1].x, 3.0, 1e-3, 0);
    th_assert_near(v[0].x, 0.0, 0.05, 0);
    th_assert_near(v[1].x, 3.0, 0.05, 0);
    th_world_destroy(w);
}

/* A hull, and a box, thrown at a thin static wall at 100 m/s without gravity stop on their
 * face and stay there: the force that stopped them is not carried into the next step (it
 * threw the hull back at 30 m/s), nor what was left of it once the impact's share was taken
 * off (with the stiffness the impact grew it kicked the box off the wall at 5 mm/s), and
 * they leave with no speed. */
static void impact_is_not_carried(int box)
{
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    tb_world* w = block_world_of(&wd);
    tb_body_def d = th_static_def(th_box(w, th_v3(0.025f, 5, 5)), th_v3(0, 0, 0));
    th_body(w, &d);
    d = th_dynamic_def(box ? th_box(w, th_v3(0.1f, 0.1f, 0.1f)) : th_rock(w), th_v3(-3.05f, 0, 0));
    d.linear_velocity = th_v3(100, 0, 0);
    tb_body_id id = th_body(w, &d);
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 3));
    tb_vec3 at, x, v, omega;
    th_read_pose(w, id, &at, NULL);
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 30));
    th_read_pose(w, id, &x, NULL);
    th_assert_ok(tb_body_get_velocity(w, id, &v, &omega));
    print_message("  %s at %.4f m after 3 steps, %.4f after 33, speed %.2e m/s\n",
                  box ? "box" : "hull", at.x, x.x, sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
    assert_true(at.x > -0.025f - 0.2f && at.x < -0.025f - 0.08f);
    th_assert_near(x.x, at.x, 1e-3, 0);
    assert_true(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) < 1e-3);
    th_world_destroy(w);
}

static void test_impact_is_not_carried(void** state)
{
    (void)state;
    impact_is_not_carried(0);
    impact_is_not_carried(1);
}

static int crowd_on_cpu;   /* crowd_after's world ran on a CPU device */

/* The centres of n spheres of radius 0.5 started within 1 cm of the origin without gravity,
 * after `steps` steps with the block solver; the stats of the first step, and the slowest
 * ball's speed after it. */
static void crowd_after(uint32_t n, uint32_t steps, tb_vec3* at, tb_world_stats* stats,
                        double* slowest)
{
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    tb_world* w = block_world_of(&def);
    tb_device_info info;
    th_assert_ok(tb_world_device_info(w, &info));
    crowd_on_cpu = info.is_cpu;
    tb_shape_id ball = bouncy_sphere(w, 0.5f, 0.3f);   /* the bounce's tail pass runs too */
    th_rng rng = th_rng_seed(11);
    tb_body_id ids[128];
    assert_true(n <= 128);
    for (uint32_t i = 0; i < n; i++) {
        tb_vec3 p = th_v3(th_rng_range(&rng, -0.01f, 0.01f), th_rng_range(&rng, -0.01f, 0.01f),
                          th_rng_range(&rng, -0.01f, 0.01f));
        tb_body_def d = th_dynamic_def(ball, p);
        ids[i] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step(w, 1.0f / 60));
    th_assert_ok(tb_world_get_stats(w, stats));
    *slowest = INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        tb_vec3 v, omega;
        th_assert_ok(tb_body_get_velocity(w, ids[i], &v, &omega));
        double speed = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        if (!(speed >= *slowest)) *slowest = speed;
    }
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, steps - 1));
    tb_quat q[128];
    th_assert_ok(tb_world_read_transforms(w, ids, n, at, q));
    th_world_destroy(w);
}

/* 100 balls in one place touch each other: a body's neighbours outnumber the 64 colours,
 * and the bodies the colouring leaves over are solved one at a time after the colours (the
 * tail). Every ball is pushed out in the first step (measured: the slowest leaves at 1.06
 * m/s; a ball the tail left unsolved stays at rest, and before the tail the step was
 * refused), they end apart, and the run repeats bit for bit. */
static void crowd_beyond_the_colours(void)
{
    enum { N = 100 };
    tb_vec3 at[2][N];
    tb_world_stats stats;
    double slowest;
    for (int run = 0; run < 2; run++) crowd_after(N, 240, at[run], &stats, &slowest);
    assert_int_equal(stats.colour_rounds, TB_MAX_COLOURS);
    assert_int_equal(stats.colour_count, TB_MAX_COLOURS);
    double deepest = 0;
    for (int i = 0; i < N; i++)
        for (int j = i + 1; j < N; j++) {
            double dx = at[0][i].x - at[0][j].x, dy = at[0][i].y - at[0][j].y,
                   dz = at[0][i].z - at[0][j].z;
            double depth = 1.0 - sqrt(dx * dx + dy * dy + dz * dz);
            if (!(depth <= deepest)) deepest = isnan(depth) ? INFINITY : depth;
        }
    print_message("  crowd of %d: slowest ball after the first step %.4f m/s, deepest "
                  "overlap at the end %.4f m\n", N, slowest, deepest);
    assert_true(slowest > 0.1);
    assert_true(deepest < 0.01);
    assert_memory_equal(at[0], at[1], sizeof at[0]);
}

static void test_crowd_beyond_the_colours(void** state)
{
    (void)state;
    crowd_beyond_the_colours();
}

/* The same with the GPU's tail kernel (block/solve_tail: a workgroup's invocations share
 * each body, their sums added in a fixed order), which lavapipe takes only when asked. */
static void test_crowd_with_the_wide_tail(void** state)
{
    (void)state;
    setenv("TUMBLE_WIDE_TAIL", "1", 1);
    crowd_beyond_the_colours();
    unsetenv("TUMBLE_WIDE_TAIL");
}

/* The sweeps with 16 and 32 lanes a body, held by TUMBLE_BLOCK_LANES (a world on lavapipe
 * otherwise keeps the 8-lane sweep, the same kernel there): made on first use, valid, and
 * on lavapipe, which runs every sweep one lane a body, the same crowd to the bit. */
static void test_wide_sweeps_agree(void** state)
{
    (void)state;
    enum { N = 20 };
    tb_vec3 at[3][N];
    tb_world_stats stats;
    double slowest;
    const char* lanes[3] = { NULL, "16", "32" };
    for (int run = 0; run < 3; run++) {
        if (lanes[run]) setenv("TUMBLE_BLOCK_LANES", lanes[run], 1);
        crowd_after(N, 40, at[run], &stats, &slowest);
        unsetenv("TUMBLE_BLOCK_LANES");
    }
    assert_true(slowest > 0.1);
    if (crowd_on_cpu) {
        assert_memory_equal(at[0], at[1], sizeof at[0]);
        assert_memory_equal(at[0], at[2], sizeof at[0]);
    }
}

/* The fused solve (every sweep of the step in one workgroup, block/solve_fused) against a
 * dispatch a colour, held by TUMBLE_BLOCK_FUSED: the same bodies move by the same steps in the
 * same order, so the same states to the bit. A pile of 72 boxes and balls (on lavapipe two
 * passes of the fused workgroup a colour), bouncy balls among them, and a hanging chain of
 * ten links with two bodies dropped beside it (the sweeps with the joints' rows). The worlds
 * log through fused_log, which reads the recorded dispatches, so they are made here, with
 * validation asked for as th_world_create asks. */
static uint32_t fused_dispatches;

static void fused_log(void* user, tb_log_level level, const char* message)
{
    unsigned stages, dispatches;
    if (sscanf(message, "step recorded: %u stages, %u dispatches", &stages, &dispatches) == 2)
        fused_dispatches = dispatches;
    th_log_fn(user, level, message);
}

enum { FUSED_BODIES = 72 };

static void fused_run(int joints, const char* fused, tb_vec3* at, tb_quat* q, uint32_t* dispatches)
{
    setenv("TUMBLE_BLOCK_FUSED", fused, 1);
    setenv("TUMBLE_BLOCK_LANES", "8", 1);   /* the same lanes both ways on a GPU too */
    tb_world_def def = tb_default_world_def();
    def.validation = 1;
    def.log = fused_log;
    th_log log = { 0 };
    def.log_user = &log;
    tb_world* w = NULL;
    th_assert_ok(tb_world_create(&def, &w));
    unsetenv("TUMBLE_BLOCK_FUSED");
    unsetenv("TUMBLE_BLOCK_LANES");
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id shapes[3] = { th_box(w, th_v3(0.2f, 0.2f, 0.2f)), th_sphere(w, 0.2f),
                              bouncy_sphere(w, 0.2f, 0.6f) };
    th_rng rng = th_rng_seed(5);
    tb_body_id ids[FUSED_BODIES];
    uint32_t n = 0;
    if (joints) {
        tb_body_id last = th_post(w, th_v3(0, 4, 0));
        tb_shape_id link = th_box(w, th_v3(0.15f, 0.05f, 0.05f));
        for (int i = 0; i < 10; i++) {
            tb_body_def d = th_dynamic_def(link, th_v3(0.15f + 0.3f * (float)i, 4, 0));
            ids[n] = th_body(w, &d);
            tb_joint_def jd = th_joint_def_at(w, TB_JOINT_BALL, last, ids[n],
                                              th_v3(0.3f * (float)i, 4, 0), th_v3(0, 0, 1));
            th_joint(w, &jd);
            last = ids[n++];
        }
    }
    while (n < (joints ? 12u : (uint32_t)FUSED_BODIES)) {
        tb_body_def d = th_dynamic_def(shapes[n % 3], th_v3(th_rng_range(&rng, -1.5f, 1.5f),
                                       0.3f + 0.45f * (float)(n / 16), th_rng_range(&rng, -1.5f, 1.5f)));
        d.rotation = th_rng_quat(&rng);
        ids[n++] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 40));
    th_assert_ok(tb_world_read_transforms(w, ids, n, at, q));
    *dispatches = fused_dispatches;
    tb_world_stats stats = th_stats(w);
    assert_int_equal(stats.validation_messages, 0);
    assert_int_equal(log.warnings, 0);
    tb_world_destroy(w);
}

static void test_fused_solve_agrees(void** state)
{
    (void)state;
    for (int joints = 0; joints < 2; joints++) {
        tb_vec3 at[2][FUSED_BODIES];
        tb_quat q[2][FUSED_BODIES];
        uint32_t dispatches[2];
        memset(at, 0, sizeof at);
        memset(q, 0, sizeof q);
        fused_run(joints, "0", at[0], q[0], &dispatches[0]);
        fused_run(joints, "1", at[1], q[1], &dispatches[1]);
        print_message("  %s: %u dispatches a step a colour at a time, %u fused\n",
                      joints ? "chain" : "pile", dispatches[0], dispatches[1]);
        /* 30 sweeps of two colours or more in one dispatch. */
        assert_true(dispatches[0] >= dispatches[1] + 50);
        assert_memory_equal(at[0], at[1], sizeof at[0]);
        assert_memory_equal(q[0], q[1], sizeof q[0]);
        /* Something moved: the pile's top body (2.55 m up) fell, the chain's end (4 m) swung down. */
        assert_true(at[0][joints ? 9 : FUSED_BODIES - 1].y < (joints ? 3.7f : 2.2f));
    }
}

/* Small worlds fuse their sweeps on a GPU; a CPU device's and a world with the tail never
 * do unless told; TUMBLE_BLOCK_FUSED decides when set. */
static void test_fused_choice(void** state)
{
    (void)state;
    assert_int_equal(tb_block_fuses(20, 3, 0, -1), 1);
    assert_int_equal(tb_block_fuses(TB_BLOCK_FUSED_BODIES, 8, 0, -1), 1);
    assert_int_equal(tb_block_fuses(TB_BLOCK_FUSED_BODIES + 1, 8, 0, -1), 0);
    assert_int_equal(tb_block_fuses(20, 3, 1, -1), TB_BLOCK_FUSED_BODIES_CPU >= 20);
    assert_int_equal(tb_block_fuses(20, TB_MAX_COLOURS, 0, -1), 0);
    assert_int_equal(tb_block_fuses(20, TB_MAX_COLOURS, 0, 1), 0);
    assert_int_equal(tb_block_fuses(100000, 8, 1, 1), 1);
    assert_int_equal(tb_block_fuses(20, 3, 0, 0), 0);
}

/* The sweeps' lanes a body (8, 16, 32) follow the bodies and their contact points, with a
 * margin before a change. (On lavapipe every sweep runs 1 lane a body, so the choice is
 * checked here and its speed on a GPU, docs/performance.md.) */
static void test_lanes_choice(void** state)
{
    (void)state;
    assert_int_equal(tb_block_lanes_for(0, 0, 8), 8);
    assert_int_equal(tb_block_lanes_for(100000, 600000, 8), 8);      /* many bodies */
    assert_int_equal(tb_block_lanes_for(100000, 600000, 32), 8);
    assert_int_equal(tb_block_lanes_for(5051, 59800, 8), 32);        /* base-100 pyramid */
    assert_int_equal(tb_block_lanes_for(4000, 16000, 8), 16);        /* 8 entries a body */
    assert_int_equal(tb_block_lanes_for(4000, 1000, 8), 8);          /* few contacts */
    assert_int_equal(tb_block_lanes_for(4000, 1000, 16), 8);
    /* At a bound, the lanes in use stay: 4 entries a body, 7,000 and 8,192 bodies. */
    assert_int_equal(tb_block_lanes_for(7000, 14000, 8), 8);
    assert_int_equal(tb_block_lanes_for(7000, 14000, 16), 16);
    assert_int_equal(tb_block_lanes_for(8192, 40000, 16), 16);
    assert_int_equal(tb_block_lanes_for(8192, 40000, 8), 8);
    /* Well past it, they change. */
    assert_int_equal(tb_block_lanes_for(5000, 20000, 8), 16);
    assert_int_equal(tb_block_lanes_for(7000, 9000, 16), 8);
    assert_int_equal(tb_block_lanes_for(11000, 40000, 16), 8);
}

/* A world starts with the block solver (30 sweeps); tb_world_set_solver chooses the solver
 * before the first step, and only then; bad arguments are refused with a sentence and
 * change nothing. A world switched to the soft step and back after bodies were added steps
 * with each. */
static void test_solver_choice(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    uint32_t iterations = 0;
    assert_int_equal(tb_world_get_solver(w, &iterations), TB_SOLVER_BLOCK);
    assert_int_equal(iterations, 30);
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), th_v3(0, 0.6f, 0));
    tb_body_id box = th_body(w, &d);
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 0));
    assert_int_equal(tb_world_get_solver(w, NULL), TB_SOLVER_SOFT_STEP);
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_BLOCK, 20));
    assert_int_equal(tb_world_get_solver(w, &iterations), TB_SOLVER_BLOCK);
    assert_int_equal(iterations, 20);
    assert_int_equal(tb_world_set_solver(w, (tb_solver_kind)7, 0), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "unknown solver"));
    assert_int_equal(tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 1001), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "iterations"));
    assert_int_equal(tb_world_get_solver(w, &iterations), TB_SOLVER_BLOCK);
    assert_int_equal(iterations, 20);
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 0));
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_BLOCK, 0));
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 60));
    assert_int_equal(tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 0), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "before the world's first step"));
    assert_int_equal(tb_world_get_solver(w, NULL), TB_SOLVER_BLOCK);
    tb_vec3 p;
    th_read_pose(w, box, &p, NULL);
    th_assert_near(p.y, 0.5, 1e-3, 0);
    assert_int_equal(tb_world_get_solver(NULL, NULL), TB_SOLVER_BLOCK);
    assert_int_equal(tb_world_set_solver(NULL, TB_SOLVER_BLOCK, 0), TB_ERROR_INVALID_ARGUMENT);
    th_world_destroy(w);

    /* The soft step, stepped: the box rests on the floor too. */
    w = th_world_create(NULL);
    ground.shape = th_plane(w, th_v3(0, 1, 0), 0);
    th_body(w, &ground);
    th_assert_ok(tb_world_set_solver(w, TB_SOLVER_SOFT_STEP, 0));
    d.shape = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
    box = th_body(w, &d);
    th_assert_ok(tb_world_step_n(w, 1.0f / 60, 60));
    assert_int_equal(tb_world_get_solver(w, NULL), TB_SOLVER_SOFT_STEP);
    th_read_pose(w, box, &p, NULL);
    th_assert_near(p.y, 0.5, 1e-2, 0);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_column_of_20_holds),
        cmocka_unit_test(test_tilted_box_lands),
        cmocka_unit_test(test_repeatable),
        cmocka_unit_test(test_bounce_height),
        cmocka_unit_test(test_head_on_bounce_trades_velocities),
        cmocka_unit_test(test_impact_is_not_carried),
        cmocka_unit_test(test_crowd_beyond_the_colours),
        cmocka_unit_test(test_crowd_with_the_wide_tail),
        cmocka_unit_test(test_lanes_choice),
        cmocka_unit_test(test_wide_sweeps_agree),
        cmocka_unit_test(test_fused_solve_agrees),
        cmocka_unit_test(test_fused_choice),
        cmocka_unit_test(test_solver_choice),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
