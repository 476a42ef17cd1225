/* Joints in the world: their ids, the bodies they hold, and what adding them changes in the
 * step (its lists' room, its joint passes). The table itself is src/joints/. */
#include "world/world.h"

tb_joint_record* tb_joint_lookup(tb_world* w, tb_joint_id id, uint32_t* slot, tb_result* r)
{
    if (!w) {
        *r = TB_ERROR_INVALID_ARGUMENT;
        return NULL;
    }
    if (id.index1 == 0 || id.world != w->serial || id.index1 > w->joints.slots.used) {
        *r = tb_fail(&w->diag, TB_ERROR_INVALID_ID, "joint id {%u, %u, %u} does not name a "
                     "joint of this world", id.index1, id.world, id.generation);
        return NULL;
    }
    tb_joint_record* j = &w->joints.records[id.index1 - 1];
    if (!j->alive || j->generation != id.generation) {
        *r = tb_fail(&w->diag, TB_ERROR_STALE_ID, "joint id {%u, %u, %u} is stale: the joint "
                     "was destroyed", id.index1, id.world, id.generation);
        return NULL;
    }
    *slot = id.index1 - 1;
    *r = TB_OK;
    return j;
}

tb_joint_id tb_joint_id_of_slot(const tb_world* w, uint32_t slot)
{
    if (slot >= w->joints.slots.used || !w->joints.records[slot].alive) return tb_null_joint;
    return (tb_joint_id){ slot + 1, w->serial, w->joints.records[slot].generation };
}

tb_result tb_world_joints_add(tb_world* w, const tb_joint_def* defs, const uint32_t* a,
                              const uint32_t* b, uint32_t count, tb_joint_id* out)
{
    int grew = 0;
    tb_result r = tb_joints_reserve(&w->joints, &w->transfer, count, &grew);
    if (!r) r = tb_sim_reserve_joints(&w->sim, &w->transfer, w->joints.capacity);
    if (r) return r;
    if (grew) w->buffer_generation++;
    for (uint32_t i = 0; i < count; i++) {
        uint32_t slot = tb_joints_add(&w->joints, &defs[i], a[i], b[i]);
        out[i] = tb_joint_id_of_slot(w, slot);
    }
    if (count) w->joint_ranks_dirty = 1;
    /* The step's joint passes cover the capacity they were recorded for. */
    if (count && w->joint_passes != w->joints.capacity) w->step_built = 0;
    return TB_OK;
}

void tb_world_joint_remove(tb_world* w, uint32_t slot)
{
    tb_joints_remove(&w->joints, slot);
    w->joint_ranks_dirty = 1;
}

void tb_world_joints_of_body_remove(tb_world* w, uint32_t body_slot)
{
    for (uint32_t s = 0; s < w->joints.slots.used; s++) {
        const tb_joint_record* j = &w->joints.records[s];
        if (j->alive && (j->body_a == body_slot || j->body_b == body_slot)) {
            tb_joints_remove(&w->joints, s);
            w->joint_ranks_dirty = 1;
        }
    }
}

uint32_t tb_world_joints_ids(const tb_world* w, tb_joint_id* out, uint32_t capacity)
{
    uint32_t n = 0;
    for (uint32_t s = 0; s < w->joints.slots.used; s++) {
        if (!w->joints.records[s].alive) continue;
        if (out && n < capacity) out[n] = tb_joint_id_of_slot(w, s);
        n++;
    }
    return n;
}
