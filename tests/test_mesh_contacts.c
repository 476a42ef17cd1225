/* Triangle meshes and heightfields in the step (GPU, lavapipe): spheres, boxes and hulls
 * resting on a quad of two triangles and on a fine flat grid without drift, a box sliding
 * across the grid's seams without hopping, hard landings on hills, a sphere rolling down a
 * heightfield as down an inclined plane, holes, every broadphase splitting the same body
 * pairs into the same triangle pairs, and bad meshes and heightfields refused. */
#include "harness.h"

#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)

typedef struct grid_mesh {
    tb_vec3* vertices;
    uint32_t* indices;
    uint32_t vertex_count, triangle_count;
} grid_mesh;

/* A flat square of cells x cells quads (two triangles each, sharing vertices) of side
 * `size` centred on the origin at y = 0, facing up; every other quad split along its other
 * diagonal, so seams run every way. */
static grid_mesh flat_grid(uint32_t cells, float size)
{
    uint32_t side = cells + 1;
    grid_mesh m = { malloc(sizeof(tb_vec3) * side * side),
                    malloc(6 * sizeof(uint32_t) * cells * cells), side * side,
                    2 * cells * cells };
    assert_non_null(m.vertices);
    assert_non_null(m.indices);
    for (uint32_t z = 0; z < side; z++)
        for (uint32_t x = 0; x < side; x++)
            m.vertices[z * side + x] = th_v3(size * ((float)x / cells - 0.5f), 0.0f,
                                            size * ((float)z / cells - 0.5f));
    uint32_t* t = m.indices;
    for (uint32_t z = 0; z < cells; z++) {
        for (uint32_t x = 0; x < cells; x++) {
            uint32_t a = z * side + x, b = a + 1, c = a + side, d = c + 1;
            /* Counter-clockwise seen from +y: a (x, z), c (x, z + 1), b (x + 1, z). */
            if ((x + z) % 2 == 0) {
                t[0] = a; t[1] = c; t[2] = b;
                t[3] = b; t[4] = c; t[5] = d;
            } else {
                t[0] = a; t[1] = c; t[2] = d;
                t[3] = a; t[4] = d; t[5] = b;
            }
            t += 6;
        }
    }
    return m;
}

static void grid_free(grid_mesh* m)
{
    free(m->vertices);
    free(m->indices);
}

static tb_body_id static_mesh(tb_world* w, const grid_mesh* m, float friction)
{
    tb_shape_def sd = tb_default_shape_def();
    sd.friction = friction;
    tb_shape_id shape;
    th_assert_ok(tb_shape_create_mesh(w, &sd, m->vertices, m->vertex_count, m->indices,
                                      m->triangle_count, &shape));
    tb_body_def d = th_static_def(shape, th_v3(0, 0, 0));
    return th_body(w, &d);
}

static double distance(tb_vec3 a, tb_vec3 b)
{
    double x = a.x - b.x, y = a.y - b.y, z = a.z - b.z;
    return sqrt(x * x + y * y + z * z);
}

/* A body placed resting at `start` moves less than 1 mm in 600 steps. */
static void assert_rests(tb_world* w, tb_body_id body, tb_vec3 start)
{
    for (int i = 0; i < 6; i++) {
        th_assert_ok(tb_world_step_n(w, DT, 100));
        tb_vec3 p;
        th_read_pose(w, body, &p, NULL);
        if (!(distance(p, start) < 1e-3))
            fail_msg("moved %.3g m from its start after %d steps (at %g %g %g)",
                     distance(p, start), 100 * (i + 1), p.x, p.y, p.z);
    }
}

static void rests_on(uint32_t cells, float size, int kind)
{
    tb_world* w = th_world_create(NULL);
    grid_mesh m = flat_grid(cells, size);
    static_mesh(w, &m, 0.6f);
    tb_shape_id shape = kind == 0 ? th_sphere(w, 0.5f)
                                  : (kind == 1 ? th_box(w, th_v3(0.5f, 0.5f, 0.5f)) : th_rock(w));
    tb_vec3 start = th_v3(0.13f, 0.5f, -0.21f);
    if (kind == 2) {
        /* The rock's lowest point: its hull vertices in its body frame. */
        tb_vec3 v[16];
        uint32_t n = 0;
        th_assert_ok(tb_shape_get_hull_vertices(w, shape, v, 16, &n));
        float lowest = 0;
        for (uint32_t i = 0; i < n; i++) lowest = fminf(lowest, v[i].y);
        start.y = -lowest;
    }
    tb_body_def d = th_dynamic_def(shape, start);
    tb_body_id body = th_body(w, &d);
    assert_rests(w, body, start);
    tb_world_stats s = th_stats(w);
    assert_true(s.contact_count >= 1);
    grid_free(&m);
    th_world_destroy(w);
}

