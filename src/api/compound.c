/* Compound shapes through the API: the children checked, their mass properties composed
 * (src/geom/compound.c), the world keeps the result (src/world/shapes.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/checks.h"
#include "world/world.h"

/* How far from the compound's origin a child may sit (m), as for mesh vertices. */
#define MAX_CHILD_DISTANCE 1.0e6f

/* Child i's shape: live, of this world, convex and with a volume. */
static tb_result check_child_shape(tb_world* w, const tb_compound_child* c, uint32_t i,
                                   const tb_shape_record** out)
{
    uint32_t slot;
    tb_result r;
    const tb_shape_record* s = tb_shape_lookup(w, c->shape, &slot, &r);
    if (!s) return r;
    if (!tb_shape_type_is_convex(s->type))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "compound child %u: only convex "
                       "shapes (spheres, boxes, hulls, capsules, cylinders, cones) can be "
                       "children (its shape has type %d)", i, (int)s->type);
    *out = s;
    return TB_OK;
}

static tb_result check_child(tb_world* w, const tb_compound_child* c, uint32_t i,
                             tb_compound_input* in)
{
    const tb_shape_record* s = NULL;
    tb_result r = check_child_shape(w, c, i, &s);
    if (r) return r;
    tb_vec3 p = c->position;
    if (!tb_finite3(p) || fabsf(p.x) > MAX_CHILD_DISTANCE || fabsf(p.y) > MAX_CHILD_DISTANCE ||
        fabsf(p.z) > MAX_CHILD_DISTANCE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "compound child %u: position (%g, %g, "
                       "%g) is not finite or farther than 1e6 m", i, (double)p.x, (double)p.y,
                       (double)p.z);
    tb_quat q;
    char what[48];
    snprintf(what, sizeof what, "compound child %u", i);
    r = tb_check_rotation(&w->diag, c->rotation, &q, what);
    if (r) return r;
    const tb_gpu_shape* g = &w->gpu_shapes[c->shape.index1 - 1];
    *in = (tb_compound_input){
        .shape = c->shape.index1 - 1, .position = { p.x, p.y, p.z },
        .rotation = { q.x, q.y, q.z, q.w }, .volume = s->volume, .density = s->material.density,
        .unit_inertia = { s->unit_inertia.x, s->unit_inertia.y, s->unit_inertia.z },
        .box_center = { g->aabb_center.x, g->aabb_center.y, g->aabb_center.z },
        .box_half = { g->aabb_half.x, g->aabb_half.y, g->aabb_half.z },
    };
    return TB_OK;
}

static tb_gpu_shape compound_gpu_shape(const tb_compound* c)
{
    tb_gpu_shape g;
    memset(&g, 0, sizeof g);
    for (int k = 0; k < 3; k++) {
        (&g.aabb_center.x)[k] = (c->box_min[k] + c->box_max[k]) / 2;
        (&g.aabb_half.x)[k] = (c->box_max[k] - c->box_min[k]) / 2;
    }
    g.info = (tb_gpu_uvec4){ TB_GPU_SHAPE_COMPOUND, c->count, 0, 0 };
    return g;
}

tb_result tb_shape_create_compound(tb_world* w, const tb_compound_child* children, uint32_t count,
                                   tb_shape_id* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out || !children)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "compound: children or out is NULL");
    if (count == 0 || count > TB_COMPOUND_MAX_CHILDREN)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "compound: %u children; a compound "
                       "has 1 to %u", count, (unsigned)TB_COMPOUND_MAX_CHILDREN);
    tb_compound_input in[TB_COMPOUND_MAX_CHILDREN];
    for (uint32_t i = 0; i < count; i++) {
        tb_result r = check_child(w, &children[i], i, &in[i]);
        if (r) return r;
    }
    tb_compound* c = malloc(sizeof *c);
    if (!c) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_compound_build(in, count, c);
    tb_shape_record rec = { .type = TB_SHAPE_COMPOUND, .material = tb_default_shape_def(),
                            .volume = (float)c->volume, .compound = c };
    rec.material.density = (float)c->mass_per_volume;
    rec.unit_inertia = (tb_vec3){ (float)c->unit_inertia[0], (float)c->unit_inertia[1],
                                  (float)c->unit_inertia[2] };
    tb_gpu_shape gpu = compound_gpu_shape(c);
    return tb_shapes_add(w, &rec, &gpu, out);
}

static const tb_compound* compound_of(tb_world* w, tb_shape_id id, tb_result* r)
{
    uint32_t slot;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, r);
    if (!s) return NULL;
    if (s->type == TB_SHAPE_COMPOUND) return s->compound;
    *r = tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "shape {%u, %u, %u} is not a compound",
                 id.index1, id.world, id.generation);
    return NULL;
}

tb_result tb_shape_get_compound_info(const tb_world* cw, tb_shape_id id, tb_compound_info* out)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_compound* c = compound_of(w, id, &r);
    if (!c) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = (tb_compound_info){
        .child_count = c->count, .volume = (float)c->volume,
        .mass_per_volume = (float)c->mass_per_volume,
        .center_of_mass = { (float)c->center[0], (float)c->center[1], (float)c->center[2] },
        .principal_axes = { (float)c->rotation[0], (float)c->rotation[1], (float)c->rotation[2],
                            (float)c->rotation[3] },
        .unit_inertia = { (float)c->unit_inertia[0], (float)c->unit_inertia[1],
                          (float)c->unit_inertia[2] },
    };
    return TB_OK;
}

tb_result tb_shape_get_compound_children(const tb_world* cw, tb_shape_id id,
                                         tb_compound_child* out, uint32_t capacity,
                                         uint32_t* count)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_compound* c = compound_of(w, id, &r);
    if (!c) return r;
    if (!count || (!out && capacity))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "count is NULL, or out is NULL "
                       "with a capacity");
    for (uint32_t i = 0; i < c->count && i < capacity; i++) {
        const tb_compound_part* p = &c->parts[i];
        out[i] = (tb_compound_child){
            .shape = { p->shape + 1, w->serial, w->shapes[p->shape].generation },
            .position = { p->position[0], p->position[1], p->position[2] },
            .rotation = { p->rotation[0], p->rotation[1], p->rotation[2], p->rotation[3] },
        };
    }
    *count = c->count;
    return TB_OK;
}
