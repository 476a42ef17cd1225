/* Hull pile: N convex hulls poured into the pile scenes' walled container.
 *
 * HULL_SHAPES hull shapes are shared among the bodies (body i uses shape i % HULL_SHAPES),
 * as a game shares a few rock meshes among many rocks. Each shape is the hull of 8-32
 * random points on a jittered ellipsoid (radius scaled by 1 +- HULL_JITTER), so hulls
 * have both flat-ish and pointed faces and no two are alike. A hull's body frame is its
 * centre of mass (tb_shape_create_hull), which lies near the ellipsoid's centre for points
 * spread over its whole surface, so a hull reaches about (1 + HULL_JITTER) * HULL_RADIUS
 * = 0.35 m from its origin: less than half the pile's closest start spacing (pitch 1.1 m
 * less twice the jitter), so the hulls start apart whatever their orientation.
 */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define HULL_SHAPES HULLS_SHAPES
#define HULL_MIN_POINTS 8
#define HULL_MAX_POINTS 32
#define HULL_RADIUS 0.3f     /* largest semi-axis before jitter, m */
#define HULL_JITTER 0.15f    /* relative radius jitter of each point */

/* Shape k: 8 + (k * 24) / (HULL_SHAPES - 1) points, so the set spans 8 to 32. */
static uint32_t hull_point_count(uint32_t k)
{
    return HULL_MIN_POINTS + k * (HULL_MAX_POINTS - HULL_MIN_POINTS) / (HULL_SHAPES - 1);
}

/* A direction uniform on the sphere (rejection from the cube, so no pole clustering). */
static tb_vec3 random_direction(uint32_t* rng)
{
    for (;;) {
        float x = scene_rng_signed(rng), y = scene_rng_signed(rng), z = scene_rng_signed(rng);
        float l2 = x * x + y * y + z * z;
        if (l2 > 1e-4f && l2 <= 1.0f) {
            float s = 1.0f / sqrtf(l2);
            return (tb_vec3){ x * s, y * s, z * s };
        }
    }
}

static tb_quat random_rotation(uint32_t* rng)
{
    for (;;) {
        float x = scene_rng_signed(rng), y = scene_rng_signed(rng), z = scene_rng_signed(rng),
              w = scene_rng_signed(rng);
        float l2 = x * x + y * y + z * z + w * w;
        if (l2 > 1e-4f && l2 <= 1.0f) {
            float s = 1.0f / sqrtf(l2);
            return (tb_quat){ x * s, y * s, z * s, w * s };
        }
    }
}

static tb_result make_hull(tb_world* w, uint32_t k, uint32_t* rng, tb_shape_id* out)
{
    tb_vec3 points[HULL_MAX_POINTS];
    uint32_t count = hull_point_count(k);
    /* Semi-axes between 0.5 and 1 of HULL_RADIUS: boulders, slabs and rods. */
    tb_vec3 axes = { HULL_RADIUS * (0.75f + 0.25f * scene_rng_signed(rng)),
                     HULL_RADIUS * (0.75f + 0.25f * scene_rng_signed(rng)),
                     HULL_RADIUS * (0.75f + 0.25f * scene_rng_signed(rng)) };
    for (uint32_t i = 0; i < count; i++) {
        tb_vec3 d = random_direction(rng);
        float r = 1.0f + HULL_JITTER * scene_rng_signed(rng);
        points[i] = (tb_vec3){ d.x * axes.x * r, d.y * axes.y * r, d.z * axes.z * r };
    }
    tb_shape_def sd = tb_default_shape_def();
    return tb_shape_create_hull(w, &sd, points, count, out);
}

tb_result hulls_make_shapes(tb_world* w, uint32_t* rng, tb_shape_id shapes[HULLS_SHAPES])
{
    tb_result r = TB_OK;
    for (uint32_t k = 0; k < HULL_SHAPES && r == TB_OK; k++) r = make_hull(w, k, rng, &shapes[k]);
    return r;
}

tb_quat hulls_random_rotation(uint32_t* rng)
{
    return random_rotation(rng);
}

tb_result pile_pour_turned(tb_world* w, const pile_layout* l, const tb_shape_id* shapes,
                           uint32_t kinds, uint32_t n, uint32_t* rng, tb_result r,
                           scene_instance** out)
{
    *out = NULL;
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (r == TB_OK && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        tb_body_def d = tb_default_body_def();
        d.shape = shapes[i % kinds];
        d.position = pile_grid_slot(l, i, rng);
        d.rotation = random_rotation(rng);
        defs[i] = d;
    }
    return pile_finish(w, l, defs, n, r, inst, out);
}

tb_result hulls_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    pile_layout l = pile_layout_for(params->n);
    uint32_t rng = scene_rng_seed(params->seed);
    tb_shape_id shapes[HULL_SHAPES];
    tb_result r = hulls_make_shapes(w, &rng, shapes);
    return pile_pour_turned(w, &l, shapes, HULL_SHAPES, params->n, &rng, r, out);
}