static void test_sphere_rests_on_quad(void** state)
{
    (void)state;
    rests_on(1, 4.0f, 0);
}

static void test_box_rests_on_quad(void** state)
{
    (void)state;
    rests_on(1, 4.0f, 1);
}

static void test_hull_rests_on_quad(void** state)
{
    (void)state;
    rests_on(1, 4.0f, 2);
}

/* 200 x 200 quads of 10 cm: a unit box covers about 200 triangles. */
static void test_sphere_rests_on_fine_grid(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the sphere on the fine grid", "128")) skip();
    rests_on(200, 20.0f, 0);
}

static void test_box_rests_on_fine_grid(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the box on the fine grid", "256")) skip();
    rests_on(200, 20.0f, 1);
}

/* A box slides without friction across the fine grid at 2 m/s, across seams of every
 * direction: its height stays within 1 mm and it keeps its speed (no seam catches it). */
static void test_box_slides_over_seams(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    grid_mesh m = flat_grid(200, 20.0f);
    static_mesh(w, &m, 0.0f);
    tb_vec3 start = th_v3(-5.0f, 0.5f, -1.3f);
    tb_body_def d = th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), start);
    d.linear_velocity = th_v3(1.9f, 0.0f, 0.6f);
    tb_body_id box = th_body(w, &d);
    double speed = sqrt(1.9 * 1.9 + 0.6 * 0.6);
    for (int i = 0; i < 240; i++) {
        th_assert_ok(tb_world_step(w, DT));
        tb_vec3 p, v, av;
        th_read_pose(w, box, &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, box, &v, &av));
        if (!(fabs(p.y - 0.5) < 1e-3))
            fail_msg("step %d: height %.5f m, not within 1 mm of 0.5", i, p.y);
        double s = sqrt((double)v.x * v.x + (double)v.z * v.z);
        if (!(fabs(s - speed) < 0.01 * speed))
            fail_msg("step %d: speed %.4f m/s, not %.4f", i, s, speed);
    }
    tb_vec3 p;
    th_read_pose(w, box, &p, NULL);
    assert_true(p.x > 2.0f);   /* it went across many cells */
    grid_free(&m);
    th_world_destroy(w);
}

/* ---- hard landings on rolling terrain ------------------------------------------------ */

#define HILLS_HALF 37.0f

static float hills_height(float x, float z)
{
    float u = x / HILLS_HALF, v = z / HILLS_HALF;
    return 0.1f * HILLS_HALF * (u * u + v * v) +
           0.5f * sinf(2.0f * (float)M_PI * x / 12.0f) * sinf(2.0f * (float)M_PI * z / 12.0f);
}

/* A bowl of hills over [-37, 37]^2 m in 256 x 256 quads (cells of 0.29 m). */
static grid_mesh rolling_terrain(void)
{
    grid_mesh m = flat_grid(256, 2.0f * HILLS_HALF);
    for (uint32_t i = 0; i < m.vertex_count; i++)
        m.vertices[i].y = hills_height(m.vertices[i].x, m.vertices[i].z);
    return m;
}

/* A hull of 8 to 20 points on an ellipsoid of semi-axes 0.13 to 0.3 m: slabs, rods, rocks. */
static tb_shape_id random_hull(tb_world* w, th_rng* rng)
{
    tb_vec3 points[20];
    uint32_t count = 8 + th_rng_u32(rng) % 13;
    tb_vec3 axes = th_v3(th_rng_range(rng, 0.13f, 0.3f), th_rng_range(rng, 0.13f, 0.3f),
                         th_rng_range(rng, 0.13f, 0.3f));
    for (uint32_t i = 0; i < count; i++) {
        tb_quat q = th_rng_quat(rng);   /* a random direction: a rotated axis */
        double d[3] = { 1, 0, 0 }, r[3];
        th_quat_rotate(q, d, r);
        points[i] = th_v3((float)r[0] * axes.x, (float)r[1] * axes.y, (float)r[2] * axes.z);
    }
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shape;
    th_assert_ok(tb_shape_create_hull(w, &sd, points, count, &shape));
    return shape;
}

