/* Bodies: their records and ids, and their place in the body store (the host mirror of
 * the GPU's body arrays). */
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

tb_body_id tb_body_id_of_slot(const tb_world* w, uint32_t slot)
{
    if (slot >= w->body_slots.used || !w->bodies[slot].alive) return tb_null_body;
    return (tb_body_id){ slot + 1, w->serial, w->bodies[slot].generation };
}

static float inverse(float x)
{
    return x > 0 ? 1.0f / x : 0.0f;
}

tb_result tb_bodies_reserve_records(tb_world* w, uint32_t needed)
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
static tb_body_id commit(tb_world* w, const tb_body_def* d, const tb_body_resolved* rb)
{
    uint32_t slot;
    tb_slots_take(&w->body_slots, &slot);
    w->body_set_version++;
    tb_body_record* b = &w->bodies[slot];
    *b = (tb_body_record){ .generation = tb_next_generation(b->generation), .alive = 1,
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
    const tb_shape_record* shape = &w->shapes[rb->shape];
    uint32_t flags = TB_BODY_FLAG_ALIVE | (dynamic ? TB_BODY_FLAG_DYNAMIC : 0) |
                     (shape->mesh || shape->heightfield ? TB_BODY_FLAG_MESH : 0) |
                     (shape->compound ? TB_BODY_FLAG_COMPOUND : 0);
    *info = (tb_gpu_uvec4){ rb->shape, flags, 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_AABB_MIN, slot) = (tb_gpu_vec4){ 0, 0, 0, 0 };
    *tb_body_store_write(s, TB_ARRAY_AABB_MAX, slot) = (tb_gpu_vec4){ 0, 0, 0, 0 };
    return (tb_body_id){ slot + 1, w->serial, b->generation };
}

tb_result tb_bodies_add(tb_world* w, const tb_body_def* defs, const tb_body_resolved* resolved,
                        uint32_t count, tb_body_id* out)
{
    uint32_t fresh = count > w->body_slots.free_count ? count - w->body_slots.free_count : 0;
    uint32_t slots = w->body_slots.used + fresh;
    tb_result r = tb_bodies_reserve_records(w, slots);
    if (!r) r = tb_world_reserve_bodies(w, slots);
    for (uint32_t i = 0; i < count && !r; i++) out[i] = commit(w, &defs[i], &resolved[i]);
    return r;
}

void tb_bodies_remove(tb_world* w, uint32_t slot)
{
    tb_body_record* b = &w->bodies[slot];
    b->alive = 0;
    if (b->isolated) w->isolated_bodies--;
    b->isolated = 0;
    w->shapes[b->shape].users--;
    tb_gpu_uvec4* info = (tb_gpu_uvec4*)tb_body_store_write(&w->store, TB_ARRAY_INFO, slot);
    *info = (tb_gpu_uvec4){ 0, 0, 0, 0 };
    tb_slots_give(&w->body_slots, slot);
    w->body_set_version++;
}

void tb_bodies_set_pose(tb_world* w, uint32_t slot, tb_vec3 p, tb_quat unit)
{
    float mass = w->bodies[slot].mass;
    *tb_body_store_write(&w->store, TB_ARRAY_POS, slot) = (tb_gpu_vec4){ p.x, p.y, p.z, inverse(mass) };
    *tb_body_store_write(&w->store, TB_ARRAY_ROT, slot) = (tb_gpu_vec4){ unit.x, unit.y, unit.z, unit.w };
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

void tb_bodies_set_velocity(tb_world* w, uint32_t slot, tb_vec3 v, tb_vec3 av)
{
    write_velocity(w, slot, (vec3){ v.x, v.y, v.z }, (vec3){ av.x, av.y, av.z });
}

tb_result tb_bodies_get_velocity(tb_world* w, uint32_t slot, tb_vec3* v, tb_vec3* av)
{
    tb_result r = tb_world_fetch(w, TB_ARRAY_BIT(TB_ARRAY_LINVEL) | TB_ARRAY_BIT(TB_ARRAY_ANGVEL));
    if (r) return r;
    const tb_gpu_vec4 lin = w->store.host[TB_ARRAY_LINVEL][slot];
    const tb_gpu_vec4 ang = w->store.host[TB_ARRAY_ANGVEL][slot];
    if (v) *v = (tb_vec3){ lin.x, lin.y, lin.z };
    if (av) *av = (tb_vec3){ ang.x, ang.y, ang.z };
    return TB_OK;
}

/* dv = J / m; dw = R diag(1/I) R^T (r x J), with r from the centre to the point. */
tb_result tb_bodies_apply_impulse(tb_world* w, uint32_t slot, tb_vec3 impulse, tb_vec3 point)
{
    tb_result r;
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

/* Gather two mirror arrays (as vec3 and quat / vec3) for a list of ids. */
tb_result tb_bodies_gather(tb_world* w, const tb_body_id* ids, uint32_t count,
                           tb_body_array a, tb_body_array b, tb_vec3* out_a, void* out_b,
                           int b_is_quat)
{
    uint32_t mask = (out_a ? TB_ARRAY_BIT(a) : 0) | (out_b ? TB_ARRAY_BIT(b) : 0);
    tb_result r = tb_world_fetch(w, mask);
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

uint32_t tb_bodies_ids(const tb_world* w, tb_body_id* out, uint32_t capacity)
{
    uint32_t n = 0;
    for (uint32_t slot = 0; w && slot < w->body_slots.used && n < capacity; slot++) {
        const tb_body_record* b = &w->bodies[slot];
        if (b->alive) out[n++] = (tb_body_id){ slot + 1, w->serial, b->generation };
    }
    return n;
}
