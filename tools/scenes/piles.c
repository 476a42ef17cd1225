/* Pile scenes: N bodies on a regular grid with small gaps and a small fixed jitter (so
 * columns do not stand by symmetry) dropped into a static container whose walls are taller
 * than the pile. A body has escaped when its centre leaves the container's interior. */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define PILE_SIZE 0.5f       /* sphere radius, box half extent, m */
#define PILE_GAP 0.1f        /* m between neighbours at the start */
#define PILE_JITTER 0.04f    /* m */
#define PILE_DROP 0.5f       /* m between the floor and the lowest layer */
#define WALL 0.5f            /* half thickness of floor and walls, m */
#define ESCAPE_TOLERANCE 0.05f
#define REST_SPEED 0.1f      /* m/s: slower bodies count as resting */

typedef enum pile_kind { PILE_SPHERES, PILE_BOXES, PILE_MIXED } pile_kind;

/* A footprint about as wide as the pile is tall, walls above the top of the grid. */
pile_layout pile_layout_for(uint32_t n)
{
    pile_layout l;
    l.side = (uint32_t)ceil(cbrt((double)(n ? n : 1)));
    if (l.side < 2) l.side = 2;
    l.layers = (n + l.side * l.side - 1) / (l.side * l.side);
    l.pitch = 2.0f * PILE_SIZE + PILE_GAP;
    l.half_width = 0.5f * (float)l.side * l.pitch;
    l.height = PILE_DROP + (float)l.layers * l.pitch + 2.0f;
    return l;
}

static tb_result add_static_box(tb_world* w, const tb_shape_def* sd, tb_vec3 centre,
                                tb_vec3 half)
{
    tb_shape_id shape;
    tb_result r = tb_shape_create_box(w, sd, half, &shape);
    if (r != TB_OK) return r;
    tb_body_def d = tb_default_body_def();
    d.type = TB_BODY_STATIC;
    d.shape = shape;
    d.position = centre;
    tb_body_id id;
    return tb_body_create(w, &d, &id);
}

/* Floor (its top at y = 0) and four walls around [-hw, hw] x [0, height] x [-hw, hw]. */
tb_result pile_build_container(tb_world* w, const pile_layout* l, const tb_shape_def* sd)
{
    float hw = l->half_width, hh = 0.5f * l->height, outer = hw + 2.0f * WALL;
    tb_result r = add_static_box(w, sd, (tb_vec3){ 0, -WALL, 0 }, (tb_vec3){ outer, WALL, outer });
    if (r == TB_OK) r = add_static_box(w, sd, (tb_vec3){ hw + WALL, hh, 0 }, (tb_vec3){ WALL, hh, outer });
    if (r == TB_OK) r = add_static_box(w, sd, (tb_vec3){ -hw - WALL, hh, 0 }, (tb_vec3){ WALL, hh, outer });
    if (r == TB_OK) r = add_static_box(w, sd, (tb_vec3){ 0, hh, hw + WALL }, (tb_vec3){ hw, hh, WALL });
    if (r == TB_OK) r = add_static_box(w, sd, (tb_vec3){ 0, hh, -hw - WALL }, (tb_vec3){ hw, hh, WALL });
    return r;
}


tb_vec3 pile_grid_slot(const pile_layout* l, uint32_t i, uint32_t* rng)
{
    uint32_t x = i % l->side, z = (i / l->side) % l->side, y = i / (l->side * l->side);
    tb_vec3 p;
    p.x = -l->half_width + ((float)x + 0.5f) * l->pitch + PILE_JITTER * scene_rng_signed(rng);
    p.z = -l->half_width + ((float)z + 0.5f) * l->pitch + PILE_JITTER * scene_rng_signed(rng);
    p.y = PILE_DROP + PILE_SIZE + (float)y * l->pitch + PILE_JITTER * scene_rng_signed(rng);
    return p;
}

tb_result pile_finish(tb_world* w, const pile_layout* l, tb_body_def* defs, uint32_t n,
                      tb_result r, scene_instance* inst, scene_instance** out)
{
    tb_shape_def sd = tb_default_shape_def();
    return pile_finish_of(w, l, &sd, defs, n, r, inst, out);
}

tb_result pile_finish_of(tb_world* w, const pile_layout* l, const tb_shape_def* container,
                         tb_body_def* defs, uint32_t n, tb_result r, scene_instance* inst,
                         scene_instance** out)
{
    /* Dynamic bodies first, so their ids lead the instance's list. */
    if (r == TB_OK && n) r = tb_body_create_many(w, defs, n, inst->ids);
    if (r == TB_OK) r = pile_build_container(w, l, container);
    free(defs);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    inst->box_min = (tb_vec3){ -l->half_width, 0.0f, -l->half_width };
    inst->box_max = (tb_vec3){ l->half_width, l->height, l->half_width };
    *out = inst;
    return TB_OK;
}

