/* Compound pile: N compound bodies of 2 to 5 convex children poured into the pile scenes'
 * walled container. Five compound shapes are shared among the bodies (body i uses shape
 * i % 5), each reaching less than 0.5 m from its centre of mass, so they start apart on
 * the pile grid (pitch 1.1 m) whatever their orientation:
 *   dumbbell  two spheres on a bar (3 children)
 *   angle     two boxes in an L (2)
 *   table     a top on four legs (5)
 *   snowman   three spheres stacked (3)
 *   club      a random hull with a sphere beside it (2)
 */
#include "instance.h"

#define COMPOUND_KINDS 5

static tb_result make_compound(tb_world* w, const tb_compound_child* c, uint32_t n,
                               tb_shape_id* out)
{
    return tb_shape_create_compound(w, c, n, out);
}

static tb_compound_child part(tb_shape_id s, float x, float y, float z)
{
    return (tb_compound_child){ s, { x, y, z }, { 0, 0, 0, 1 } };
}

static tb_result sphere(tb_world* w, float r, tb_shape_id* out)
{
    tb_shape_def sd = tb_default_shape_def();
    return tb_shape_create_sphere(w, &sd, r, out);
}

static tb_result box(tb_world* w, float x, float y, float z, tb_shape_id* out)
{
    tb_shape_def sd = tb_default_shape_def();
    return tb_shape_create_box(w, &sd, (tb_vec3){ x, y, z }, out);
}

static tb_result make_kinds(tb_world* w, uint32_t* rng, tb_shape_id kinds[COMPOUND_KINDS])
{
    tb_shape_id ball, bar, beam, post, top, leg, s1, s2, s3, rocks[HULLS_SHAPES], knob;
    tb_result r = sphere(w, 0.18f, &ball);
    if (!r) r = box(w, 0.2f, 0.05f, 0.05f, &bar);
    if (!r) r = box(w, 0.35f, 0.1f, 0.1f, &beam);
    if (!r) r = box(w, 0.1f, 0.25f, 0.1f, &post);
    if (!r) r = box(w, 0.35f, 0.04f, 0.25f, &top);
    if (!r) r = box(w, 0.04f, 0.15f, 0.04f, &leg);
    if (!r) r = sphere(w, 0.2f, &s1);
    if (!r) r = sphere(w, 0.15f, &s2);
    if (!r) r = sphere(w, 0.1f, &s3);
    if (!r) r = sphere(w, 0.15f, &knob);
    if (!r) r = hulls_make_shapes(w, rng, rocks);
    if (r) return r;
    tb_compound_child dumbbell[3] = { part(ball, 0.27f, 0, 0), part(ball, -0.27f, 0, 0),
                                      part(bar, 0, 0, 0) };
    tb_compound_child angle[2] = { part(beam, 0, 0, 0), part(post, -0.25f, 0.25f, 0) };
    tb_compound_child table[5] = { part(top, 0, 0.1f, 0), part(leg, 0.3f, -0.09f, 0.2f),
                                   part(leg, -0.3f, -0.09f, 0.2f), part(leg, 0.3f, -0.09f, -0.2f),
                                   part(leg, -0.3f, -0.09f, -0.2f) };
    tb_compound_child snowman[3] = { part(s1, 0, -0.2f, 0), part(s2, 0, 0.12f, 0),
                                     part(s3, 0, 0.33f, 0) };
    tb_compound_child club[2] = { part(rocks[0], 0.12f, 0, 0), part(knob, -0.25f, 0, 0) };
    r = make_compound(w, dumbbell, 3, &kinds[0]);
    if (!r) r = make_compound(w, angle, 2, &kinds[1]);
    if (!r) r = make_compound(w, table, 5, &kinds[2]);
    if (!r) r = make_compound(w, snowman, 3, &kinds[3]);
    if (!r) r = make_compound(w, club, 2, &kinds[4]);
    return r;
}

tb_result compounds_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    pile_layout l = pile_layout_for(params->n);
    uint32_t rng = scene_rng_seed(params->seed);
    tb_shape_id kinds[COMPOUND_KINDS];
    tb_result r = make_kinds(w, &rng, kinds);
    return pile_pour_turned(w, &l, kinds, COMPOUND_KINDS, params->n, &rng, r, out);
}
