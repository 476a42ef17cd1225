/* Compound shapes: mass properties composed from their children (a dumbbell of two
 * spheres against its analytic inertia, unequal densities), and in the step on lavapipe: a
 * table of five boxes dropped on a plane settles on its four legs, bricks of two boxes
 * stack, a table stands on a triangle mesh, every broadphase finds the same child pairs,
 * a split that overflows the pair buffers grows them, isap keeps a compound pair once from
 * step to step, and bad compounds are refused with
 * nothing changed. */
#include "harness.h"

#include <math.h>
#include <string.h>

#define DT (1.0f / 60.0f)
#define PI 3.14159265358979323846

static tb_compound_child child(tb_shape_id shape, tb_vec3 position, tb_quat rotation)
{
    return (tb_compound_child){ shape, position, rotation };
}

static tb_shape_id compound(tb_world* w, const tb_compound_child* children, uint32_t count)
{
    tb_shape_id id;
    th_assert_ok(tb_shape_create_compound(w, children, count, &id));
    return id;
}

/* Two spheres of radius r at +-d along a tilted axis: mass 2m, centre between them, and
 * moments 2 (2/5 m r^2) about the axis and 2 (2/5 m r^2 + m d^2) across it. */
static void test_dumbbell_inertia(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    const double r = 0.25, d = 1.0, rho = 1000.0;
    tb_shape_id ball = th_sphere(w, (float)r);
    const double axis[3] = { 0.6, 0.8, 0.0 };
    tb_vec3 centre = th_v3(1.0f, 2.0f, 3.0f);
    tb_compound_child c[2] = {
        child(ball, th_v3(centre.x + (float)(d * axis[0]), centre.y + (float)(d * axis[1]), centre.z),
              th_q(0, 0, 0, 1)),
        child(ball, th_v3(centre.x - (float)(d * axis[0]), centre.y - (float)(d * axis[1]), centre.z),
              th_quat_axis_angle(th_v3(0, 0, 1), 0.7)),
    };
    tb_shape_id shape = compound(w, c, 2);
    tb_compound_info info;
    th_assert_ok(tb_shape_get_compound_info(w, shape, &info));
    const double m = rho * 4.0 / 3.0 * PI * r * r * r;
    assert_int_equal(info.child_count, 2);
    th_assert_near(info.volume, 2 * m / rho, 0, 1e-5);
    th_assert_near(info.mass_per_volume, rho, 0, 1e-5);
    th_assert_near(info.center_of_mass.x, centre.x, 1e-5, 0);
    th_assert_near(info.center_of_mass.y, centre.y, 1e-5, 0);
    th_assert_near(info.center_of_mass.z, centre.z, 1e-5, 0);
    /* The body axis with the smallest moment lies along the dumbbell. */
    double along = 2 * 0.4 * r * r / 2, across = (2 * (0.4 * r * r + d * d)) / 2;
    const float* u = &info.unit_inertia.x;
    int smallest = 0;
    for (int k = 1; k < 3; k++) smallest = u[k] < u[smallest] ? k : smallest;
    for (int k = 0; k < 3; k++) th_assert_near(u[k], k == smallest ? along : across, 0, 1e-4);
    double e[3] = { 0, 0, 0 }, turned[3];
    e[smallest] = 1;
    th_quat_rotate(info.principal_axes, e, turned);
    th_assert_near(fabs(turned[0] * axis[0] + turned[1] * axis[1]), 1.0, 1e-5, 0);
    /* A body of it gets the composed mass and inertia. */
    tb_body_def def = th_dynamic_def(shape, th_v3(0, 5, 0));
    tb_body_id body = th_body(w, &def);
    float mass;
    tb_vec3 inertia;
    th_assert_ok(tb_body_get_mass(w, body, &mass, &inertia));
    th_assert_near(mass, 2 * m, 0, 1e-5);
    th_assert_near((&inertia.x)[smallest], 2 * m * along, 0, 1e-4);
    /* The children come back in the body frame: at -+d along the smallest axis. */
    tb_compound_child back[2];
    uint32_t count = 0;
    th_assert_ok(tb_shape_get_compound_children(w, shape, back, 2, &count));
    assert_int_equal(count, 2);
    th_assert_near(fabs((&back[0].position.x)[smallest]), d, 1e-5, 0);
    th_assert_near(back[0].position.x + back[1].position.x, 0, 1e-5, 0);
    th_world_destroy(w);
}

