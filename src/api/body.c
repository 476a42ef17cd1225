/* Bodies: argument checks, mass properties, and their place in the body store. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "world/world.h"

tb_body_record* tb_body_lookup(tb_world* w, tb_body_id id, uint32_t* slot, tb_result* r)
{
    if (!w) {
        *r = TB_ERROR_INVALID_ARGUMENT;
        return NULL;
    }
    if (id.index1 == 0 || id.world != w->serial || id.index1 > w->body_slots.used) {
        *r = tb_fail(&w->diag, TB_ERROR_INVALID_ID, "body id {%u, %u, %u} does not name a body "
                     "of this world", id.index1, id.world, id.generation);
        return NULL;
    }
    tb_body_record* b = &w->bodies[id.index1 - 1];
    if (!b->alive || b->generation != id.generation) {
        *r = tb_fail(&w->diag, TB_ERROR_STALE_ID, "body id {%u, %u, %u} is stale: the body was "
                     "destroyed", id.index1, id.world, id.generation);
        return NULL;
    }
    *slot = id.index1 - 1;
    *r = TB_OK;
    return b;
}

/* A def checked and turned into what the GPU needs. */
typedef struct resolved_body {
    uint32_t shape;
    tb_quat rotation;
    float mass;
    tb_vec3 inertia;
} resolved_body;

static tb_result check_numbers(tb_world* w, const tb_body_def* d, uint32_t i)
{
    tb_diag* diag = &w->diag;
    if (!tb_finite3(d->position) || !tb_finite3(d->linear_velocity) ||
        !tb_finite3(d->angular_velocity))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: position and velocities "
                       "must be finite", i);
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
    return TB_OK;
}

/* Mass from the def or the shape's volume and density; inertia likewise. */
static tb_result resolve_mass(tb_world* w, const tb_body_def* d, uint32_t i,
                              const tb_shape_record* shape, resolved_body* out)
{
    out->mass = 0;
    out->inertia = (tb_vec3){ 0, 0, 0 };
    if (d->type == TB_BODY_STATIC) return TB_OK;
    if (shape->type == TB_SHAPE_PLANE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: a plane has no volume; "
                       "only static bodies may use it", i);
    float mass = d->mass > 0 ? d->mass : shape->volume * shape->material.density;
    if (!(mass > 0) || !isfinite(mass))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: a dynamic body needs a "
                       "mass > 0 (give mass, or a shape density > 0)", i);
    out->mass = mass;
    tb_vec3 u = shape->unit_inertia;
    int given = d->inertia.x > 0;
    out->inertia = given ? d->inertia : (tb_vec3){ u.x * mass, u.y * mass, u.z * mass };
    if (!tb_finite3(out->inertia) || !(out->inertia.x > 0 && out->inertia.y > 0 && out->inertia.z > 0))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "body def %u: inertia out of range", i);
    return TB_OK;
}

static tb_result resolve(tb_world* w, const tb_body_def* d, uint32_t i, resolved_body* out)
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

static float inverse(float x)
{
    return x > 0 ? 1.0f / x : 0.0f;
}

static tb_result grow_records(tb_world* w, uint32_t needed)
{
    if (needed <= w->body_record_capacity) return TB_OK;
    uint32_t cap = w->body_record_capacity ? w->body_record_capacity : 64;
    while (cap < needed) cap *= 2;
    tb_body_record* grown = realloc(w->bodies, (size_t)cap * sizeof *grown);
    if (!grown) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    memset(grown + w->body_record_capacity, 0, (size_t)(cap - w->body_record_capacity) * sizeof *grown);
    w->bodies = grown;
    w->body_record_capacity = cap;
    return TB_OK;
}

