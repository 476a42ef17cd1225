/* Stacks and pyramids stand, piles settle (DESIGN.md §7). Boxes placed at rest, exactly
 * touching, on a ground plane must stay where they are. The scenes are the bench's
 * (tools/scenes/stacks.c, hulls.c), so the bench's `drift` and these tests measure the same
 * thing; here every step is read back, so a box that sways and comes back still fails.
 *
 * World settings are the defaults (the block solver, 60 steps per second): a stack that
 * stands only with more iterations or a smaller step does not stand for a user who leaves
 * them alone. Measured on lavapipe: the column's top box moves 2.2 mm at most, the
 * pyramid's apex 0.2 mm, the 1,000 hulls overlap 0.9 mm at most after 300 steps. (With the
 * soft step the column's top settled 6.8 mm into its contacts, the apex 1.9 mm; the
 * split-impulse solver before it let the column rock by 2.8 cm.)
 */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

#define STEPS 1000

typedef struct run {
    double max_drift;        /* largest displacement of any box at any step, m */
    double max_top_drift;    /* the same for the last box of the scene (top / apex) */
    uint32_t worst_box, worst_step;
    uint32_t nan;            /* boxes with a non-finite pose at the end */
} run;

static double distance(tb_vec3 a, tb_vec3 b)
{
    double dx = (double)a.x - b.x, dy = (double)a.y - b.y, dz = (double)a.z - b.z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Every check of a scene, printed. */
static void print_checks(const scene_checks* c)
{
    for (uint32_t i = 0; i < c->count; i++)
        print_message("  %s %g\n", c->items[i].key, c->items[i].value);
}

/* The value of check `key`; fails the test when the scene reported none. */
static double check_of(const scene_checks* c, const char* key)
{
    for (uint32_t i = 0; i < c->count; i++)
        if (!strcmp(c->items[i].key, key)) return c->items[i].value;
    fail_msg("the scene reported no check '%s'", key);
    return NAN;
}

/* Builds scene `name` with n boxes, steps it STEPS times at its dt with default settings,
 * and follows every box's displacement from its start after each step. A NaN pose counts
 * as an infinite displacement, so it cannot hide behind a comparison that is false. */
static run run_scene(const char* name, uint32_t n, uint32_t expect_boxes)
{
    tb_world* w = th_world_create(NULL);
    const scene* sc = scene_find(name);
    assert_non_null(sc);
    scene_params params = { n, 1 };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    uint32_t count;
    const tb_body_id* ids = scene_body_ids(inst, &count);
    assert_int_equal(count, expect_boxes);
    tb_vec3* x0 = malloc(count * sizeof *x0);
    tb_vec3* pos = malloc(count * sizeof *pos);
    tb_quat* rot = malloc(count * sizeof *rot);
    assert_true(x0 && pos && rot);
    th_assert_ok(tb_world_read_transforms(w, ids, count, x0, rot));
    run r = { 0 };
    for (uint32_t step = 1; step <= STEPS; step++) {
        th_assert_ok(tb_world_step(w, sc->dt));
        th_assert_ok(tb_world_read_transforms(w, ids, count, pos, rot));
        for (uint32_t i = 0; i < count; i++) {
            double d = distance(pos[i], x0[i]);
            if (isnan(d) || !isfinite(rot[i].w)) d = INFINITY;
            if (d > r.max_drift) { r.max_drift = d; r.worst_box = i; r.worst_step = step; }
            if (i == count - 1 && d > r.max_top_drift) r.max_top_drift = d;
        }
    }
    scene_checks checks = { 0 };
    th_assert_ok(sc->check(w, inst, STEPS, sc->dt, &checks));
    print_checks(&checks);
    r.nan = (uint32_t)check_of(&checks, "nan");
    print_message("  %s: max drift %.4f m (box %u, step %u), top box %.4f m\n", name,
                  r.max_drift, r.worst_box, r.worst_step, r.max_top_drift);
    free(x0);
    free(pos);
    free(rot);
    sc->destroy(inst);
    th_world_destroy(w);
    return r;
}

/* 10 unit boxes in a column: the top box stays within 1 cm of its start at every step. */
static void test_stack_of_10_stands(void** state)
{
    (void)state;
    run r = run_scene("stack", 10, 10);
    assert_int_equal(r.nan, 0);
    assert_true(r.max_top_drift < 0.01);
    /* The top box carries the error of every contact below it, so no box moves more. */
    assert_true(r.max_drift < 0.01);
}

/* A pyramid of base 10 (55 unit boxes): every box stays within 1 cm of its start at every
 * step. 1 cm is 1 % of a box: a pyramid that settles a few mm into its soft contacts passes,
 * one that rocks out of its plane (as it did with contacts at a quarter of the substep
 * rate, 2.6 cm) or slides apart fails long before it would be visible. */
static void test_pyramid_of_55_stands(void** state)
{
    (void)state;
    run r = run_scene("pyramid", 55, 55);
    assert_int_equal(r.nan, 0);
    assert_true(r.max_drift < 0.01);
}

/* Scene `name` with n bodies (its seed 1) after `steps` steps at its dt, default settings:
 * its checks, printed. */
static scene_checks checks_after(const char* name, uint32_t n, uint32_t steps)
{
    tb_world* w = th_world_create(NULL);
    const scene* sc = scene_find(name);
    assert_non_null(sc);
    scene_params params = { n, 1 };
    scene_instance* inst = NULL;
    th_assert_ok(sc->build(w, &params, &inst));
    th_assert_ok(tb_world_step_n(w, sc->dt, steps));
    scene_checks checks = { 0 };
    th_assert_ok(sc->check(w, inst, steps, sc->dt, &checks));
    print_checks(&checks);
    sc->destroy(inst);
    th_world_destroy(w);
    return checks;
}

/* 1000 random convex hulls poured into the walled container settle within 300 steps (5 s):
 * no NaN, none escaped, nearly all at rest, and no two overlap by 1 cm or more. */
static void test_hull_pour_settles(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the hull pour", "128")) skip();
    scene_checks c = checks_after("hulls", 1000, 300);
    assert_true(check_of(&c, "nan") == 0);
    assert_true(check_of(&c, "escaped") == 0);
    assert_true(check_of(&c, "max_penetration") < 0.01);
    assert_true(check_of(&c, "resting") >= 0.98);
}

/* The deep pile at 4,000 boxes: 16 layers fall into walls 10 m high and land in columns;
 * after 600 steps (10 s) none has escaped, none is NaN, at least 99 % are at rest, nothing
 * overlaps by 1 cm, and the columns still stand 14 m or more of their 16. */
static void test_deep_pile_stands(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the deep pile", "256")) skip();
    scene_checks c = checks_after("deep", 4000, 600);
    assert_true(check_of(&c, "nan") == 0);
    assert_true(check_of(&c, "escaped") == 0);
    assert_true(check_of(&c, "resting") >= 0.99);
    assert_true(check_of(&c, "max_penetration") < 0.01);
    assert_true(check_of(&c, "layers") == 16);
    assert_true(check_of(&c, "column_min") >= 14.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stack_of_10_stands),
        cmocka_unit_test(test_pyramid_of_55_stands),
        cmocka_unit_test(test_hull_pour_settles),
        cmocka_unit_test(test_deep_pile_stands),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