/* A sphere ten times as dense as its twin pulls the centre of mass to 10/11 of the way. */
static void test_unequal_densities(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_shape_def heavy = tb_default_shape_def();
    heavy.density = 10000;
    tb_shape_id a, b = th_sphere(w, 0.5f);
    th_assert_ok(tb_shape_create_sphere(w, &heavy, 0.5f, &a));
    tb_compound_child c[2] = { child(a, th_v3(1, 0, 0), th_q(0, 0, 0, 1)),
                               child(b, th_v3(-1, 0, 0), th_q(0, 0, 0, 1)) };
    tb_compound_info info;
    th_assert_ok(tb_shape_get_compound_info(w, compound(w, c, 2), &info));
    th_assert_near(info.center_of_mass.x, 1.0 - 2.0 / 11.0, 1e-5, 0);
    th_assert_near(info.mass_per_volume, 5500, 0, 1e-5);
    th_world_destroy(w);
}

/* A table: a top of 1.6 x 0.1 x 1.2 m and four legs 0.1 x 1 x 0.1 m under its corners. Its
 * input frame has the top's centre at the origin and the legs' feet at y = -1.05. */
static tb_shape_id table(tb_world* w)
{
    tb_shape_id top = th_box(w, th_v3(0.8f, 0.05f, 0.6f)), leg = th_box(w, th_v3(0.05f, 0.5f, 0.05f));
    tb_quat id = th_q(0, 0, 0, 1);
    tb_compound_child c[5] = { child(top, th_v3(0, 0, 0), id),
                               child(leg, th_v3(0.7f, -0.55f, 0.5f), id),
                               child(leg, th_v3(-0.7f, -0.55f, 0.5f), id),
                               child(leg, th_v3(0.7f, -0.55f, -0.5f), id),
                               child(leg, th_v3(-0.7f, -0.55f, -0.5f), id) };
    return compound(w, c, 5);
}

/* Where a table's body sits when its feet stand on y = ground, level. */
static tb_vec3 table_rest(tb_world* w, tb_shape_id shape, float ground, tb_quat* rotation)
{
    tb_compound_info info;
    th_assert_ok(tb_shape_get_compound_info(w, shape, &info));
    *rotation = info.principal_axes;
    return th_v3(info.center_of_mass.x, ground + 1.05f + info.center_of_mass.y, info.center_of_mass.z);
}

static double distance(tb_vec3 a, tb_vec3 b)
{
    double x = a.x - b.x, y = a.y - b.y, z = a.z - b.z;
    return sqrt(x * x + y * y + z * z);
}

/* Contacts of the last step all at the feet: four places on the ground. */
static void assert_on_feet(tb_world* w, float ground)
{
    tb_contact contacts[64];
    uint32_t n = 0;
    th_assert_ok(tb_world_read_contacts(w, contacts, 64, &n));
    assert_true(n >= 4 && n <= 64);
    int corners = 0;
    for (uint32_t i = 0; i < n; i++) {
        th_assert_near(contacts[i].point.y, ground, 5e-3, 0);
        assert_true(fabsf(fabsf(contacts[i].point.x) - 0.7f) < 0.06f);
        assert_true(fabsf(fabsf(contacts[i].point.z) - 0.5f) < 0.06f);
        corners |= 1 << ((contacts[i].point.x > 0) + 2 * (contacts[i].point.z > 0));
    }
    assert_int_equal(corners, 15);
}

/* A table dropped from `lift` above standing on the ground (y = 0, already in w) lands on
 * its legs and stands without drifting. */
