/* The deep pile: N unit boxes on a grid of pitch 1.1 m, each layer ceil(cbrt N)^2 boxes,
 * dropped into a container whose walls are 10 m high, lower than the falling pile, all of
 * friction 0.5. The boxes land in columns as deep as the grid has layers (46 at 100k), and
 * only a solver stiff enough for that depth keeps them standing inside the walls: a soft one
 * lets the columns sink and burst, throwing boxes over the walls.
 *
 * Checks: nan, escaped (centre outside the walls' footprint or below the floor; above the
 * walls is inside), resting (share slower than 0.1 m/s), max_penetration, and the columns'
 * heights: the top of the highest box over each cell of the start grid, in m (column_min,
 * column_mean, column_max; `layers` boxes deep would be `layers` m). */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define DEEP_HALF 0.5f       /* box half extent, m */
#define DEEP_WALLS 10.0f     /* m */
#define DEEP_FRICTION 0.5f

static pile_layout deep_layout(uint32_t n)
{
    pile_layout l = pile_layout_for(n);
    l.height = DEEP_WALLS;
    return l;
}

tb_result deep_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    pile_layout l = deep_layout(n);
    tb_shape_def sd = tb_default_shape_def();
    sd.friction = DEEP_FRICTION;
    tb_shape_id box;
    tb_result r = tb_shape_create_box(w, &sd, (tb_vec3){ DEEP_HALF, DEEP_HALF, DEEP_HALF }, &box);
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (r == TB_OK && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    uint32_t rng = scene_rng_seed(params->seed);
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        defs[i] = tb_default_body_def();
        defs[i].shape = box;
        defs[i].position = pile_grid_slot(&l, i, &rng);
    }
    r = pile_finish_of(w, &l, &sd, defs, n, r, inst, out);
    if (r == TB_OK) (*out)->box_max.y = INFINITY;   /* above the walls is still inside */
    return r;
}

/* The top of the highest box over each start cell, and how many cells hold any. */
static void column_heights(const scene_instance* inst, const tb_vec3* pos, scene_checks* out)
{
    pile_layout l = deep_layout(inst->count);
    uint32_t cells = l.side * l.side, filled = 0;
    float* top = calloc(cells, sizeof *top);
    if (!top) return;
    for (uint32_t i = 0; i < inst->count; i++) {
        if (!scene_vec3_finite(pos[i]) || pile_outside(pos[i], inst->box_min, inst->box_max))
            continue;
        int x = (int)floorf((pos[i].x + l.half_width) / l.pitch);
        int z = (int)floorf((pos[i].z + l.half_width) / l.pitch);
        x = x < 0 ? 0 : x >= (int)l.side ? (int)l.side - 1 : x;
        z = z < 0 ? 0 : z >= (int)l.side ? (int)l.side - 1 : z;
        float y = pos[i].y + DEEP_HALF;
        if (y > top[(uint32_t)z * l.side + (uint32_t)x]) top[(uint32_t)z * l.side + (uint32_t)x] = y;
    }
    double lo = INFINITY, hi = 0.0, sum = 0.0;
    for (uint32_t c = 0; c < cells; c++) {
        if (top[c] <= 0.0f) continue;
        filled++;
        sum += top[c];
        if (top[c] < lo) lo = top[c];
        if (top[c] > hi) hi = top[c];
    }
    free(top);
    scene_put(out, "layers", l.layers);
    scene_put(out, "column_min", filled ? lo : 0.0);
    scene_put(out, "column_mean", filled ? sum / filled : 0.0);
    scene_put(out, "column_max", hi);
}

tb_result deep_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                     scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos = malloc((inst->count ? inst->count : 1) * sizeof *pos);
    pile_counts counts;
    tb_result r = pos ? pile_census(w, inst, pos, &counts) : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", counts.nan);
        scene_put(out, "escaped", counts.escaped);
        scene_put(out, "resting", counts.resting);
        scene_put(out, "max_penetration", counts.max_penetration);
        column_heights(inst, pos, out);
    }
    free(pos);
    return r;
}
