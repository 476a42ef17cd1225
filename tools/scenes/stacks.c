/* Stacking scenes: unit cubes at rest on a static ground plane, placed exactly touching, so
 * nothing should move at all. What moves is the solver's error: `drift` is the largest
 * distance any box ends up from where it started. The tests (tests/test_stacking.c) build
 * the same scenes and also follow the boxes over the whole run.
 *
 * - stack: N boxes in one vertical column.
 * - pyramid: a 2-D pyramid in the x-y plane whose base row holds the most boxes N allows
 *   (largest b with b(b+1)/2 <= N; extra boxes are not placed), each box centred over the
 *   gap between the two below. Boxes of a row touch, as in Box2D's pyramid sample: a gap
 *   would let the rows above settle into it, which is motion the scene does not ask for.
 * - columns: free-standing columns of COLUMNS_LAYERS boxes on a square grid of pitch 1.1 m
 *   (bottom layer first, the last layer as full as N allows), every box shifted sideways by
 *   up to COLUMNS_JITTER, so each column leans a little and its contacts carry their loads
 *   off centre, as the columns of a pile that fell do; the boxes start COLUMNS_GAP apart
 *   and land on each other. Nothing holds a column but its own contacts: a solver that
 *   leaves them trembling shows it in `resting`. Its `drift` and `fallen` count only the
 *   sideways motion (the boxes fall COLUMNS_GAP a layer as they land).
 */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define STACK_HALF 0.5f       /* box half extent, m */
#define STACK_GAP 0.0f        /* horizontal gap between boxes of a pyramid row, m */
/* A box whose centre moved further than its half extent has fallen off its support. */
#define STACK_FALLEN STACK_HALF
#define STACK_REST_SPEED 0.1f /* m/s: slower boxes count as resting */
#define COLUMNS_LAYERS 16u
#define COLUMNS_PITCH 1.1f    /* m between neighbouring columns */
#define COLUMNS_JITTER 0.04f  /* m */
#define COLUMNS_GAP 0.1f      /* m between a column's boxes at the start */

tb_result scene_ground_plane(tb_world* w)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id plane;
    tb_result r = tb_shape_create_plane(w, &sd, (tb_vec3){ 0, 1, 0 }, 0.0f, &plane);
    if (r != TB_OK) return r;
    tb_body_def d = tb_default_body_def();
    d.type = TB_BODY_STATIC;
    d.shape = plane;
    tb_body_id id;
    return tb_body_create(w, &d, &id);
}

uint32_t pyramid_base(uint32_t n)
{
    uint32_t b = 0;
    while ((uint64_t)(b + 1) * (b + 2) / 2 <= n) b++;
    return b;
}

