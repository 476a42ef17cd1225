/* The golden determinism hash: a mixed pile (boxes, spheres, hulls, capsules, cylinders and
 * cones dropped on a plane) stepped 90 times must end in the very state recorded for this
 * device and driver in tests/golden.txt: a hash of every body's pose and velocities, bit
 * for bit. Any change to what the step computes changes it; a change meant to do so
 * records the new hash with TUMBLE_GOLDEN_UPDATE=1 (and says why in its commit). A device
 * with no line is reported and skipped: its hash is printed to add. */
#include "harness.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BODIES 160
#define STEPS 90
#define GOLDEN TB_SOURCE_DIR "/tests/golden.txt"

static uint64_t fnv1a(uint64_t h, const void* data, size_t size)
{
    const unsigned char* p = data;
    for (size_t i = 0; i < size; i++) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

static uint64_t pile_hash(tb_world* w)
{
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shapes[6] = { th_box(w, th_v3(0.3f, 0.2f, 0.25f)), th_sphere(w, 0.25f),
                              th_rock(w) };
    th_assert_ok(tb_shape_create_capsule(w, &sd, 0.15f, 0.2f, &shapes[3]));
    th_assert_ok(tb_shape_create_cylinder(w, &sd, 0.25f, 0.2f, &shapes[4]));
    th_assert_ok(tb_shape_create_cone(w, &sd, 0.25f, 0.3f, &shapes[5]));
    th_rng rng = th_rng_seed(2026);
    tb_body_id ids[BODIES];
    for (int i = 0; i < BODIES; i++) {
        tb_body_def d = th_dynamic_def(shapes[i % 6], th_v3(th_rng_range(&rng, -2, 2),
                                       0.4f + 0.5f * (float)(i / 16), th_rng_range(&rng, -2, 2)));
        d.rotation = th_rng_quat(&rng);
        ids[i] = th_body(w, &d);
    }
    th_assert_ok(tb_world_step_n(w, 1.0f / 60.0f, STEPS));
    uint64_t h = 0xcbf29ce484222325ull;
    for (int i = 0; i < BODIES; i++) {
        tb_vec3 p, v, av;
        tb_quat q;
        th_read_pose(w, ids[i], &p, &q);
        th_assert_ok(tb_body_get_velocity(w, ids[i], &v, &av));
        h = fnv1a(h, &p, sizeof p);
        h = fnv1a(h, &q, sizeof q);
        h = fnv1a(h, &v, sizeof v);
        h = fnv1a(h, &av, sizeof av);
    }
    return h;
}

/* This device's key in golden.txt: its name and driver, tabs and line ends taken out. */
static void device_key(tb_world* w, char* key, size_t size)
{
    tb_device_info info;
    th_assert_ok(tb_world_device_info(w, &info));
    snprintf(key, size, "%s | %s", info.name, info.driver);
    for (char* c = key; *c; c++)
        if (*c == '\t' || *c == '\n' || *c == '\r') *c = ' ';
}

/* The recorded hash for `key`, or 0 when golden.txt has no line for it. */
static uint64_t recorded_hash(const char* key)
{
    FILE* f = fopen(GOLDEN, "r");
    assert_non_null(f);
    char line[1024];
    uint64_t found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        char* tab = strchr(line, '\t');
        if (line[0] == '#' || !tab) continue;
        line[strcspn(line, "\r\n")] = 0;
        if (strcmp(tab + 1, key) == 0) found = strtoull(line, NULL, 16);
    }
    fclose(f);
    return found;
}

/* golden.txt with this device's line set to `hash` (other lines kept). */
static void record_hash(const char* key, uint64_t hash)
{
    FILE* f = fopen(GOLDEN, "r");
    assert_non_null(f);
    static char kept[1 << 16];
    size_t used = 0;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        char* tab = strchr(line, '\t');
        char bare[1024];
        snprintf(bare, sizeof bare, "%s", tab ? tab + 1 : "");
        bare[strcspn(bare, "\r\n")] = 0;
        if (line[0] != '#' && tab && strcmp(bare, key) == 0) continue;
        used += (size_t)snprintf(kept + used, sizeof kept - used, "%s", line);
    }
    fclose(f);
    f = fopen(GOLDEN, "w");
    assert_non_null(f);
    fprintf(f, "%s%016llx\t%s\n", kept, (unsigned long long)hash, key);
    fclose(f);
}

static void test_golden_hash(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    char key[600];
    device_key(w, key, sizeof key);
    uint64_t hash = pile_hash(w);
    th_world_destroy(w);
    if (getenv("TUMBLE_GOLDEN_UPDATE")) {
        record_hash(key, hash);
        print_message("  recorded %016llx for %s\n", (unsigned long long)hash, key);
        return;
    }
    uint64_t want = recorded_hash(key);
    if (!want) {
        print_message("  no golden hash for %s: this run's is %016llx "
                      "(TUMBLE_GOLDEN_UPDATE=1 records it)\n", key, (unsigned long long)hash);
        skip();
    }
    if (hash != want)
        fail_msg("the pile ended in another state: hash %016llx, recorded %016llx for %s",
                 (unsigned long long)hash, (unsigned long long)want, key);
}

/* The same scene twice in one process ends the same, whatever golden.txt says. */
static void test_same_scene_twice(void** state)
{
    (void)state;
    tb_world* a = th_world_create(NULL);
    uint64_t first = pile_hash(a);
    th_world_destroy(a);
    tb_world* b = th_world_create(NULL);
    uint64_t second = pile_hash(b);
    th_world_destroy(b);
    assert_true(first == second);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_hash),
        cmocka_unit_test(test_same_scene_twice),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
