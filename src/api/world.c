/* The world through the API: creation, stepping, gravity, stats, errors. */
#include <math.h>
#include <stdlib.h>

#include "api/api.h"
#include "base/checks.h"
#include "world/world.h"

static tb_result check_world_def(tb_diag* diag, const tb_world_def* def)
{
    if (!def || def->internal_cookie != TB_DEF_COOKIE)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT,
                       "world def was not initialised with tb_default_world_def()");
    if (!tb_finite3(def->gravity))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "gravity must be finite");
    if (!tb_within3(def->gravity, TB_MAX_GRAVITY))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "|gravity| must be at most "
                       "TB_MAX_GRAVITY (%g m/s^2)", (double)TB_MAX_GRAVITY);
    if (!isfinite(def->max_rotation_per_step) || def->max_rotation_per_step <= 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "max_rotation_per_step must be finite "
                       "and > 0, not %g", (double)def->max_rotation_per_step);
    if (def->substeps < 1 || def->substeps > 64)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "substeps must be in [1, 64], not %u",
                       def->substeps);
    if (!isfinite(def->contact_hertz) || def->contact_hertz < 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "contact_hertz must be finite and >= 0, "
                       "not %g", (double)def->contact_hertz);
    if (def->solver_iterations < 1 || def->solver_iterations > 1000)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "solver_iterations must be in [1, 1000], "
                       "not %u", def->solver_iterations);
    const struct { float v; const char* name; float hi; } ranges[] = {
        { def->contact_margin, "contact_margin", 1e30f },
        { def->restitution_threshold, "restitution_threshold", 1e30f },
        { def->contact_damping_ratio, "contact_damping_ratio", 1e30f },
        { def->contact_push_speed, "contact_push_speed", 1e30f },
    };
    for (size_t i = 0; i < sizeof ranges / sizeof ranges[0]; i++)
        if (!isfinite(ranges[i].v) || ranges[i].v < 0 || ranges[i].v > ranges[i].hi)
            return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s must be finite, >= 0%s, not %g",
                           ranges[i].name, ranges[i].hi == 1.0f ? " and <= 1" : "",
                           (double)ranges[i].v);
    return TB_OK;
}

tb_result tb_api_world_create(const tb_world_def* def, const tb_gpu_options* extra,
                              tb_world** out)
{
    tb_diag early = { .log = def ? def->log : NULL, .log_user = def ? def->log_user : NULL };
    if (!out) return tb_fail(&early, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = NULL;
    tb_result r = check_world_def(&early, def);
    tb_broadphase broadphase = TB_BROADPHASE_GRID;
    if (!r) r = tb_broadphase_resolve(&early, def->broadphase, &broadphase);
    if (!r) r = tb_world_build(def, broadphase, &early, extra, out);
    tb_diag_set_create_error(r ? early.message : "");
    return r;
}

tb_result tb_world_create(const tb_world_def* def, tb_world** out)
{
    tb_gpu_options none = { 0 };
    return tb_api_world_create(def, &none, out);
}

/* Within a step the plugins' callbacks are being iterated and the world is in use: a call
 * that would step, free, save or load it, or change its plugins, is refused. */
tb_result tb_api_refuse_in_callbacks(tb_world* w, const char* call)
{
    return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "%s cannot be called from a plugin's "
                   "contact callback, within a step", call);
}

void tb_world_destroy(tb_world* w)
{
    /* Within a step (a plugin's contact callback) the library is still using the world. */
    if (w && w->in_callbacks) {
        tb_api_refuse_in_callbacks(w, "tb_world_destroy");
        return;
    }
    tb_world_free(w);
}

const char* tb_world_last_error(const tb_world* w)
{
    return w ? w->diag.message : tb_diag_create_error();
}

const char* tb_result_string(tb_result result)
{
    switch (result) {
    case TB_OK: return "success";
    case TB_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case TB_ERROR_INVALID_ID: return "invalid id";
    case TB_ERROR_STALE_ID: return "stale id (the object was destroyed)";
    case TB_ERROR_CAPACITY: return "capacity exhausted";
    case TB_ERROR_OUT_OF_MEMORY: return "out of memory";
    case TB_ERROR_NO_DEVICE: return "no suitable Vulkan device";
    case TB_ERROR_DEVICE: return "Vulkan device error";
    case TB_ERROR_IN_USE: return "object in use";
    default: return "unknown result code";
    }
}