/* Put a resolved body into a slot: host record and the GPU mirror. */
static tb_body_id commit(tb_world* w, const tb_body_def* d, const resolved_body* rb)
{
    uint32_t slot;
    tb_slots_take(&w->body_slots, &slot);
    w->body_set_version++;
    tb_body_record* b = &w->bodies[slot];
    uint16_t generation = (uint16_t)(b->generation + 1);
    *b = (tb_body_record){ .generation = generation ? generation : 1, .alive = 1,
                           .type = (uint8_t)d->type, .shape = rb->shape, .mass = rb->mass,
                           .inertia = rb->inertia, .user_data = d->user_data };
    w->shapes[rb->shape].users++;
    int dynamic = d->type == TB_BODY_DYNAMIC;
    tb_vec3 p = d->position, v = d->linear_velocity, av = d->angular_velocity;
    tb_quat q = rb->rotation;
    tb_body_store* s = &w->store;
    *tb_body_store_write(s, TB_ARRAY_POS, slot) = (tb_gpu_vec4){ p.x, p.y, p.z, inverse(rb->mass) };
    *tb_body_store_write(s, TB_ARRAY_ROT, slot) = (tb_gpu_vec4){ q.x, q.y, q.z, q.w };
    *tb_body_store_write(s, TB_ARRAY_LINVEL, slot) = dynamic
        ? (tb_gpu_vec4){ v.x, v.y, v.z, d->linear_damping } : (tb_gpu_vec4){ 0, 0, 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_ANGVEL, slot) = dynamic
        ? (tb_gpu_vec4){ av.x, av.y, av.z, d->angular_damping } : (tb_gpu_vec4){ 0, 0, 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_INV_INERTIA, slot) = (tb_gpu_vec4){
        inverse(rb->inertia.x), inverse(rb->inertia.y), inverse(rb->inertia.z), d->gravity_scale };
    tb_gpu_uvec4* info = (tb_gpu_uvec4*)tb_body_store_write(s, TB_ARRAY_INFO, slot);
    *info = (tb_gpu_uvec4){ rb->shape, TB_BODY_FLAG_ALIVE | (dynamic ? TB_BODY_FLAG_DYNAMIC : 0), 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_AABB_MIN, slot) = (tb_gpu_vec4){ 0, 0, 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_AABB_MAX, slot) = (tb_gpu_vec4){ 0, 0, 0, 0 };
    return (tb_body_id){ slot + 1, w->serial, b->generation };
}

tb_result tb_body_create_many(tb_world* w, const tb_body_def* defs, uint32_t count, tb_body_id* out)
{
    if (!w || (count && (!defs || !out)))
        return w ? tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "defs and out_ids are required")
                 : TB_ERROR_INVALID_ARGUMENT;
    if ((uint64_t)w->body_slots.live + count > w->max_bodies)
        return tb_fail(&w->diag, TB_ERROR_CAPACITY, "%u more bodies would pass the limit of %u "
                       "(tb_world_def.max_bodies)", count, w->max_bodies);
    resolved_body* rb = malloc((size_t)(count ? count : 1) * sizeof *rb);
    if (!rb) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < count && !r; i++) r = resolve(w, &defs[i], i, &rb[i]);
    uint32_t fresh = count > w->body_slots.free_count ? count - w->body_slots.free_count : 0;
    uint32_t slots = w->body_slots.used + fresh;
    if (!r) r = grow_records(w, slots);
    if (!r) r = tb_world_reserve_bodies(w, slots);
    for (uint32_t i = 0; i < count && !r; i++) out[i] = commit(w, &defs[i], &rb[i]);
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
    b->alive = 0;
    w->shapes[b->shape].users--;
    tb_gpu_uvec4* info = (tb_gpu_uvec4*)tb_body_store_write(&w->store, TB_ARRAY_INFO, slot);
    *info = (tb_gpu_uvec4){ 0, 0, 0, 0 };
    tb_slots_give(&w->body_slots, slot);
    w->body_set_version++;
    return TB_OK;
}

