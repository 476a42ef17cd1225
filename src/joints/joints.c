/* The joint table on the host and its GPU image (joints.h). */
#include "joints/joints.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/device.h"

#define USAGE (VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | \
               VK_BUFFER_USAGE_TRANSFER_DST_BIT)
#define FIRST_CAPACITY 16u

static tb_diag* diag_of(const tb_joints* j)
{
    return j->memory->gpu->diag;
}

/* New GPU arrays for `capacity` slots, the old state copied over (the rest zeroed: a
 * state of generation 0 belongs to no joint). */
static tb_result replace_arrays(tb_joints* j, tb_transfer* t, uint32_t capacity)
{
    tb_buffer joints = { 0 }, state = { 0 };
    tb_result r = tb_buffer_create(j->memory, (VkDeviceSize)capacity * sizeof(tb_gpu_joint),
                                   USAGE, 0, &joints);
    if (!r) r = tb_buffer_create(j->memory, (VkDeviceSize)capacity * sizeof(tb_gpu_joint_state),
                                 USAGE, 0, &state);
    if (!r) r = tb_transfer_begin(t, 64);
    if (!r) {
        vkCmdFillBuffer(t->cb, joints.buffer, 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(t->cb, state.buffer, 0, VK_WHOLE_SIZE, 0);
        if (j->state.buffer) {
            VkMemoryBarrier fill_first = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT };
            vkCmdPipelineBarrier(t->cb, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &fill_first, 0, NULL, 0,
                                 NULL);
            VkBufferCopy copy = { 0, 0, (VkDeviceSize)j->capacity * sizeof(tb_gpu_joint_state) };
            vkCmdCopyBuffer(t->cb, j->state.buffer, state.buffer, 1, &copy);
        }
        r = tb_transfer_end(t);
    }
    if (!r) r = tb_gpu_submit_wait(j->memory->gpu, &t->cb, 1);
    if (r) {
        tb_buffer_destroy(j->memory, &joints);
        tb_buffer_destroy(j->memory, &state);
        return r;
    }
    tb_buffer_destroy(j->memory, &j->joints);
    tb_buffer_destroy(j->memory, &j->state);
    j->joints = joints;
    j->state = state;
    j->table_dirty = 1;
    return TB_OK;
}

/* Host records and table for `capacity` slots, the new ones zeroed. */
static tb_result grow_host(tb_joints* j, uint32_t capacity)
{
    tb_joint_record* records = realloc(j->records, (size_t)capacity * sizeof *records);
    if (records) j->records = records;
    tb_gpu_joint* table = realloc(j->table, (size_t)capacity * sizeof *table);
    if (table) j->table = table;
    if (!records || !table)
        return tb_fail(diag_of(j), TB_ERROR_OUT_OF_MEMORY, "out of host memory for joints");
    size_t old = j->capacity;
    memset(records + old, 0, (capacity - old) * sizeof *records);
    memset(table + old, 0, (capacity - old) * sizeof *table);
    return TB_OK;
}

tb_result tb_joints_init(tb_joints* j, tb_memory* memory, tb_transfer* t)
{
    memset(j, 0, sizeof *j);
    j->memory = memory;
    tb_result r = grow_host(j, FIRST_CAPACITY);
    if (!r) r = replace_arrays(j, t, FIRST_CAPACITY);
    if (!r) j->capacity = FIRST_CAPACITY;
    return r;
}

void tb_joints_destroy(tb_joints* j)
{
    if (!j->memory) return;
    tb_buffer_destroy(j->memory, &j->joints);
    tb_buffer_destroy(j->memory, &j->state);
    tb_buffer_destroy(j->memory, &j->filter);
    tb_slots_free(&j->slots);
    free(j->records);
    free(j->table);
    free(j->filter_host);
    memset(j, 0, sizeof *j);
}

tb_result tb_joints_reserve(tb_joints* j, tb_transfer* t, uint32_t count, int* grew)
{
    *grew = 0;
    uint32_t fresh = count > j->slots.free_count ? count - j->slots.free_count : 0;
    uint64_t need = (uint64_t)j->slots.used + fresh;
    if (need <= j->capacity) return TB_OK;
    if (need > TB_MAX_JOINTS)
        return tb_fail(diag_of(j), TB_ERROR_CAPACITY, "%u more joints would pass the limit of "
                       "TB_MAX_JOINTS (%u)", count, (unsigned)TB_MAX_JOINTS);
    uint32_t capacity = j->capacity;
    while (capacity < need) capacity *= 2;
    tb_result r = grow_host(j, capacity);
    if (!r) r = replace_arrays(j, t, capacity);
    if (r) return r;
    j->capacity = capacity;
    *grew = 1;
    return TB_OK;
}