uint32_t tb_version(void)
{
    return TB_VERSION;
}

tb_result tb_world_set_gravity(tb_world* w, tb_vec3 gravity)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!tb_finite3(gravity))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "gravity must be finite");
    if (!tb_within3(gravity, TB_MAX_GRAVITY))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "|gravity| must be at most "
                       "TB_MAX_GRAVITY (%g m/s^2)", (double)TB_MAX_GRAVITY);
    w->gravity = gravity;
    return TB_OK;
}

tb_vec3 tb_world_get_gravity(const tb_world* w)
{
    return w ? w->gravity : (tb_vec3){ 0, 0, 0 };
}

tb_result tb_world_set_solver(tb_world* w, tb_solver_kind solver, uint32_t iterations)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (solver != TB_SOLVER_SOFT_STEP && solver != TB_SOLVER_BLOCK)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "unknown solver %d", (int)solver);
    if (iterations > 1000)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "the block solver's iterations "
                       "must be in [1, 1000] (0: the default), not %u", iterations);
    if (w->submits > 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "the solver can only be chosen "
                       "before the world's first step");
    return tb_world_use_solver(w, solver == TB_SOLVER_BLOCK, iterations);
}

tb_result tb_world_set_contact_reuse(tb_world* w, float distance, float angle)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!isfinite(distance) || distance < 0 || !isfinite(angle) || angle < 0 ||
        angle > TB_MAX_REUSE_ANGLE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "contact reuse needs a finite "
                       "distance >= 0 and an angle in [0, %g] rad, not %g m and %g rad",
                       (double)TB_MAX_REUSE_ANGLE, (double)distance, (double)angle);
    w->reuse_distance = distance;
    w->reuse_angle = angle;
    return TB_OK;
}

void tb_world_get_contact_reuse(const tb_world* w, float* distance, float* angle)
{
    if (distance) *distance = w ? w->reuse_distance : TB_DEFAULT_REUSE_DISTANCE;
    if (angle) *angle = w ? w->reuse_angle : TB_DEFAULT_REUSE_ANGLE;
}

tb_solver_kind tb_world_get_solver(const tb_world* w, uint32_t* iterations)
{
    if (iterations) *iterations = w ? w->block_settings.iterations : 0;
    return !w || w->block_solver ? TB_SOLVER_BLOCK : TB_SOLVER_SOFT_STEP;
}

tb_result tb_world_step_n(tb_world* w, float dt, uint32_t n)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_world_step");
    if (!isfinite(dt) || dt <= 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "dt must be finite and > 0, not %g",
                       (double)dt);
    if (dt > TB_MAX_DT)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "dt must be at most TB_MAX_DT (%g "
                       "s), not %g", (double)TB_MAX_DT, (double)dt);
    return tb_world_run(w, dt, n);
}

tb_result tb_world_step(tb_world* w, float dt)
{
    return tb_world_step_n(w, dt, 1);
}

tb_result tb_world_snapshot(tb_world* w, void* out, size_t capacity, size_t* size)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!size)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_snapshot: size is NULL");
    if (!out && capacity)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_snapshot: out is NULL "
                       "with a capacity of %zu", capacity);
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_world_snapshot");
    return tb_world_save(w, out, capacity, size);
}

tb_result tb_world_restore(tb_world* w, const void* snapshot, size_t size)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!snapshot)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_restore: snapshot is "
                       "NULL");
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_world_restore");
    return tb_world_load(w, snapshot, size);
}

tb_result tb_world_device_info(const tb_world* w, tb_device_info* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out)
        return tb_fail(&((tb_world*)w)->diag, TB_ERROR_INVALID_ARGUMENT,
                       "tb_world_device_info: out is NULL");
    tb_world_device(w, out);
    return TB_OK;
}

tb_result tb_world_get_stats(const tb_world* w, tb_world_stats* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out)
        return tb_fail(&((tb_world*)w)->diag, TB_ERROR_INVALID_ARGUMENT,
                       "tb_world_get_stats: out is NULL");
    tb_world_stats_read(w, out);
    return TB_OK;
}

tb_result tb_world_set_shader_dir(tb_world* w, const char* dir)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    return tb_world_shader_dir(w, dir);
}