/* Boxes at `count` positions (written into inst->x0 by `place`), then the ground. */
static tb_result boxes_at(tb_world* w, uint32_t count,
                          void (*place)(scene_instance*, uint32_t, uint32_t), uint32_t param,
                          uint32_t seed, scene_instance** out)
{
    *out = NULL;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id box;
    tb_result r = tb_shape_create_box(w, &sd, (tb_vec3){ STACK_HALF, STACK_HALF, STACK_HALF }, &box);
    scene_instance* inst = r == TB_OK ? instance_alloc(count) : NULL;
    tb_body_def* defs = malloc((count ? count : 1) * sizeof *defs);
    if (r == TB_OK && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) place(inst, param, seed);
    for (uint32_t i = 0; r == TB_OK && i < count; i++) {
        defs[i] = tb_default_body_def();
        defs[i].shape = box;
        defs[i].position = inst->x0[i];
        inst->v0[i] = (tb_vec3){ 0, 0, 0 };
    }
    /* Dynamic bodies first, so their ids lead the instance's list. */
    if (r == TB_OK && count) r = tb_body_create_many(w, defs, count, inst->ids);
    if (r == TB_OK) r = scene_ground_plane(w);
    free(defs);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

/* Box i of the column, bottom first: the top box is the last. */
static void place_column(scene_instance* inst, uint32_t n, uint32_t seed)
{
    (void)seed;
    for (uint32_t i = 0; i < n; i++)
        inst->x0[i] = (tb_vec3){ 0.0f, STACK_HALF + 2.0f * STACK_HALF * (float)i, 0.0f };
}

/* Rows from the base up, each row left to right; the apex is the last box. */
static void place_pyramid(scene_instance* inst, uint32_t base, uint32_t seed)
{
    (void)seed;
    float pitch = 2.0f * STACK_HALF + STACK_GAP;
    uint32_t i = 0;
    for (uint32_t row = 0; row < base; row++) {
        uint32_t in_row = base - row;
        for (uint32_t k = 0; k < in_row; k++, i++)
            inst->x0[i] = (tb_vec3){ ((float)k - 0.5f * (float)(in_row - 1)) * pitch,
                                     STACK_HALF + 2.0f * STACK_HALF * (float)row, 0.0f };
    }
}

/* Layer by layer from the floor up, each layer row by row over the grid of columns. */
static void place_columns(scene_instance* inst, uint32_t n, uint32_t seed)
{
    uint32_t per_layer = (n + COLUMNS_LAYERS - 1) / COLUMNS_LAYERS;
    uint32_t side = (uint32_t)ceil(sqrt((double)(per_layer ? per_layer : 1)));
    uint32_t rng = scene_rng_seed(seed);
    float centre = 0.5f * (float)(side - 1) * COLUMNS_PITCH;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t cell = i % (side * side), layer = i / (side * side);
        inst->x0[i].x = (float)(cell % side) * COLUMNS_PITCH - centre
                        + COLUMNS_JITTER * scene_rng_signed(&rng);
        inst->x0[i].z = (float)(cell / side) * COLUMNS_PITCH - centre
                        + COLUMNS_JITTER * scene_rng_signed(&rng);
        inst->x0[i].y = STACK_HALF + (2.0f * STACK_HALF + COLUMNS_GAP) * (float)layer;
    }
}

tb_result stack_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return boxes_at(w, params->n, place_column, params->n, params->seed, out);
}

tb_result pyramid_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    uint32_t base = pyramid_base(params->n);
    return boxes_at(w, base * (base + 1) / 2, place_pyramid, base, params->seed, out);
}

tb_result columns_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return boxes_at(w, params->n, place_columns, params->n, params->seed, out);
}

/* The checks of the boxes' scenes; `sideways`: drift and fallen leave out the height. */
static tb_result boxes_check(tb_world* w, const scene_instance* inst, int sideways,
                             scene_checks* out)
{
    uint32_t n = inst->count;
    tb_vec3* pos = malloc((n ? n : 1) * sizeof *pos);
    tb_quat* rot = malloc((n ? n : 1) * sizeof *rot);
    tb_result r = pos && rot ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK && n) r = tb_world_read_transforms(w, inst->ids, n, pos, rot);
    uint32_t nan = 0, fallen = 0, resting = 0;
    double drift = 0.0;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        if (!scene_vec3_finite(pos[i]) || !scene_quat_finite(rot[i])) {
            nan++;
            continue;
        }
        double dx = (double)pos[i].x - inst->x0[i].x, dy = (double)pos[i].y - inst->x0[i].y,
               dz = (double)pos[i].z - inst->x0[i].z;
        if (sideways) dy = 0.0;
        double d = sqrt(dx * dx + dy * dy + dz * dz);
        if (d > drift) drift = d;
        if (d > STACK_FALLEN) fallen++;
        tb_vec3 v, av;
        r = tb_body_get_velocity(w, inst->ids[i], &v, &av);
        if (r == TB_OK && sqrtf(v.x * v.x + v.y * v.y + v.z * v.z) < STACK_REST_SPEED) resting++;
    }
    double depth = 0.0;
    if (r == TB_OK) r = scene_max_penetration(w, &depth);
    tb_world_stats st;
    if (r == TB_OK) r = tb_world_get_stats(w, &st);
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "fallen", fallen);
        scene_put(out, "drift", drift);
        scene_put(out, "max_penetration", depth);
        scene_put(out, "contacts", st.contact_count);
        scene_put(out, "colours", st.colour_count);
        scene_put(out, "resting", n ? (double)resting / n : 1.0);
    }
    free(pos);
    free(rot);
    return r;
}

tb_result stack_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out)
{
    (void)steps;
    (void)dt;
    return boxes_check(w, inst, 0, out);
}

tb_result columns_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                        scene_checks* out)
{
    (void)steps;
    (void)dt;
    return boxes_check(w, inst, 1, out);
}