/* 400 hulls, boxes and spheres dropped from 9 m at random turns onto hills: they land at
 * up to 13 m/s, faster than a slab is thick per step, and spin on landing; none may end
 * below the surface (a slab landing on one end used to spin its other end through). */
static void test_hard_landings_stay_on_terrain(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the hard landings", "128")) skip();
    tb_world* w = th_world_create(NULL);
    grid_mesh m = rolling_terrain();
    static_mesh(w, &m, 0.6f);
    th_rng rng = th_rng_seed(11);
    tb_shape_id shapes[8];
    for (int k = 0; k < 6; k++) shapes[k] = random_hull(w, &rng);
    shapes[6] = th_box(w, th_v3(0.2f, 0.1f, 0.3f));
    shapes[7] = th_sphere(w, 0.15f);
    enum { N = 400, ACROSS = 20 };
    tb_body_def defs[N];
    for (int i = 0; i < N; i++) {
        float x = -10.0f + 1.3f * (i % ACROSS), z = -8.0f + 1.3f * (i / ACROSS);
        defs[i] = th_dynamic_def(shapes[i % 8], th_v3(x, hills_height(x, z) + 9.0f, z));
        defs[i].rotation = th_rng_quat(&rng);
    }
    tb_body_id ids[N];
    th_assert_ok(tb_body_create_many(w, defs, N, ids));
    static tb_vec3 p[N];
    for (int s = 0; s < 4; s++) {
        th_assert_ok(tb_world_step_n(w, DT, 30));
        th_assert_ok(tb_world_read_transforms(w, ids, N, p, NULL));
        for (int i = 0; i < N; i++)
            if (!(p[i].y > hills_height(p[i].x, p[i].z) - 0.05f))
                fail_msg("body %d (shape %d) at step %d: %.3f m, the surface %.3f m", i, i % 8,
                         30 * (s + 1), p[i].y, hills_height(p[i].x, p[i].z));
    }
    grid_free(&m);
    th_world_destroy(w);
}

/* ---- heightfields ------------------------------------------------------------------------ */

static tb_body_id static_heightfield(tb_world* w, const float* heights, uint32_t nx, uint32_t nz,
                                     float cell, const uint8_t* holes, tb_quat rotation)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shape;
    th_assert_ok(tb_shape_create_heightfield(w, &sd, heights, nx, nz, cell, cell, holes, &shape));
    tb_body_def d = th_static_def(shape, th_v3(0, 0, 0));
    d.rotation = rotation;
    return th_body(w, &d);
}

/* How far a sphere of radius 0.5 placed on the ground 2 m up the slope of a 20 degree
 * incline rolls in 90 steps: on a heightfield whose heights make the slope (ramp != 0), or
 * on a plane turned by the same angle. */
static double roll_distance(int ramp)
{
    const double angle = 20.0 * M_PI / 180.0;
    tb_world* w = th_world_create(NULL);
    enum { NX = 41, NZ = 9 };
    const float cell = 0.5f;
    tb_vec3 down = th_v3((float)cos(angle), (float)-sin(angle), 0);   /* along the slope */
    tb_vec3 up = th_v3((float)sin(angle), (float)cos(angle), 0);      /* its normal */
    if (ramp) {
        static float heights[NX * NZ];
        for (int k = 0; k < NZ; k++)
            for (int i = 0; i < NX; i++)
                heights[k * NX + i] = -(float)tan(angle) * cell * (float)(i - (NX - 1) / 2);
        static_heightfield(w, heights, NX, NZ, cell, NULL, th_q(0, 0, 0, 1));
    } else {
        tb_shape_def sd = tb_default_shape_def();
        tb_shape_id plane;
        th_assert_ok(tb_shape_create_plane(w, &sd, up, 0.0f, &plane));
        tb_body_def d = th_static_def(plane, th_v3(0, 0, 0));
        th_body(w, &d);
    }
    /* 4 m up the slope from the middle, resting on it. */
    tb_vec3 start = th_v3(-4.0f * down.x + 0.5f * up.x, -4.0f * down.y + 0.5f * up.y, 0);
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.5f), start);
    tb_body_id ball = th_body(w, &d);
    th_assert_ok(tb_world_step_n(w, DT, 90));
    tb_vec3 p;
    th_read_pose(w, ball, &p, NULL);
    th_world_destroy(w);
    return (p.x - start.x) * down.x + (p.y - start.y) * down.y;
}

