/* Bodies through the API: argument checks and mass properties; the world keeps them
 * (src/world/bodies.c). */
#include <math.h>
#include <stdlib.h>

#include "base/checks.h"
#include "world/world.h"

/* A def checked and turned into what the GPU needs (tb_body_resolved). */
static tb_result check_numbers(tb_world* w, const tb_body_def* d, uint32_t i)
{
    tb_diag* diag = &w->diag;
    if (!tb_finite3(d->position) || !tb_finite3(d->linear_velocity) ||
        !tb_finite3(d->angular_velocity))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: position and velocities "
                       "must be finite", i);
    if (!tb_coordinates_within(d->position, TB_MAX_COORDINATE) ||
        !tb_within3(d->linear_velocity, TB_MAX_SPEED) ||
        !tb_within3(d->angular_velocity, TB_MAX_SPIN))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: position coordinates "
                       "must be within TB_MAX_COORDINATE (%g m), speed within TB_MAX_SPEED (%g "
                       "m/s), spin within TB_MAX_SPIN (%g rad/s)", i, (double)TB_MAX_COORDINATE,
                       (double)TB_MAX_SPEED, (double)TB_MAX_SPIN);
    if (!isfinite(d->mass) || d->mass < 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: mass must be finite and "
                       ">= 0, not %g", i, (double)d->mass);
    tb_vec3 I = d->inertia;
    int none = I.x == 0 && I.y == 0 && I.z == 0;
    if (!tb_finite3(I) || !(none || (I.x > 0 && I.y > 0 && I.z > 0)))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: inertia must be all 0 "
                       "(from the shape) or all finite and > 0", i);
    if (!isfinite(d->linear_damping) || d->linear_damping < 0 ||
        !isfinite(d->angular_damping) || d->angular_damping < 0 || !isfinite(d->gravity_scale))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: damping must be finite and "
                       ">= 0, gravity_scale finite", i);
    if (fabsf(d->gravity_scale) > TB_MAX_GRAVITY_SCALE)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: |gravity_scale| must be "
                       "at most TB_MAX_GRAVITY_SCALE (%g), not %g", i,
                       (double)TB_MAX_GRAVITY_SCALE, (double)d->gravity_scale);
    return TB_OK;
}

/* Mass from the def or the shape's volume and density; inertia likewise. */
static tb_result resolve_mass(tb_world* w, const tb_body_def* d, uint32_t i,
                              const tb_shape_record* shape, tb_body_resolved* out)
{
    out->mass = 0;
    out->inertia = (tb_vec3){ 0, 0, 0 };
    if (d->type == TB_BODY_STATIC) return TB_OK;
    if (shape->type == TB_SHAPE_PLANE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: a plane has no volume; "
                       "only static bodies may use it", i);
    if (shape->type == TB_SHAPE_MESH || shape->type == TB_SHAPE_HEIGHTFIELD)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: a triangle mesh or "
                       "heightfield is for static bodies only; give a moving body hulls", i);
    float mass = d->mass > 0 ? d->mass : shape->volume * shape->material.density;
    if (!(mass > 0) || !isfinite(mass))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: a dynamic body needs a "
                       "mass > 0 (give mass, or a shape density > 0)", i);
    out->mass = mass;
    tb_vec3 u = shape->unit_inertia;
    int given = d->inertia.x > 0;
    out->inertia = given ? d->inertia : (tb_vec3){ u.x * mass, u.y * mass, u.z * mass };
    tb_vec3 I = out->inertia;
    if (!tb_finite3(I) || !(I.x > 0 && I.y > 0 && I.z > 0))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: inertia out of range", i);
    /* A shape's own moments are physical, however thin it is (a rod 100 m long and 1 cm
     * thick has them 5e7 apart); given ones near zero flung a body to 1e13 m. */
    float most = fmaxf(I.x, fmaxf(I.y, I.z)), least = fminf(I.x, fminf(I.y, I.z));
    if (given && most > TB_MAX_INERTIA_RATIO * least)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: inertia (%g, %g, %g) "
                       "has moments further apart than TB_MAX_INERTIA_RATIO (%g)", i, (double)I.x,
                       (double)I.y, (double)I.z, (double)TB_MAX_INERTIA_RATIO);
    return TB_OK;
}

static tb_result resolve(tb_world* w, const tb_body_def* d, uint32_t i, tb_body_resolved* out)
{
    if (!d || d->internal_cookie != TB_DEF_COOKIE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u was not initialised with "
                       "tb_default_body_def()", i);
    if (d->type != TB_BODY_STATIC && d->type != TB_BODY_DYNAMIC)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: unknown body type %d", i,
                       (int)d->type);
    tb_result r;
    const tb_shape_record* shape = tb_shape_lookup(w, d->shape, &out->shape, &r);
    if (!shape) return r;
    if ((r = check_numbers(w, d, i))) return r;
    if ((r = tb_check_rotation(&w->diag, d->rotation, &out->rotation, "body def"))) return r;
    return resolve_mass(w, d, i, shape, out);
}

tb_result tb_body_create_many(tb_world* w, const tb_body_def* defs, uint32_t count, tb_body_id* out)
{
    if (!w || (count && (!defs || !out)))
        return w ? tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "defs and out_ids are required")
                 : TB_ERROR_INVALID_ARGUMENT;
    if ((uint64_t)w->body_slots.live + count > w->max_bodies)
        return tb_fail(&w->diag, TB_ERROR_CAPACITY, "%u more bodies would pass the limit of %u "
                       "(tb_world_def.max_bodies)", count, w->max_bodies);
    tb_body_resolved* rb = malloc((size_t)(count ? count : 1) * sizeof *rb);
    if (!rb) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < count && !r; i++) r = resolve(w, &defs[i], i, &rb[i]);
    if (!r) r = tb_bodies_add(w, defs, rb, count, out);
    free(rb);
    return r;
}

