/* Structures of many joints (lavapipe, validation on), from the bench's scenes: a hanging
 * net of spheres on ball joints and a plank bridge on hinges under a dropped load, whose
 * joints hold more conditions than their bodies have freedoms, stay still and closed over
 * hundreds of steps (both once shook themselves apart: a joint starts its step with a
 * smaller share of last step's multipliers and stiffness than a contact, block/joint_start),
 * the net sweeps in the two colours its joint graph needs, and the bridge stands the same
 * in a GPU's lanes a body. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

/* Scene `name` with n bodies run `steps` steps at its dt; its checks to *out. */
static void run_scene(const char* name, uint32_t n, uint32_t steps, scene_checks* out)
{
    const scene* sc = scene_find(name);
    assert_non_null(sc);
    tb_world* w = th_world_create(NULL);
    scene_params params = { n, 1 };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    th_assert_ok(tb_world_step_n(w, sc->dt, steps));
    th_assert_ok(sc->check(w, inst, steps, sc->dt, out));
    sc->destroy(inst);
    th_world_destroy(w);
}

static double check_of(const scene_checks* c, const char* key)
{
    for (uint32_t i = 0; i < c->count; i++)
        if (strcmp(c->items[i].key, key) == 0) return c->items[i].value;
    fail_msg("the scene reports no %s", key);
    return 0;
}

/* A 10 x 10 net (90 spheres below a static row) hangs still for 180 steps: no joint opens
 * by 0.1 mm and its centre sags less than 1 mm (it opened by 9 mm at step 100 and 13 cm at
 * step 150 before). */
static void test_net_hangs_still(void** state)
{
    (void)state;
    scene_checks c;
    run_scene("joint_grid", 100, 180, &c);
    double gap = check_of(&c, "max_gap"), sag = check_of(&c, "sag");
    print_message("  net 10 x 10, 180 steps: largest gap %.4f mm, centre sagged %.4f mm\n",
                  1000 * gap, 1000 * sag);
    assert_true(check_of(&c, "nan") == 0);
    assert_true(gap < 1e-4);
    assert_true(sag > -1e-3 && sag < 1e-3);
}

/* The 10 x 10 net, two-colourable, sweeps in two colours: the host's breadth-first colouring
 * of the joint graph (src/world/joint_ranks.c) orders the GPU's colouring. */
static void test_net_colours_in_two(void** state)
{
    (void)state;
    const scene* sc = scene_find("joint_grid");
    assert_non_null(sc);
    tb_world* w = th_world_create(NULL);
    scene_params params = { 100, 1 };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    th_assert_ok(tb_world_step_n(w, sc->dt, 10));
    tb_world_stats st;
    th_assert_ok(tb_world_get_stats(w, &st));
    print_message("  net 10 x 10: %u colours\n", st.colour_count);
    assert_int_equal(st.colour_count, 2);
    sc->destroy(inst);
    th_world_destroy(w);
}

/* A bridge of 40 planks takes a load 10 times a plank dropped from 1 m and carries it for
 * 240 steps: its hinges stay closed within 2 mm and aligned within 0.01 rad, and it sags
 * no further than 0.5 m below where it started (it twisted 0.3 rad by step 200 before). */
static void test_bridge_carries_a_load(void** state)
{
    (void)state;
    scene_checks c;
    run_scene("bridge", 40, 240, &c);
    double gap = check_of(&c, "max_gap"), twist = check_of(&c, "max_twist");
    double sag = check_of(&c, "sag"), start = check_of(&c, "sag_start");
    print_message("  bridge of 40 planks, 240 steps: largest gap %.3f mm, twist %.5f rad, sag "
                  "%.3f m (%.3f m at the start)\n", 1000 * gap, twist, sag, start);
    assert_true(check_of(&c, "nan") == 0 && check_of(&c, "load_fell") == 0);
    assert_true(gap < 2e-3);
    assert_true(twist < 0.01);
    assert_true(sag > start - 0.5 && sag < start + 0.5);
}

/* The bridge again with a GPU's lanes (TUMBLE_GPU_LANES=1: 8 lanes a body share its entries
 * and add up their Newton blocks by shuffles, which lavapipe otherwise solves one lane a
 * body): the same bridge, to rounding, as one lane a body. */
static void test_bridge_in_gpu_lanes(void** state)
{
    (void)state;
    scene_checks one, eight;
    run_scene("bridge", 40, 240, &one);
    setenv("TUMBLE_GPU_LANES", "1", 1);
    run_scene("bridge", 40, 240, &eight);
    unsetenv("TUMBLE_GPU_LANES");
    double gap = check_of(&eight, "max_gap"), sag = check_of(&eight, "sag");
    print_message("  bridge in 8 lanes a body: largest gap %.3f mm (%.3f in one), sag %.4f m "
                  "(%.4f)\n", 1000 * gap, 1000 * check_of(&one, "max_gap"), sag,
                  check_of(&one, "sag"));
    assert_true(check_of(&eight, "nan") == 0 && check_of(&eight, "load_fell") == 0);
    assert_true(gap < 2e-3 && check_of(&eight, "max_twist") < 0.01);
    assert_true(fabs(sag - check_of(&one, "sag")) < 1e-3);
    assert_true(fabs(gap - check_of(&one, "max_gap")) < 1e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_net_hangs_still),
        cmocka_unit_test(test_net_colours_in_two),
        cmocka_unit_test(test_bridge_carries_a_load),
        cmocka_unit_test(test_bridge_in_gpu_lanes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