static void assert_table_stands(tb_world* w, float lift)
{
    tb_shape_id shape = table(w);
    tb_quat rotation;
    tb_vec3 rest = table_rest(w, shape, 0, &rotation);
    tb_body_def d = th_dynamic_def(shape, th_v3(rest.x, rest.y + lift, rest.z));
    d.rotation = rotation;
    tb_body_id body = th_body(w, &d);
    th_assert_ok(tb_world_step_n(w, DT, 120));
    tb_vec3 p;
    th_read_pose(w, body, &p, NULL);
    if (!(distance(p, rest) < 5e-3))
        fail_msg("the table came to (%g %g %g), not (%g %g %g)", p.x, p.y, p.z, rest.x, rest.y, rest.z);
    assert_on_feet(w, 0);
    tb_vec3 settled = p;
    th_assert_ok(tb_world_step_n(w, DT, 300));
    th_read_pose(w, body, &p, NULL);
    if (!(distance(p, settled) < 1e-3)) fail_msg("drifted %g m in 300 steps", distance(p, settled));
}

/* Dropped 20 cm onto a plane. */
static void test_table_settles_on_legs(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    assert_table_stands(w, 0.2f);
    th_world_destroy(w);
}

/* Bricks of two boxes side by side, three high, each turned a quarter turn on the one below:
 * compound against compound, and the stack stands still (warm starting per child pair). */
static void test_bricks_stack(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id half = th_box(w, th_v3(0.25f, 0.25f, 0.5f));
    tb_compound_child c[2] = { child(half, th_v3(-0.25f, 0, 0), th_q(0, 0, 0, 1)),
                               child(half, th_v3(0.25f, 0, 0), th_q(0, 0, 0, 1)) };
    tb_shape_id brick = compound(w, c, 2);
    tb_compound_info info;
    th_assert_ok(tb_shape_get_compound_info(w, brick, &info));
    tb_body_id bodies[3];
    tb_vec3 starts[3];
    for (int i = 0; i < 3; i++) {
        tb_quat turn = th_quat_axis_angle(th_v3(0, 1, 0), i % 2 ? PI / 2 : 0.0);
        starts[i] = th_v3(0, 0.25f + 0.5f * i, 0);
        tb_body_def d = th_dynamic_def(brick, starts[i]);
        /* Body frame = principal frame: turn the input frame by the principal axes. */
        double q[4];
        const tb_quat a = turn, b = info.principal_axes;
        q[0] = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
        q[1] = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
        q[2] = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
        q[3] = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
        d.rotation = th_q((float)q[0], (float)q[1], (float)q[2], (float)q[3]);
        bodies[i] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step_n(w, DT, 60));
    tb_vec3 settled[3];
    for (int i = 0; i < 3; i++) {
        th_read_pose(w, bodies[i], &settled[i], NULL);
        if (!(distance(settled[i], starts[i]) < 5e-3))
            fail_msg("brick %d at (%g %g %g), placed at height %g", i, settled[i].x, settled[i].y,
                     settled[i].z, starts[i].y);
    }
    th_assert_ok(tb_world_step_n(w, DT, 300));
    for (int i = 0; i < 3; i++) {
        tb_vec3 p;
        th_read_pose(w, bodies[i], &p, NULL);
        if (!(distance(p, settled[i]) < 1e-3))
            fail_msg("brick %d drifted %g m in 300 steps", i, distance(p, settled[i]));
    }
    th_world_destroy(w);
}

/* The table on a triangle mesh (a quad of two triangles): child against triangle. */
static void test_table_on_mesh(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    tb_shape_def sd = tb_default_shape_def();
    tb_vec3 v[4] = { th_v3(-3, 0, -3), th_v3(-3, 0, 3), th_v3(3, 0, -3), th_v3(3, 0, 3) };
    uint32_t quad[6] = { 0, 1, 2, 2, 1, 3 };
    tb_shape_id mesh;
    th_assert_ok(tb_shape_create_mesh(w, &sd, v, 4, quad, 2, &mesh));
    tb_body_def ground = th_static_def(mesh, th_v3(0, 0, 0));
    th_body(w, &ground);
    assert_table_stands(w, 0.1f);
    th_world_destroy(w);
}

