/* Worlds at scale: a million bodies added and read back in one call each, and more contact
 * pairs than one storage-buffer binding can hold (lavapipe's maxStorageBufferRange is
 * 128 MiB: 720k manifolds of 192 bytes pass it; the contact arrays are reached by address). */
#include "harness.h"

#include <math.h>
#include <stdlib.h>

#include "world/world.h"

/* A million spheres on a 100^3 lattice in free fall: created by one tb_body_create_many,
 * stepped, and read back by one tb_world_read_transforms. Every body falls alike. */
static void test_million_bodies(void** state)
{
    (void)state;
    enum { SIDE = 100, N = SIDE * SIDE * SIDE };
    tb_world_def def = tb_default_world_def();
    def.initial_body_capacity = 1024;          /* growth to a million on the way */
    tb_world* w = th_world_create(&def);
    tb_shape_id ball = th_sphere(w, 0.25f);
    tb_body_def* defs = malloc(N * sizeof *defs);
    tb_body_id* ids = malloc(N * sizeof *ids);
    tb_vec3* pos = malloc(N * sizeof *pos);
    tb_quat* rot = malloc(N * sizeof *rot);
    assert_true(defs && ids && pos && rot);
    for (uint32_t i = 0; i < N; i++) {
        tb_vec3 p = th_v3((float)(i % SIDE), (float)(i / SIDE % SIDE), (float)(i / (SIDE * SIDE)));
        defs[i] = th_dynamic_def(ball, p);
    }
    th_assert_ok(tb_body_create_many(w, defs, N, ids));
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    tb_world_stats st = th_stats(w);
    assert_int_equal(st.body_count, N);
    assert_int_equal(st.pair_count, 0);
    th_assert_ok(tb_world_read_transforms(w, ids, N, pos, rot));
    float drop = defs[0].position.y - pos[0].y;
    assert_true(drop > 0.0f);
    for (uint32_t i = 0; i < N; i++) {
        tb_vec3 p0 = defs[i].position;
        if (fabsf(pos[i].x - p0.x) > 1e-5f || fabsf(pos[i].z - p0.z) > 1e-5f ||
            fabsf(p0.y - pos[i].y - drop) > 1e-4f || fabsf(rot[i].w - 1.0f) > 1e-6f)
            fail_msg("body %u at (%g, %g, %g), started at (%g, %g, %g), others fell %g", i,
                     pos[i].x, pos[i].y, pos[i].z, p0.x, p0.y, p0.z, drop);
    }
    free(defs);
    free(ids);
    free(pos);
    free(rot);
    th_world_destroy(w);
}

/* 1200 parallel rods along the space diagonal, 5 cm apart: every two boxes overlap (719400
 * pairs) while no two rods touch. The manifolds of all those pairs pass one binding's range
 * on lavapipe; the step must still find them all and give no contact. */
static void test_pairs_beyond_one_binding(void** state)
{
    (void)state;
    enum { RODS = 1200 };
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&def);
    tb_shape_id rod = th_box(w, th_v3(50.0f, 0.005f, 0.005f));
    /* Turn the x axis onto (1, 1, 1) / sqrt 3: about (-1, 1, 0) / sqrt 2 by acos(1 / sqrt 3). */
    tb_quat diagonal = th_quat_axis_angle(th_v3(0, -1, 1), acos(1.0 / sqrt(3.0)));
    for (uint32_t i = 0; i < RODS; i++) {
        float s = 0.05f * (float)i / sqrtf(2.0f);
        tb_body_def d = th_dynamic_def(rod, th_v3(s, -s, 0));   /* across the diagonal */
        d.rotation = diagonal;
        th_body(w, &d);
    }
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    tb_world_stats st = th_stats(w);
    assert_int_equal(st.pair_count, RODS * (RODS - 1) / 2);
    assert_int_equal(st.contact_count, 0);
    VkDeviceSize manifold_bytes = (VkDeviceSize)st.pair_capacity * sizeof(tb_gpu_manifold);
    if (manifold_bytes <= w->gpu.props.limits.maxStorageBufferRange)
        print_message("note: this device's binding range (%llu bytes) holds every manifold\n",
                      (unsigned long long)w->gpu.props.limits.maxStorageBufferRange);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_million_bodies),
        cmocka_unit_test(test_pairs_beyond_one_binding),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
