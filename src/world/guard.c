/* The guard's host half. integrate (glsl/integrate/integrate.comp) isolates a dynamic body
 * whose pose or velocities would stop being finite: it keeps the pose it began that step
 * with, its velocities become zero, and its GPU flags lose ALIVE and DYNAMIC and gain
 * ISOLATED, so no stage meets or moves it again; counters.guard.x counts such bodies. After
 * a submission whose count grew, the host reads the flags back, marks the records, and logs
 * each body once. The body stays in the world (its pose can be read) until it is destroyed.
 */
#include "world/world.h"

tb_result tb_world_guard_check(tb_world* w, const tb_gpu_counters* c)
{
    if (c->guard.x == w->guard_seen) return TB_OK;
    w->guard_seen = c->guard.x;
    /* The step wrote the flags: the mirror of the info array is stale now. */
    w->store.fresh &= ~TB_ARRAY_BIT(TB_ARRAY_INFO);
    tb_result r = tb_world_fetch(w, TB_ARRAY_BIT(TB_ARRAY_INFO));
    if (r) return r;
    const tb_gpu_uvec4* info = (const tb_gpu_uvec4*)w->store.host[TB_ARRAY_INFO];
    for (uint32_t slot = 0; slot < w->body_slots.used; slot++) {
        tb_body_record* b = &w->bodies[slot];
        if (!b->alive || b->isolated || !(info[slot].y & TB_BODY_FLAG_ISOLATED)) continue;
        b->isolated = 1;
        w->isolated_bodies++;
        tb_body_id id = tb_body_id_of_slot(w, slot);
        tb_log(&w->diag, TB_LOG_WARNING, "body {%u, %u, %u} isolated by step %llu: its pose "
               "or velocity stopped being finite; it keeps its last finite pose and no longer "
               "moves or collides (tb_world_isolated_bodies)", id.index1, id.world,
               id.generation, (unsigned long long)w->gpu_steps);
    }
    return TB_OK;
}

uint32_t tb_world_isolated(const tb_world* w, tb_body_id* out, uint32_t capacity)
{
    uint32_t n = 0;
    for (uint32_t slot = 0; slot < w->body_slots.used && n < w->isolated_bodies; slot++) {
        const tb_body_record* b = &w->bodies[slot];
        if (!b->alive || !b->isolated) continue;
        if (out && n < capacity) out[n] = tb_body_id_of_slot(w, slot);
        n++;
    }
    return n;
}