/* A heap of compounds placed touching, on a plane, in a world of `def`. */
static tb_world* compound_heap(const tb_world_def* def)
{
    tb_world* w = th_world_create(def);
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id ball = th_sphere(w, 0.2f), cube = th_box(w, th_v3(0.2f, 0.2f, 0.2f));
    tb_compound_child c[3] = { child(ball, th_v3(-0.3f, 0, 0), th_q(0, 0, 0, 1)),
                               child(cube, th_v3(0.3f, 0, 0), th_q(0, 0, 0, 1)),
                               child(ball, th_v3(0, 0.4f, 0), th_q(0, 0, 0, 1)) };
    tb_shape_id shape = compound(w, c, 3);
    for (int i = 0; i < 8; i++) {
        tb_body_def d = th_dynamic_def(shape, th_v3(0.3f * (i % 3), 0.3f + 0.45f * i, 0.2f * (i % 2)));
        th_body(w, &d);
    }
    return w;
}

/* Every broadphase splits the same body pairs into the same child pairs (each has its own
 * paths to the pair output: sap's third gear writes for other lanes' finders): a first
 * step over the heap (later steps differ with the pair order the solver meets, as for any
 * shapes). */
static void test_broadphases_agree(void** state)
{
    (void)state;
    const tb_broadphase kinds[] = { TB_BROADPHASE_GRID, TB_BROADPHASE_SAP, TB_BROADPHASE_LBVH,
                                    TB_BROADPHASE_ISAP };
    uint32_t counts[4], points[4];
    for (int k = 0; k < 4; k++) {
        tb_world_def def = tb_default_world_def();
        def.broadphase = kinds[k];
        tb_world* w = compound_heap(&def);
        th_assert_ok(tb_world_step(w, DT));
        tb_world_stats s = th_stats(w);
        counts[k] = s.pair_count;
        points[k] = s.contact_count;
        assert_true(points[k] >= 8);
        /* isap also keeps the body pairs none of whose children touch (it starts the next
         * step from this step's pairs), as pairs without points. */
        if (k) {
            if (kinds[k] == TB_BROADPHASE_ISAP) assert_true(counts[k] >= counts[0]);
            else assert_int_equal(counts[k], counts[0]);
            assert_int_equal(points[k], points[0]);
        }
        th_world_destroy(w);
    }
}

/* Room for the broadphase's records (nine bodies make at most 36 pairs) but for fewer pairs
 * than the split makes of them: the step is run again with room for them, and ends as it
 * does with room from the start. */
static void test_split_overflow_grows(void** state)
{
    (void)state;
    tb_world_def def = tb_default_world_def();
    tb_world* roomy = compound_heap(&def);
    def.initial_pair_capacity = 40;
    tb_world* tight = compound_heap(&def);
    for (int s = 0; s < 3; s++) {
        th_assert_ok(tb_world_step(roomy, DT));
        th_assert_ok(tb_world_step(tight, DT));
    }
    tb_world_stats a = th_stats(roomy), b = th_stats(tight);
    assert_true(a.pair_count > 40);
    assert_true(b.steps_redone > 0);
    assert_int_equal(b.pair_count, a.pair_count);
    assert_int_equal(b.contact_count, a.contact_count);
    th_world_destroy(roomy);
    th_world_destroy(tight);
}

/* No two contacts of the world are one point of one pair twice. */
static void assert_no_repeated_contacts(tb_world* w)
{
    enum { MAX = 512 };
    static tb_contact c[MAX];
    uint32_t n = 0;
    th_assert_ok(tb_world_read_contacts(w, c, MAX, &n));
    assert_true(n > 0 && n <= MAX);
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++) {
            int same = memcmp(&c[i].a, &c[j].a, sizeof c[i].a) == 0 &&
                       memcmp(&c[i].b, &c[j].b, sizeof c[i].b) == 0 &&
                       c[i].feature == c[j].feature && c[i].point.x == c[j].point.x &&
                       c[i].point.y == c[j].point.y && c[i].point.z == c[j].point.z;
            if (same) fail_msg("contacts %u and %u of %u are the same point of one pair", i, j, n);
        }
}

