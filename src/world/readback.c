/* Reading the last step's contacts back from the GPU, or handing their buffer over. */
#include <string.h>

#include "world/world.h"

/* A pair with points has solver data (solver/prepare): its friction directions turn the
 * tangent impulses into a world vector. */
static uint32_t unpack(const tb_world* w, const tb_gpu_manifold* m, const tb_gpu_constraint* c,
                       tb_contact* out, uint32_t room)
{
    uint32_t points = m->info.x < TB_MAX_MANIFOLD_POINTS ? m->info.x : TB_MAX_MANIFOLD_POINTS;
    tb_vec3 n = { m->normal.x, m->normal.y, m->normal.z };
    tb_vec3 t1 = { c->tangent1.x, c->tangent1.y, c->tangent1.z };
    tb_vec3 t2 = { c->tangent2.x, c->tangent2.y, c->tangent2.z };
    float substeps = (float)tb_world_substeps(w);
    for (uint32_t k = 0; k < points && k < room; k++) {
        const tb_gpu_vec4* p = &m->point[k];
        const tb_gpu_vec4* j = &m->impulse[k];
        out[k] = (tb_contact){
            .a = tb_body_id_of_slot(w, m->info.y), .b = tb_body_id_of_slot(w, m->info.z),
            .point = { p->x, p->y, p->z }, .normal = n, .separation = p->w,
            .normal_impulse = j->w,
            .friction_impulse = { substeps * (j->y * t1.x + j->z * t2.x),
                                  substeps * (j->y * t1.y + j->z * t2.y),
                                  substeps * (j->y * t1.z + j->z * t2.z) },
            .feature = (&m->feature.x)[k],
        };
    }
    return points;
}

/* The last step's pairs; 0 before any step and after one that overflowed. */
static uint32_t last_pairs(const tb_world* w)
{
    uint32_t pairs = w->gpu_steps ? tb_sim_counters(&w->sim)->state.z : 0;
    return pairs <= w->sim.pair_capacity ? pairs : 0;
}

/* The array that holds the last completed step's manifolds. */
static const tb_buffer* last_manifolds(const tb_world* w)
{
    return tb_sim_manifolds_of_step(&w->sim, w->gpu_steps + 1u);
}

void tb_world_contact_buffer(const tb_world* w, VkBuffer* buffer, uint32_t* count,
                             VkDeviceSize* size)
{
    const tb_buffer* m = last_manifolds(w);
    *buffer = m->buffer;
    *count = last_pairs(w);
    *size = m->size;
}

tb_result tb_world_contacts(tb_world* w, tb_contact* out, uint32_t capacity, uint32_t* count)
{
    *count = 0;
    uint32_t pairs = last_pairs(w);
    if (!pairs) return TB_OK;
    VkDeviceSize bytes = (VkDeviceSize)pairs * sizeof(tb_gpu_manifold);
    VkDeviceSize cbytes = (VkDeviceSize)pairs * sizeof(tb_gpu_constraint);
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, bytes + cbytes + 64);
    if (r) return r;
    const void* m = tb_transfer_download(t, last_manifolds(w)->buffer, 0, bytes);
    const void* c = tb_transfer_download(t, w->sim.pair[TB_SIM_CONSTRAINTS].buffer, 0, cbytes);
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &t->cb, 1);
    if (r) return r;
    uint32_t total = 0;
    for (uint32_t p = 0; p < pairs; p++) {
        tb_gpu_manifold mf;
        tb_gpu_constraint cn;
        memcpy(&mf, (const tb_gpu_manifold*)m + p, sizeof mf);
        memcpy(&cn, (const tb_gpu_constraint*)c + p, sizeof cn);
        uint32_t room = total < capacity ? capacity - total : 0;
        total += unpack(w, &mf, &cn, out ? out + total : NULL, room);
    }
    *count = total;
    return TB_OK;
}