int tb_body_is_valid(const tb_world* w, tb_body_id id)
{
    if (!w || id.index1 == 0 || id.world != w->serial || id.index1 > w->body_slots.used) return 0;
    const tb_body_record* b = &w->bodies[id.index1 - 1];
    return b->alive && b->generation == id.generation;
}

tb_result tb_body_set_pose(tb_world* w, tb_body_id id, tb_vec3 p, tb_quat q)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(p))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "position must be finite");
    tb_quat unit;
    if ((r = tb_check_rotation(&w->diag, q, &unit, "tb_body_set_pose"))) return r;
    *tb_body_store_write(&w->store, TB_ARRAY_POS, slot) = (tb_gpu_vec4){ p.x, p.y, p.z, inverse(b->mass) };
    *tb_body_store_write(&w->store, TB_ARRAY_ROT, slot) = (tb_gpu_vec4){ unit.x, unit.y, unit.z, unit.w };
    return TB_OK;
}

tb_result tb_body_get_pose(tb_world* w, tb_body_id id, tb_vec3* position, tb_quat* rotation)
{
    return tb_world_read_transforms(w, &id, 1, position, rotation);
}

/* Write a velocity pair, keeping the damping rates the GPU never changes (w). */
static void write_velocity(tb_world* w, uint32_t slot, vec3 v, vec3 av)
{
    tb_gpu_vec4* lin = &w->store.host[TB_ARRAY_LINVEL][slot];
    tb_gpu_vec4* ang = &w->store.host[TB_ARRAY_ANGVEL][slot];
    float lin_damping = lin->w, ang_damping = ang->w;
    *tb_body_store_write(&w->store, TB_ARRAY_LINVEL, slot) = (tb_gpu_vec4){ v[0], v[1], v[2], lin_damping };
    *tb_body_store_write(&w->store, TB_ARRAY_ANGVEL, slot) = (tb_gpu_vec4){ av[0], av[1], av[2], ang_damping };
}

tb_result tb_body_set_velocity(tb_world* w, tb_body_id id, tb_vec3 v, tb_vec3 av)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(v) || !tb_finite3(av))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "velocity must be finite");
    if (b->type == TB_BODY_STATIC) return TB_OK;
    write_velocity(w, slot, (vec3){ v.x, v.y, v.z }, (vec3){ av.x, av.y, av.z });
    return TB_OK;
}

tb_result tb_body_get_velocity(tb_world* w, tb_body_id id, tb_vec3* v, tb_vec3* av)
{
    uint32_t slot;
    tb_result r;
    if (!tb_body_lookup(w, id, &slot, &r)) return r;
    if ((r = tb_world_fetch(w, TB_ARRAY_BIT(TB_ARRAY_LINVEL) | TB_ARRAY_BIT(TB_ARRAY_ANGVEL)))) return r;
    const tb_gpu_vec4 lin = w->store.host[TB_ARRAY_LINVEL][slot];
    const tb_gpu_vec4 ang = w->store.host[TB_ARRAY_ANGVEL][slot];
    if (v) *v = (tb_vec3){ lin.x, lin.y, lin.z };
    if (av) *av = (tb_vec3){ ang.x, ang.y, ang.z };
    return TB_OK;
}