/* isap starts each step from last step's pairs, which a compound pair left as several child
 * pairs: it must take the body pair back once, not once per child pair (each would be split
 * again, and the pairs multiply step by step). Compounds resting side by side, 40 steps. */
static void test_isap_keeps_compound_pairs_once(void** state)
{
    (void)state;
    tb_world_def def = tb_default_world_def();
    def.broadphase = TB_BROADPHASE_ISAP;
    def.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&def);
    tb_shape_id ball = th_sphere(w, 0.2f), cube = th_box(w, th_v3(0.2f, 0.2f, 0.2f));
    tb_compound_child c[3] = { child(ball, th_v3(0, 0, -0.45f), th_q(0, 0, 0, 1)),
                               child(cube, th_v3(0, 0, 0), th_q(0, 0, 0, 1)),
                               child(ball, th_v3(0, 0, 0.45f), th_q(0, 0, 0, 1)) };
    tb_shape_id shape = compound(w, c, 3);
    for (int i = 0; i < 4; i++) {
        tb_body_def d = th_dynamic_def(shape, th_v3(0.399f * i, 0, 0));
        th_body(w, &d);
    }
    uint32_t pairs_at_10 = 0;
    for (int s = 0; s < 40; s++) {
        th_assert_ok(tb_world_step(w, DT));
        if (s == 9) pairs_at_10 = th_stats(w).pair_count;
    }
    assert_no_repeated_contacts(w);
    assert_true(th_stats(w).pair_count <= pairs_at_10 + 2);
    th_world_destroy(w);
}

static void assert_shapes_unchanged(tb_world* w, uint32_t before)
{
    tb_shape_id ids[16];
    assert_int_equal(tb_world_shape_ids(w, ids, 16), before);
}

/* Bad compounds are refused with a sentence and the world keeps its shapes; children stay in
 * use while a compound holds them. */
static void test_bad_compounds_refused(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_shape_id ball = th_sphere(w, 0.5f), plane = th_plane(w, th_v3(0, 1, 0), 0);
    tb_shape_id gone = th_sphere(w, 0.5f);
    th_assert_ok(tb_shape_destroy(w, gone));
    tb_shape_id ids[16], out;
    uint32_t before = tb_world_shape_ids(w, ids, 16);
    tb_quat id = th_q(0, 0, 0, 1);
    tb_compound_child good = child(ball, th_v3(0, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, NULL, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_compound(w, &good, 1, NULL), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_compound(w, &good, 0, &out), TB_ERROR_INVALID_ARGUMENT);
    tb_compound_child many[65];
    for (int i = 0; i < 65; i++) many[i] = child(ball, th_v3((float)i, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, many, 65, &out), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "64"));
    tb_compound_child bad = child(plane, th_v3(0, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    bad = child(gone, th_v3(0, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_STALE_ID);
    bad = child(ball, th_v3(NAN, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    bad = child(ball, th_v3(0, 2e6f, 0), id);
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    bad = child(ball, th_v3(0, 0, 0), th_q(0, 0, 0, 0));
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    assert_shapes_unchanged(w, before);
    /* A compound is no child; its children cannot go while it lives. */
    tb_shape_id made;
    th_assert_ok(tb_shape_create_compound(w, &good, 1, &made));
    bad = child(made, th_v3(0, 0, 0), id);
    th_assert_result(tb_shape_create_compound(w, &bad, 1, &out), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_destroy(w, ball), TB_ERROR_IN_USE);
    tb_compound_info info;
    th_assert_result(tb_shape_get_compound_info(w, ball, &info), TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_shape_destroy(w, made));
    th_assert_ok(tb_shape_destroy(w, ball));
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dumbbell_inertia),
        cmocka_unit_test(test_unequal_densities),
        cmocka_unit_test(test_table_settles_on_legs),
        cmocka_unit_test(test_bricks_stack),
        cmocka_unit_test(test_table_on_mesh),
        cmocka_unit_test(test_broadphases_agree),
        cmocka_unit_test(test_split_overflow_grows),
        cmocka_unit_test(test_isap_keeps_compound_pairs_once),
        cmocka_unit_test(test_bad_compounds_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
