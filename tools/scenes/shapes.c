/* Mixed-shape pile: N bodies of capsules, cylinders, cones, boxes and hulls poured into the
 * pile scenes' walled container, at rotations uniform over all.
 *
 * Eight kinds of body share their shapes among the bodies, one eighth of the bodies each,
 * so the round shapes are three quarters of the pile (a quarter each) and boxes and hulls
 * an eighth each:
 *   capsule   r 0.15, half height 0.25 (0.8 m long) and r 0.10, half height 0.20
 *   cylinder  r 0.25, half height 0.20 (a drum) and r 0.12, half height 0.35 (a rod)
 *   cone      r 0.25, half height 0.25 (squat) and r 0.15, half height 0.30 (tall)
 *   box       half extents 0.30 x 0.20 x 0.15
 *   hull      the hull scene's HULLS_SHAPES random hulls, in turn
 * Which body gets which kind is a shuffle (from the scene's seed) of i % 8 over the bodies,
 * so the counts are exact and the kinds mixed throughout the pile. Every body reaches less
 * than 0.46 m from its origin (a tall cone's apex, 1.5 x 0.30 above its centre of mass),
 * less than half the pile grid's closest start spacing (pitch 1.1 m less twice the
 * jitter), so the bodies start apart whatever their orientation.
 */
#include "instance.h"

#include <stdlib.h>

enum {
    SHAPE_CAPSULE, SHAPE_CAPSULE_THIN, SHAPE_DRUM, SHAPE_ROD, SHAPE_CONE, SHAPE_CONE_TALL,
    SHAPE_BOX, SHAPE_HULL, SHAPE_KINDS
};

typedef struct shapes_set {
    tb_shape_id kind[SHAPE_KINDS - 1];   ///< all but the hulls
    tb_shape_id hulls[HULLS_SHAPES];
} shapes_set;

static tb_result make_shapes(tb_world* w, uint32_t* rng, shapes_set* s)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_result r = tb_shape_create_capsule(w, &sd, 0.15f, 0.25f, &s->kind[SHAPE_CAPSULE]);
    if (!r) r = tb_shape_create_capsule(w, &sd, 0.10f, 0.20f, &s->kind[SHAPE_CAPSULE_THIN]);
    if (!r) r = tb_shape_create_cylinder(w, &sd, 0.25f, 0.20f, &s->kind[SHAPE_DRUM]);
    if (!r) r = tb_shape_create_cylinder(w, &sd, 0.12f, 0.35f, &s->kind[SHAPE_ROD]);
    if (!r) r = tb_shape_create_cone(w, &sd, 0.25f, 0.25f, &s->kind[SHAPE_CONE]);
    if (!r) r = tb_shape_create_cone(w, &sd, 0.15f, 0.30f, &s->kind[SHAPE_CONE_TALL]);
    if (!r) r = tb_shape_create_box(w, &sd, (tb_vec3){ 0.30f, 0.20f, 0.15f }, &s->kind[SHAPE_BOX]);
    if (!r) r = hulls_make_shapes(w, rng, s->hulls);
    return r;
}

tb_result shapes_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    pile_layout l = pile_layout_for(n);
    uint32_t rng = scene_rng_seed(params->seed);
    shapes_set set;
    tb_result r = make_shapes(w, &rng, &set);
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    uint8_t* kinds = malloc(n ? n : 1);
    if (r == TB_OK && (!inst || !defs || !kinds)) r = TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) {
        for (uint32_t i = 0; i < n; i++) kinds[i] = (uint8_t)(i % SHAPE_KINDS);
        for (uint32_t i = n; i > 1; i--) {   /* Fisher-Yates */
            uint32_t j = scene_rng_next(&rng) % i;
            uint8_t t = kinds[i - 1];
            kinds[i - 1] = kinds[j];
            kinds[j] = t;
        }
    }
    uint32_t hulls = 0;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        tb_body_def d = tb_default_body_def();
        d.shape = kinds[i] == SHAPE_HULL ? set.hulls[hulls++ % HULLS_SHAPES] : set.kind[kinds[i]];
        d.position = pile_grid_slot(&l, i, &rng);
        d.rotation = hulls_random_rotation(&rng);
        defs[i] = d;
    }
    free(kinds);
    return pile_finish(w, &l, defs, n, r, inst, out);
}
