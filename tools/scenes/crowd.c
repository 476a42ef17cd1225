/* Crowd: N spheres of radius 0.5 m created at one point in free space, every one touching
 * every other (N (N - 1) / 2 pairs): the worst case of the broadphase's output, the
 * colouring (each body needs as many colours as there are bodies; past 64 the solver's
 * tail takes the rest one by one) and of growth and redo. Its checks: nan, the slowest
 * sphere (m/s; the crowd pushed apart moves every one) and the deepest overlap left. */
#include <math.h>
#include <stdlib.h>

#include "instance.h"

tb_result crowd_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    uint32_t n = params->n;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id ball;
    tb_result r = tb_shape_create_sphere(w, &sd, 0.5f, &ball);
    scene_instance* inst = r ? NULL : instance_alloc(n);
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (!r && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; !r && i < n; i++) {
        defs[i] = tb_default_body_def();
        defs[i].shape = ball;
        defs[i].position = (tb_vec3){ 0, 5, 0 };
        inst->x0[i] = defs[i].position;
        inst->v0[i] = (tb_vec3){ 0, 0, 0 };
    }
    if (!r) r = tb_body_create_many(w, defs, n, inst->ids);
    free(defs);
    if (r) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

tb_result crowd_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out)
{
    (void)steps;
    (void)dt;
    uint32_t nan = 0;
    double slowest = INFINITY;
    for (uint32_t i = 0; i < inst->count; i++) {
        tb_vec3 v, av;
        tb_result r = tb_body_get_velocity(w, inst->ids[i], &v, &av);
        if (r) return r;
        if (!scene_vec3_finite(v)) {
            nan++;
            continue;
        }
        double speed = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
        if (speed < slowest) slowest = speed;
    }
    double deepest = 0;
    tb_result r = scene_max_penetration(w, &deepest);
    if (r) return r;
    scene_put(out, "nan", nan);
    scene_put(out, "slowest", isfinite(slowest) ? slowest : 0);
    scene_put(out, "max_penetration", deepest);
    return TB_OK;
}