static tb_result pile_build(tb_world* w, const scene_params* params, pile_kind kind,
                            scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    pile_layout l = pile_layout_for(n);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id sphere, box;
    tb_result r = tb_shape_create_sphere(w, &sd, PILE_SIZE, &sphere);
    if (r == TB_OK) r = tb_shape_create_box(w, &sd, (tb_vec3){ PILE_SIZE, PILE_SIZE, PILE_SIZE }, &box);
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (r == TB_OK && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    uint32_t rng = scene_rng_seed(params->seed);
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        tb_body_def d = tb_default_body_def();
        int use_box = kind == PILE_BOXES || (kind == PILE_MIXED && (i % 2) == 1);
        d.shape = use_box ? box : sphere;
        d.position = pile_grid_slot(&l, i, &rng);
        defs[i] = d;
    }
    return pile_finish(w, &l, defs, n, r, inst, out);
}

tb_result spheres_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return pile_build(w, params, PILE_SPHERES, out);
}

tb_result boxes_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return pile_build(w, params, PILE_BOXES, out);
}

tb_result mixed_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return pile_build(w, params, PILE_MIXED, out);
}

int pile_outside(tb_vec3 p, tb_vec3 lo, tb_vec3 hi)
{
    float t = ESCAPE_TOLERANCE;
    return p.x < lo.x - t || p.y < lo.y - t || p.z < lo.z - t ||
           p.x > hi.x + t || p.y > hi.y + t || p.z > hi.z + t;
}

/* Deepest overlap among the last step's contact points, m (0 when none overlap). */
tb_result scene_max_penetration(tb_world* w, double* out)
{
    *out = 0.0;
    uint32_t count = 0;
    tb_result r = tb_world_read_contacts(w, NULL, 0, &count);
    if (r != TB_OK || count == 0) return r;
    tb_contact* c = malloc(count * sizeof *c);
    if (!c) return TB_ERROR_OUT_OF_MEMORY;
    r = tb_world_read_contacts(w, c, count, &count);
    for (uint32_t i = 0; r == TB_OK && i < count; i++)
        if (-c[i].separation > *out) *out = -c[i].separation;
    free(c);
    return r;
}

void scene_put(scene_checks* out, const char* key, double value)
{
    if (out->count < SCENE_MAX_CHECKS) {
        out->items[out->count].key = key;
        out->items[out->count].value = value;
        out->count++;
    }
}

tb_result pile_census(tb_world* w, const scene_instance* inst, tb_vec3* pos, pile_counts* out)
{
    uint32_t n = inst->count;
    tb_quat* rot = malloc((n ? n : 1) * sizeof *rot);
    tb_result r = rot ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK && n) r = tb_world_read_transforms(w, inst->ids, n, pos, rot);
    *out = (pile_counts){ 0, 0, 0, 0.0 };
    uint32_t resting = 0;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        tb_vec3 v, w_;
        if (!scene_vec3_finite(pos[i]) || !scene_quat_finite(rot[i])) out->nan++;
        else if (pile_outside(pos[i], inst->box_min, inst->box_max)) out->escaped++;
        r = tb_body_get_velocity(w, inst->ids[i], &v, &w_);
        if (r == TB_OK && sqrtf(v.x * v.x + v.y * v.y + v.z * v.z) < REST_SPEED) resting++;
    }
    out->resting = n ? (double)resting / n : 1.0;
    if (r == TB_OK) r = scene_max_penetration(w, &out->max_penetration);
    free(rot);
    return r;
}

tb_result pile_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                     scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos = malloc((inst->count ? inst->count : 1) * sizeof *pos);
    pile_counts counts;
    tb_result r = pos ? pile_census(w, inst, pos, &counts) : TB_ERROR_OUT_OF_MEMORY;
    tb_world_stats st;
    if (r == TB_OK) r = tb_world_get_stats(w, &st);
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", counts.nan);
        scene_put(out, "escaped", counts.escaped);
        scene_put(out, "max_penetration", counts.max_penetration);
        scene_put(out, "pairs", st.pair_count);
        scene_put(out, "contacts", st.contact_count);
        scene_put(out, "batches", st.batch_count);
        scene_put(out, "colours", st.colour_count);
        scene_put(out, "resting", counts.resting);
    }
    free(pos);
    return r;
}
