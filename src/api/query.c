/* Distance queries through the API: every query checked (live convex shapes, finite
 * positions, unit rotations, a known penetration method) before any runs, then packed for
 * the GPU (src/world/query.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/checks.h"
#include "world/world.h"

/* One side of query i: its shape checked, its pose as the GPU reads it. */
static tb_result pack_side(tb_world* w, uint32_t i, char side, tb_shape_id id, tb_vec3 position,
                           tb_quat rotation, tb_gpu_vec4* out_position, tb_gpu_vec4* out_rotation)
{
    uint32_t slot;
    tb_result r;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, &r);
    if (!s) return r;
    if (!tb_shape_type_is_convex(s->type))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "distance query %u: shape %c is "
                       "not convex (type %d)", i, side, (int)s->type);
    if (slot > TB_DISTANCE_SHAPE_MASK)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "distance query %u: shape %c's slot "
                       "%u is beyond what a query can name", i, side, slot);
    if (!tb_finite3(position))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "distance query %u: position %c is "
                       "not finite", i, side);
    char what[48];
    snprintf(what, sizeof what, "distance query %u, rotation %c", i, side);
    tb_quat unit;
    if ((r = tb_check_rotation(&w->diag, rotation, &unit, what))) return r;
    float bits;
    memcpy(&bits, &slot, sizeof bits);
    *out_position = (tb_gpu_vec4){ position.x, position.y, position.z, bits };
    *out_rotation = (tb_gpu_vec4){ unit.x, unit.y, unit.z, unit.w };
    return TB_OK;
}

/* Query i's penetration method as the GPU reads it, above a's shape index (layout.h). EPA
 * is the default: on the measured pairs its depths are the accurate ones (docs/shapes.md). */
static tb_result pack_method(tb_world* w, uint32_t i, tb_penetration method, tb_gpu_vec4* out)
{
    uint32_t bits;
    if (method == TB_PENETRATION_DEFAULT || method == TB_PENETRATION_EPA)
        bits = TB_DISTANCE_METHOD_EPA;
    else if (method == TB_PENETRATION_MPR)
        bits = TB_DISTANCE_METHOD_MPR;
    else
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "distance query %u: penetration "
                       "method %d is unknown", i, (int)method);
    uint32_t word;
    memcpy(&word, &out->w, sizeof word);
    word |= bits << TB_DISTANCE_SHAPE_BITS;
    memcpy(&out->w, &word, sizeof word);
    return TB_OK;
}

static tb_result pack(tb_world* w, const tb_distance_query* q, uint32_t count,
                      tb_gpu_distance_query* out)
{
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < count && !r; i++) {
        r = pack_side(w, i, 'a', q[i].a, q[i].position_a, q[i].rotation_a, &out[i].position_a,
                      &out[i].rotation_a);
        if (!r) r = pack_side(w, i, 'b', q[i].b, q[i].position_b, q[i].rotation_b,
                              &out[i].position_b, &out[i].rotation_b);
        if (!r) r = pack_method(w, i, q[i].penetration, &out[i].position_a);
    }
    return r;
}

static void unpack(const tb_gpu_distance_result* in, uint32_t count, tb_distance_result* out)
{
    for (uint32_t i = 0; i < count; i++) {
        const tb_gpu_distance_result* g = &in[i];
        uint32_t status, iterations;
        memcpy(&status, &g->point_b.w, sizeof status);
        memcpy(&iterations, &g->normal.w, sizeof iterations);
        out[i] = (tb_distance_result){
            .distance = g->point_a.w, .normal = { g->normal.x, g->normal.y, g->normal.z },
            .point_a = { g->point_a.x, g->point_a.y, g->point_a.z },
            .point_b = { g->point_b.x, g->point_b.y, g->point_b.z },
            .status = status, .iterations = iterations,
        };
    }
}

tb_result tb_world_query_distances(tb_world* w, const tb_distance_query* queries, uint32_t count,
                                   tb_distance_result* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (count && (!queries || !out))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "queries or out is NULL");
    if (!count) return TB_OK;
    tb_gpu_distance_query* packed = malloc((size_t)count * sizeof *packed);
    tb_gpu_distance_result* results = malloc((size_t)count * sizeof *results);
    tb_result r = packed && results ? TB_OK
                                    : tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    if (!r) r = pack(w, queries, count, packed);
    if (!r) r = tb_world_distances(w, packed, count, results);
    if (!r) unpack(results, count, out);
    free(packed);
    free(results);
    return r;
}