tb_result tb_body_create(tb_world* w, const tb_body_def* def, tb_body_id* out)
{
    return tb_body_create_many(w, def, 1, out);
}

tb_result tb_body_destroy(tb_world* w, tb_body_id id)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    tb_world_joints_of_body_remove(w, slot);
    tb_bodies_remove(w, slot);
    return TB_OK;
}

int tb_body_is_valid(const tb_world* w, tb_body_id id)
{
    if (!w || id.index1 == 0 || id.world != w->serial || id.index1 > w->body_slots.used) return 0;
    const tb_body_record* b = &w->bodies[id.index1 - 1];
    return b->alive && b->generation == id.generation;
}

/* The record of a body the caller may move: live, and not isolated by the guard. */
static tb_body_record* lookup_movable(tb_world* w, tb_body_id id, uint32_t* slot, tb_result* r)
{
    tb_body_record* b = tb_body_lookup(w, id, slot, r);
    if (b && b->isolated) {
        *r = tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body {%u, %u, %u} is isolated: its "
                     "state stopped being finite in a step, and it stays where it was until "
                     "destroyed", id.index1, id.world, id.generation);
        return NULL;
    }
    return b;
}

tb_result tb_body_set_pose(tb_world* w, tb_body_id id, tb_vec3 p, tb_quat q)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = lookup_movable(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(p))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "position must be finite");
    if (!tb_coordinates_within(p, TB_MAX_COORDINATE))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "position coordinates must be "
                       "within TB_MAX_COORDINATE (%g m)", (double)TB_MAX_COORDINATE);
    tb_quat unit;
    if ((r = tb_check_rotation(&w->diag, q, &unit, "tb_body_set_pose"))) return r;
    tb_bodies_set_pose(w, slot, p, unit);
    return TB_OK;
}

tb_result tb_body_get_pose(tb_world* w, tb_body_id id, tb_vec3* position, tb_quat* rotation)
{
    return tb_world_read_transforms(w, &id, 1, position, rotation);
}

tb_result tb_body_set_velocity(tb_world* w, tb_body_id id, tb_vec3 v, tb_vec3 av)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = lookup_movable(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(v) || !tb_finite3(av))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "velocity must be finite");
    if (!tb_within3(v, TB_MAX_SPEED) || !tb_within3(av, TB_MAX_SPIN))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "speed must be within TB_MAX_SPEED "
                       "(%g m/s), spin within TB_MAX_SPIN (%g rad/s)", (double)TB_MAX_SPEED,
                       (double)TB_MAX_SPIN);
    if (b->type == TB_BODY_STATIC) return TB_OK;
    tb_bodies_set_velocity(w, slot, v, av);
    return TB_OK;
}

tb_result tb_body_get_velocity(tb_world* w, tb_body_id id, tb_vec3* v, tb_vec3* av)
{
    uint32_t slot;
    tb_result r;
    if (!tb_body_lookup(w, id, &slot, &r)) return r;
    return tb_bodies_get_velocity(w, slot, v, av);
}

/* An impulse changes the velocities at once (src/world/bodies.c). */
tb_result tb_body_apply_impulse(tb_world* w, tb_body_id id, tb_vec3 impulse, tb_vec3 point)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = lookup_movable(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(impulse) || !tb_finite3(point))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "impulse and point must be finite");
    if (b->type == TB_BODY_STATIC) return TB_OK;
    return tb_bodies_apply_impulse(w, slot, impulse, point);
}

tb_result tb_body_get_mass(const tb_world* cw, tb_body_id id, float* mass, tb_vec3* inertia)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    if (mass) *mass = b->mass;
    if (inertia) *inertia = b->inertia;
    return TB_OK;
}

tb_result tb_body_get_type(const tb_world* cw, tb_body_id id, tb_body_type* out)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_body_get_type: out is NULL");
    *out = (tb_body_type)b->type;
    return TB_OK;
}

void* tb_body_get_user_data(const tb_world* cw, tb_body_id id)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    return b ? b->user_data : NULL;
}

/* Check every id before anything is read, so a bad id leaves the outputs untouched. */
static tb_result check_ids(tb_world* w, const tb_body_id* ids, uint32_t count)
{
    if (count && !ids) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "ids are required");
    for (uint32_t i = 0; i < count; i++) {
        uint32_t slot;
        tb_result r;
        if (!tb_body_lookup(w, ids[i], &slot, &r)) return r;
    }
    return TB_OK;
}

tb_result tb_world_read_transforms(tb_world* w, const tb_body_id* ids, uint32_t count,
                                   tb_vec3* positions, tb_quat* rotations)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    tb_result r = check_ids(w, ids, count);
    return r ? r : tb_bodies_gather(w, ids, count, TB_ARRAY_POS, TB_ARRAY_ROT, positions,
                                    rotations, 1);
}

tb_result tb_world_read_aabbs(tb_world* w, const tb_body_id* ids, uint32_t count, tb_vec3* mins,
                              tb_vec3* maxs)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    tb_result r = check_ids(w, ids, count);
    return r ? r : tb_bodies_gather(w, ids, count, TB_ARRAY_AABB_MIN, TB_ARRAY_AABB_MAX, mins, maxs, 0);
}

uint32_t tb_world_body_ids(const tb_world* w, tb_body_id* out, uint32_t capacity)
{
    return w && out ? tb_bodies_ids(w, out, capacity) : 0;
}

uint32_t tb_world_isolated_bodies(const tb_world* w, tb_body_id* out, uint32_t capacity)
{
    return w ? tb_world_isolated(w, out, capacity) : 0;
}