static tb_gpu_vec4 vec4_of(tb_vec3 v, float w)
{
    return (tb_gpu_vec4){ v.x, v.y, v.z, w };
}

static tb_gpu_vec4 unit_quat(tb_quat q)
{
    float n = sqrtf(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return (tb_gpu_vec4){ q.x / n, q.y / n, q.z / n, q.w / n };
}

/* A 6-dof def's axes: their limits into g, their modes as info.z's flags. */
static uint32_t six_dof_axes(const tb_joint_def* d, tb_gpu_joint* g)
{
    float* lower[6] = { &g->lower.x, &g->lower.y, &g->lower.z,
                        &g->turn_lower.x, &g->turn_lower.y, &g->turn_lower.z };
    float* upper[6] = { &g->upper.x, &g->upper.y, &g->upper.z,
                        &g->turn_upper.x, &g->turn_upper.y, &g->turn_upper.z };
    uint32_t flags = 0;
    for (int i = 0; i < 6; i++) {
        const tb_joint_axis* x = &d->axes[i];
        uint32_t mode = (uint32_t)x->mode;   /* checked: one of the three */
        flags |= mode << (TB_GPU_JOINT_AXIS_SHIFT + 2 * i);
        *lower[i] = mode == TB_GPU_JOINT_AXIS_LIMITED ? x->lower : 0.0f;
        *upper[i] = mode == TB_GPU_JOINT_AXIS_LIMITED ? x->upper : 0.0f;
    }
    return flags;
}

/* The GPU record of a def whose bodies are slots a and b. */
static tb_gpu_joint gpu_joint_of(const tb_joint_def* d, uint32_t a, uint32_t b,
                                 uint16_t generation)
{
    uint32_t flags = (d->enable_limit ? TB_GPU_JOINT_LIMIT : 0) |
                     (d->enable_motor ? TB_GPU_JOINT_MOTOR : 0) |
                     (d->enable_spring ? TB_GPU_JOINT_SPRING : 0) |
                     (d->break_force > 0 || d->break_torque > 0 ? TB_GPU_JOINT_BREAKABLE : 0) |
                     (d->constraint_hertz > 0 ? TB_GPU_JOINT_SOFT : 0);
    tb_gpu_joint g;
    memset(&g, 0, sizeof g);
    if (d->kind == TB_JOINT_SIX_DOF) flags |= six_dof_axes(d, &g);
    g.lower.w = d->constraint_hertz;
    g.upper.w = d->constraint_damping_ratio;
    g.info = (tb_gpu_uvec4){ a, b, (uint32_t)d->kind | flags, generation };
    g.anchor_a = vec4_of(d->anchor_a, d->kind == TB_JOINT_DISTANCE ? d->length : d->spring_target);
    g.anchor_b = vec4_of(d->anchor_b, d->spring_hertz);
    g.frame_a = unit_quat(d->frame_a);
    g.frame_b = unit_quat(d->frame_b);
    g.limit = (tb_gpu_vec4){ d->lower, d->upper, d->spring_damping_ratio, d->cone_angle };
    g.motor = (tb_gpu_vec4){ d->motor_speed, d->max_motor_force, d->break_force,
                             d->break_torque };
    return g;
}

uint32_t tb_joints_add(tb_joints* j, const tb_joint_def* def, uint32_t a, uint32_t b)
{
    uint32_t slot;
    tb_slots_take(&j->slots, &slot);
    tb_joint_record* rec = &j->records[slot];
    rec->generation = tb_next_generation(rec->generation);
    rec->alive = 1;
    rec->body_a = a;
    rec->body_b = b;
    rec->def = *def;
    j->table[slot] = gpu_joint_of(def, a, b, rec->generation);
    j->table_dirty = 1;
    if (!def->collide_connected) {
        j->no_collide++;
        j->filter_dirty = 1;
    }
    return slot;
}

void tb_joints_remove(tb_joints* j, uint32_t slot)
{
    tb_joint_record* rec = &j->records[slot];
    if (!rec->def.collide_connected) {
        j->no_collide--;
        j->filter_dirty = 1;
    }
    rec->alive = 0;
    rec->def.user_data = NULL;
    memset(&j->table[slot], 0, sizeof j->table[slot]);
    j->table_dirty = 1;
    tb_slots_give(&j->slots, slot);
}

void tb_joints_changed(tb_joints* j, uint32_t slot)
{
    const tb_joint_record* rec = &j->records[slot];
    j->table[slot] = gpu_joint_of(&rec->def, rec->body_a, rec->body_b, rec->generation);
    j->table_dirty = 1;
}

/* The filter's entries for `count` pairs: a power of two at least twice as many. */
static uint32_t filter_size_for(uint32_t count)
{
    uint32_t size = 16;
    while (size < 2 * count) size *= 2;
    return size;
}

static void filter_insert(uint32_t* table, uint32_t size, uint32_t a, uint32_t b)
{
    uint32_t lo = (a < b ? a : b) + 1, hi = (a < b ? b : a) + 1;
    uint32_t h = TB_JOINT_FILTER_HASH(lo, hi) & (size - 1);
    while (table[2 * h] && !(table[2 * h] == lo && table[2 * h + 1] == hi))
        h = (h + 1) & (size - 1);
    table[2 * h] = lo;
    table[2 * h + 1] = hi;
}

tb_result tb_joints_prepare(tb_joints* j)
{
    if (!j->filter_dirty) return TB_OK;
    if (!j->no_collide) {
        j->filter_size = 0;
        j->filter_dirty = 0;
        return TB_OK;
    }
    uint32_t size = filter_size_for(j->no_collide);
    if (size > j->filter_capacity) {
        tb_buffer fresh = { 0 };
        uint32_t* host = realloc(j->filter_host, (size_t)size * 8);
        if (!host) return tb_fail(diag_of(j), TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        j->filter_host = host;
        tb_result r = tb_buffer_create(j->memory, (VkDeviceSize)size * 8, USAGE, 0, &fresh);
        if (r) return r;
        tb_buffer_destroy(j->memory, &j->filter);
        j->filter = fresh;
        j->filter_capacity = size;
    }
    memset(j->filter_host, 0, (size_t)size * 8);
    for (uint32_t s = 0; s < j->slots.used; s++) {
        const tb_joint_record* rec = &j->records[s];
        if (rec->alive && !rec->def.collide_connected)
            filter_insert(j->filter_host, size, rec->body_a, rec->body_b);
    }
    j->filter_size = size;
    return TB_OK;
}

VkDeviceSize tb_joints_upload_bytes(const tb_joints* j)
{
    VkDeviceSize bytes = 0;
    if (j->table_dirty) bytes += (VkDeviceSize)j->slots.used * sizeof(tb_gpu_joint) + 16;
    if (j->filter_dirty && j->filter_size) bytes += (VkDeviceSize)j->filter_size * 8 + 16;
    return bytes;
}

void tb_joints_record_uploads(tb_joints* j, tb_transfer* t)
{
    if (j->table_dirty && j->slots.used) {
        VkDeviceSize bytes = (VkDeviceSize)j->slots.used * sizeof(tb_gpu_joint);
        void* dst = tb_transfer_upload(t, j->joints.buffer, 0, bytes);
        if (dst) memcpy(dst, j->table, bytes);
    }
    if (j->filter_dirty && j->filter_size) {
        VkDeviceSize bytes = (VkDeviceSize)j->filter_size * 8;
        void* dst = tb_transfer_upload(t, j->filter.buffer, 0, bytes);
        if (dst) memcpy(dst, j->filter_host, bytes);
    }
    j->table_dirty = 0;
    j->filter_dirty = 0;
}

tb_gpu_uvec4 tb_joints_params(const tb_joints* j)
{
    VkDeviceAddress filter = j->filter_size ? j->filter.address : 0;
    return (tb_gpu_uvec4){ j->slots.used, j->filter_size, (uint32_t)filter,
                           (uint32_t)(filter >> 32) };
}

tb_result tb_joints_read_state(tb_joints* j, tb_transfer* t, const uint32_t* slots,
                               uint32_t count, tb_gpu_joint_state* out)
{
    if (!count) return TB_OK;
    uint32_t last = 0;
    for (uint32_t i = 0; i < count; i++) last = slots[i] > last ? slots[i] : last;
    VkDeviceSize bytes = (VkDeviceSize)(last + 1) * sizeof(tb_gpu_joint_state);
    tb_result r = tb_transfer_begin(t, bytes + 64);
    if (r) return r;
    const void* landed = tb_transfer_download(t, j->state.buffer, 0, bytes);
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(j->memory->gpu, &t->cb, 1);
    if (r) return r;
    for (uint32_t i = 0; i < count; i++)
        memcpy(&out[i], (const tb_gpu_joint_state*)landed + slots[i], sizeof out[i]);
    return TB_OK;
}