/* Rolling without slipping, a sphere runs down at 5/7 g sin(angle) on both. */
static void test_sphere_rolls_down_heightfield_as_on_plane(void** state)
{
    (void)state;
    double on_field = roll_distance(1), on_plane = roll_distance(0);
    double t = 90 * (double)DT, analytic = 0.5 * 5.0 / 7.0 * 9.81 * sin(20.0 * M_PI / 180.0) * t * t;
    print_message("rolled %.4f m on the heightfield, %.4f m on the plane, %.4f m analytic\n",
                  on_field, on_plane, analytic);
    th_assert_near(on_plane, analytic, 0, 0.03);
    th_assert_near(on_field, on_plane, 0, 0.02);
}

/* A box rests on a flat heightfield; a sphere over a hole falls through it while one beside
 * it stays. */
static void test_heightfield_rest_and_holes(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    enum { N = 17 };
    static float heights[N * N];
    static uint8_t holes[(N - 1) * (N - 1)];
    memset(heights, 0, sizeof heights);
    memset(holes, 0, sizeof holes);
    holes[8 * (N - 1) + 8] = 1;   /* the cell just past the centre, x and z in [0, 1] */
    static_heightfield(w, heights, N, N, 1.0f, holes, th_q(0, 0, 0, 1));
    tb_body_def d = th_dynamic_def(th_sphere(w, 0.3f), th_v3(0.5f, 0.3f, 0.5f));
    tb_body_id over_hole = th_body(w, &d);
    d = th_dynamic_def(th_sphere(w, 0.3f), th_v3(-3.5f, 0.3f, 0.5f));
    tb_body_id beside = th_body(w, &d);
    d = th_dynamic_def(th_box(w, th_v3(0.4f, 0.4f, 0.4f)), th_v3(3.3f, 0.4f, -2.6f));
    tb_body_id box = th_body(w, &d);
    th_assert_ok(tb_world_step_n(w, DT, 120));
    tb_vec3 p;
    th_read_pose(w, over_hole, &p, NULL);
    assert_true(p.y < -1.0f);
    th_read_pose(w, beside, &p, NULL);
    assert_true(distance(p, th_v3(-3.5f, 0.3f, 0.5f)) < 1e-3);
    th_read_pose(w, box, &p, NULL);
    assert_true(distance(p, th_v3(3.3f, 0.4f, -2.6f)) < 1e-3);
    th_world_destroy(w);
}