/* dv = J / m; dw = R diag(1/I) R^T (r x J), with r from the centre to the point. */
tb_result tb_body_apply_impulse(tb_world* w, tb_body_id id, tb_vec3 impulse, tb_vec3 point)
{
    uint32_t slot;
    tb_result r;
    tb_body_record* b = tb_body_lookup(w, id, &slot, &r);
    if (!b) return r;
    if (!tb_finite3(impulse) || !tb_finite3(point))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "impulse and point must be finite");
    if (b->type == TB_BODY_STATIC) return TB_OK;
    uint32_t need = TB_ARRAY_BIT(TB_ARRAY_POS) | TB_ARRAY_BIT(TB_ARRAY_ROT) |
                    TB_ARRAY_BIT(TB_ARRAY_LINVEL) | TB_ARRAY_BIT(TB_ARRAY_ANGVEL);
    if ((r = tb_world_fetch(w, need))) return r;
    const tb_gpu_vec4 p = w->store.host[TB_ARRAY_POS][slot], q = w->store.host[TB_ARRAY_ROT][slot];
    const tb_gpu_vec4 lin = w->store.host[TB_ARRAY_LINVEL][slot], ang = w->store.host[TB_ARRAY_ANGVEL][slot];
    const tb_gpu_vec4 inv_i = w->store.host[TB_ARRAY_INV_INERTIA][slot];
    vec3 J = { impulse.x, impulse.y, impulse.z };
    vec3 arm = { point.x - p.x, point.y - p.y, point.z - p.z }, torque, local;
    versor rot = { q.x, q.y, q.z, q.w }, inv_rot;
    glm_vec3_cross(arm, J, torque);
    glm_quat_inv(rot, inv_rot);
    glm_quat_rotatev(inv_rot, torque, local);
    glm_vec3_mul(local, (vec3){ inv_i.x, inv_i.y, inv_i.z }, local);
    vec3 dw, v = { lin.x, lin.y, lin.z }, av = { ang.x, ang.y, ang.z };
    glm_quat_rotatev(rot, local, dw);
    glm_vec3_muladds(J, p.w, v);
    glm_vec3_add(av, dw, av);
    write_velocity(w, slot, v, av);
    return TB_OK;
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
    if (b && out) *out = (tb_body_type)b->type;
    return r;
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

/* Gather two mirror arrays (as vec3 and quat / vec3) for a list of ids. */
static tb_result gather(tb_world* w, const tb_body_id* ids, uint32_t count, tb_body_array a,
                        tb_body_array b, tb_vec3* out_a, void* out_b, int b_is_quat)
{
    tb_result r = check_ids(w, ids, count);
    uint32_t mask = (out_a ? TB_ARRAY_BIT(a) : 0) | (out_b ? TB_ARRAY_BIT(b) : 0);
    if (!r) r = tb_world_fetch(w, mask);
    if (r) return r;
    const tb_gpu_vec4* ha = w->store.host[a];
    const tb_gpu_vec4* hb = w->store.host[b];
    for (uint32_t i = 0; i < count; i++) {
        uint32_t slot = ids[i].index1 - 1;
        if (out_a) out_a[i] = (tb_vec3){ ha[slot].x, ha[slot].y, ha[slot].z };
        if (out_b && b_is_quat)
            ((tb_quat*)out_b)[i] = (tb_quat){ hb[slot].x, hb[slot].y, hb[slot].z, hb[slot].w };
        else if (out_b)
            ((tb_vec3*)out_b)[i] = (tb_vec3){ hb[slot].x, hb[slot].y, hb[slot].z };
    }
    return TB_OK;
}

tb_result tb_world_read_transforms(tb_world* w, const tb_body_id* ids, uint32_t count,
                                   tb_vec3* positions, tb_quat* rotations)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    return gather(w, ids, count, TB_ARRAY_POS, TB_ARRAY_ROT, positions, rotations, 1);
}

tb_result tb_world_read_aabbs(tb_world* w, const tb_body_id* ids, uint32_t count, tb_vec3* mins,
                              tb_vec3* maxs)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    return gather(w, ids, count, TB_ARRAY_AABB_MIN, TB_ARRAY_AABB_MAX, mins, maxs, 0);
}

uint32_t tb_world_body_ids(const tb_world* w, tb_body_id* out, uint32_t capacity)
{
    uint32_t n = 0;
    for (uint32_t slot = 0; w && slot < w->body_slots.used && n < capacity; slot++) {
        const tb_body_record* b = &w->bodies[slot];
        if (b->alive) out[n++] = (tb_body_id){ slot + 1, w->serial, b->generation };
    }
    return n;
}