static void test_bad_heightfields_refused(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_shape_def sd = tb_default_shape_def();
    float h[9] = { 0 };
    uint8_t all_holes[4] = { 1, 1, 1, 1 };
    tb_shape_id shape, ids[4];
    uint32_t before = tb_world_shape_ids(w, ids, 4);
    th_assert_result(tb_shape_create_heightfield(w, &sd, NULL, 3, 3, 1, 1, NULL, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_heightfield(w, &sd, h, 1, 9, 1, 1, NULL, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_heightfield(w, &sd, h, 3, 3, 0, 1, NULL, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_heightfield(w, &sd, h, 3, 3, 1, NAN, NULL, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_heightfield(w, &sd, h, 3, 3, 1, 1, all_holes, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    h[4] = INFINITY;
    th_assert_result(tb_shape_create_heightfield(w, &sd, h, 3, 3, 1, 1, NULL, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "height"));
    assert_int_equal(tb_world_shape_ids(w, ids, 4), before);
    h[4] = 0;
    th_assert_ok(tb_shape_create_heightfield(w, &sd, h, 3, 3, 1, 1, NULL, &shape));
    tb_body_def d = th_dynamic_def(shape, th_v3(0, 1, 0));
    tb_body_id body;
    th_assert_result(tb_body_create_many(w, &d, 1, &body), TB_ERROR_INVALID_ARGUMENT);
    th_world_destroy(w);
}

/* Every broadphase gives the same contacts: a few spheres and boxes on a coarse grid. */
static void test_broadphases_agree(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the broadphases' agreement", "256")) skip();
    const tb_broadphase kinds[] = { TB_BROADPHASE_GRID, TB_BROADPHASE_SAP, TB_BROADPHASE_LBVH,
                                    TB_BROADPHASE_ISAP };
    uint32_t counts[4];
    for (int k = 0; k < 4; k++) {
        tb_world_def def = tb_default_world_def();
        def.broadphase = kinds[k];
        tb_world* w = th_world_create(&def);
        grid_mesh m = flat_grid(8, 8.0f);
        static_mesh(w, &m, 0.6f);
        for (int i = 0; i < 6; i++) {
            tb_shape_id s = i % 2 ? th_sphere(w, 0.3f) : th_box(w, th_v3(0.3f, 0.3f, 0.3f));
            tb_body_def d = th_dynamic_def(s, th_v3(-2.5f + i, 0.32f + 0.1f * i, 0.4f * i - 1.0f));
            th_body(w, &d);
        }
        th_assert_ok(tb_world_step_n(w, DT, 30));
        counts[k] = th_stats(w).contact_count;
        assert_true(counts[k] >= 6);
        if (k) assert_int_equal(counts[k], counts[0]);
        grid_free(&m);
        th_world_destroy(w);
    }
}

/* Bad meshes are refused with a sentence and the world keeps its shapes; a dynamic body
 * cannot use a mesh. */
static void test_bad_meshes_refused(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_shape_def sd = tb_default_shape_def();
    tb_vec3 v[4] = { th_v3(0, 0, 0), th_v3(0, 0, 1), th_v3(1, 0, 0), th_v3(1, 0, 1) };
    uint32_t good[6] = { 0, 1, 2, 2, 1, 3 }, out_of_range[3] = { 0, 1, 4 };
    uint32_t flat[3] = { 0, 0, 1 };
    tb_shape_id shape, ids[4];
    uint32_t before = tb_world_shape_ids(w, ids, 4);
    th_assert_result(tb_shape_create_mesh(w, &sd, NULL, 4, good, 2, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_mesh(w, &sd, v, 4, good, 0, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_mesh(w, &sd, v, 4, out_of_range, 1, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "index"));
    th_assert_result(tb_shape_create_mesh(w, &sd, v, 4, flat, 1, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    v[3].y = NAN;
    th_assert_result(tb_shape_create_mesh(w, &sd, v, 4, good, 2, &shape),
                     TB_ERROR_INVALID_ARGUMENT);
    v[3].y = 0.0f;
    assert_int_equal(tb_world_shape_ids(w, ids, 4), before);

    th_assert_ok(tb_shape_create_mesh(w, &sd, v, 4, good, 2, &shape));
    tb_mesh_info info;
    th_assert_ok(tb_shape_get_mesh_info(w, shape, &info));
    assert_int_equal(info.triangle_count, 2);
    assert_int_equal(info.active_edge_count, 4);   /* the square's border; the diagonal is flat */
    tb_vec3 back[4];
    uint32_t back_indices[6], nv = 0, nt = 0;
    th_assert_ok(tb_shape_get_mesh_geometry(w, shape, back, 4, back_indices, 2, &nv, &nt));
    assert_int_equal(nv, 4);
    assert_int_equal(nt, 2);
    assert_memory_equal(back, v, sizeof v);
    assert_memory_equal(back_indices, good, sizeof good);
    th_assert_result(tb_shape_get_mesh_geometry(w, shape, NULL, 4, NULL, 0, &nv, &nt),
                     TB_ERROR_INVALID_ARGUMENT);
    tb_body_def d = th_dynamic_def(shape, th_v3(0, 1, 0));
    tb_body_id body;
    th_assert_result(tb_body_create_many(w, &d, 1, &body), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "static"));
    assert_int_equal(th_stats(w).body_count, 0);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_rests_on_quad),
        cmocka_unit_test(test_box_rests_on_quad),
        cmocka_unit_test(test_hull_rests_on_quad),
        cmocka_unit_test(test_sphere_rests_on_fine_grid),
        cmocka_unit_test(test_box_rests_on_fine_grid),
        cmocka_unit_test(test_box_slides_over_seams),
        cmocka_unit_test(test_hard_landings_stay_on_terrain),
        cmocka_unit_test(test_sphere_rolls_down_heightfield_as_on_plane),
        cmocka_unit_test(test_heightfield_rest_and_holes),
        cmocka_unit_test(test_bad_heightfields_refused),
        cmocka_unit_test(test_broadphases_agree),
        cmocka_unit_test(test_bad_meshes_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
