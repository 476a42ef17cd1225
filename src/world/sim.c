/* The step's GPU-only buffers: creation, growth, binding. */
#include "world/sim.h"

#include "broadphase/pair_split.h"

#include <string.h>

#define USAGE (VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | \
               VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT)

static const uint32_t body_binding[TB_SIM_BODY_BUFFER_COUNT] = {
    [TB_SIM_BODY_PAIRS] = TB_BIND_BODY_PAIRS, [TB_SIM_SOLVER_BODIES] = TB_BIND_SOLVER_BODIES,
    [TB_SIM_BODY_CLAIM] = TB_BIND_BODY_CLAIM, [TB_SIM_BODY_PAIR_COUNT] = TB_BIND_BODY_PAIR_COUNT,
    [TB_SIM_GRID_KEYS] = TB_BIND_GRID_KEYS, [TB_SIM_GRID_BODIES] = TB_BIND_GRID_BODIES,
    [TB_SIM_GRID_TABLE] = TB_BIND_GRID_TABLE, [TB_SIM_LARGE_FLAGS] = TB_BIND_LARGE_FLAGS,
    [TB_SIM_LARGE_LIST] = TB_BIND_LARGE_LIST, [TB_SIM_BODY_SCRATCH] = UINT32_MAX,
    [TB_SIM_BLOCK_START] = TB_BIND_BLOCK_START, [TB_SIM_BLOCK_FILL] = TB_BIND_BLOCK_FILL,
    [TB_SIM_BODY_COLOUR] = TB_BIND_BODY_COLOUR, [TB_SIM_BLOCK_LIST] = TB_BIND_BLOCK_LIST,
    [TB_SIM_BLOCK_TARGET] = TB_BIND_BLOCK_TARGET,
};

/* The contact arrays and the block solver's lists are reached by address
 * (tb_gpu_params.contact_arrays), not bound. */
static const uint32_t pair_binding[TB_SIM_PAIR_BUFFER_COUNT] = {
    [TB_SIM_PAIRS] = TB_BIND_PAIRS, [TB_SIM_MANIFOLDS_EVEN] = UINT32_MAX,
    [TB_SIM_CONSTRAINTS] = UINT32_MAX, [TB_SIM_COLOUR_LIST] = TB_BIND_COLOUR_LIST,
    [TB_SIM_COLOUR_WORK] = TB_BIND_COLOUR_WORK, [TB_SIM_MANIFOLDS_ODD] = UINT32_MAX,
    [TB_SIM_TAIL_SCRATCH] = UINT32_MAX, [TB_SIM_EVENT_MARKS] = UINT32_MAX,
    [TB_SIM_BLOCK_ENTRIES] = UINT32_MAX, [TB_SIM_SPLIT] = UINT32_MAX,
};

/* Bytes per body of each per-body buffer (the table and scratch are sized apart). */
static VkDeviceSize body_bytes(const tb_sim* sim, tb_sim_body_buffer b, uint32_t capacity,
                               uint32_t table_size)
{
    switch (b) {
    case TB_SIM_BODY_PAIRS: return (VkDeviceSize)capacity * 16;
    case TB_SIM_SOLVER_BODIES: return (VkDeviceSize)capacity * sizeof(tb_gpu_solver_body);
    case TB_SIM_BLOCK_LIST: return (VkDeviceSize)capacity * (sim->block_lists ? 16 : 4);
    case TB_SIM_BLOCK_TARGET: return sim->block_lists ? (VkDeviceSize)capacity * 32 : 0;
    case TB_SIM_GRID_TABLE: return (VkDeviceSize)table_size * 8;
    case TB_SIM_BODY_SCRATCH: {
        VkDeviceSize a = tb_prims_sort_scratch(sim->prims, capacity);
        VkDeviceSize s = tb_prims_scan_scratch(sim->prims, capacity);
        VkDeviceSize c = tb_prims_compact_scratch(sim->prims, capacity);
        VkDeviceSize m = a > s ? a : s;
        return m > c ? m : c;
    }
    default: return (VkDeviceSize)capacity * 4;
    }
}

/* Pairs hold two halves (this step's and the previous one's); the manifolds two arrays, of the
 * even and the odd steps, so last step's stay where they were written. */
static VkDeviceSize pair_bytes(const tb_sim* sim, tb_sim_pair_buffer b, uint32_t capacity)
{
    switch (b) {
    case TB_SIM_TAIL_SCRATCH: return tb_prims_compact_scratch(sim->prims, capacity);
    case TB_SIM_PAIRS: return 2 * (VkDeviceSize)capacity * 16;
    case TB_SIM_MANIFOLDS_EVEN:
    case TB_SIM_MANIFOLDS_ODD: return (VkDeviceSize)capacity * sizeof(tb_gpu_manifold);
    case TB_SIM_CONSTRAINTS: return (VkDeviceSize)capacity * sizeof(tb_gpu_constraint);
    case TB_SIM_COLOUR_WORK: return 2 * (VkDeviceSize)capacity * 4;
    case TB_SIM_SPLIT: return tb_pair_split_bytes(sim->prims, capacity);
    case TB_SIM_BLOCK_ENTRIES:
        return sim->block_lists ? (2 * TB_MAX_MANIFOLD_POINTS * (VkDeviceSize)capacity +
                                   2 * (VkDeviceSize)sim->joint_capacity) * 8 : 0;
    default: return (VkDeviceSize)capacity * 4;
    }
}

static tb_diag* diag_of(const tb_sim* sim)
{
    return sim->memory->gpu->diag;
}

uint32_t tb_sim_pair_limit(const tb_sim* sim)
{
    const tb_gpu* gpu = sim->memory->gpu;
    /* Bound arrays: the pairs' two halves are the largest. Addressed ones: one allocation. */
    uint64_t by_range = gpu->props.limits.maxStorageBufferRange / pair_bytes(sim, TB_SIM_PAIRS, 1);
    uint64_t by_allocation = gpu->max_allocation / pair_bytes(sim, TB_SIM_CONSTRAINTS, 1);
    uint64_t limit = TB_MAX_PAIR_CAPACITY;
    if (by_range < limit) limit = by_range;
    if (by_allocation && by_allocation < limit) limit = by_allocation;
    return (uint32_t)limit;
}

static tb_result check_range(const tb_sim* sim, VkDeviceSize bytes, const char* what)
{
    VkDeviceSize range = sim->memory->gpu->props.limits.maxStorageBufferRange;
    if (bytes <= range) return TB_OK;
    return tb_fail(diag_of(sim), TB_ERROR_CAPACITY, "the %s need a %llu-byte buffer, beyond this "
                   "device's storage buffer range of %llu bytes", what,
                   (unsigned long long)bytes, (unsigned long long)range);
}

/* Replace `old` (may be empty) by a zeroed buffer of `bytes`, copying `regions` over. */
static tb_result replace(tb_sim* sim, tb_transfer* t, tb_buffer* old, VkDeviceSize bytes,
                         const VkBufferCopy* regions, uint32_t region_count, uint32_t fill,
                         tb_buffer* out)
{
    tb_result r = tb_buffer_create(sim->memory, bytes ? bytes : 16, USAGE, 0, out);
    if (r) return r;
    vkCmdFillBuffer(t->cb, out->buffer, 0, VK_WHOLE_SIZE, fill);
    if (old->buffer && region_count) {
        VkMemoryBarrier fill_first = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT, .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT };
        vkCmdPipelineBarrier(t->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             0, 1, &fill_first, 0, NULL, 0, NULL);
        vkCmdCopyBuffer(t->cb, old->buffer, out->buffer, region_count, regions);
    }
    return TB_OK;
}

/* Run the transfer, then keep the new buffers (or, on failure, drop them). */
static tb_result finish(tb_sim* sim, tb_transfer* t, tb_buffer* olds, tb_buffer* news,
                        const uint32_t* bindings, uint32_t count, tb_result r)
{
    tb_result e = tb_transfer_end(t);
    if (!r) r = e;
    if (!r) r = tb_gpu_submit_wait(sim->memory->gpu, &t->cb, 1);
    for (uint32_t i = 0; i < count; i++) {
        if (!news[i].buffer) continue;
        tb_buffer_destroy(sim->memory, r ? &news[i] : &olds[i]);
        if (r) continue;
        olds[i] = news[i];
        if (bindings[i] != UINT32_MAX) tb_pipelines_bind(sim->pipelines, bindings[i], olds[i].buffer);
    }
    return r;
}

static uint32_t table_bits_for(uint32_t capacity)
{
    uint32_t bits = 4;
    while ((1u << bits) < 2 * capacity && bits < 30) bits++;
    return bits;
}

/* New per-body buffers for `capacity` bodies, the body pairs kept. */
static tb_result resize_bodies(tb_sim* sim, tb_transfer* t, uint32_t capacity)
{
    uint32_t bits = table_bits_for(capacity);
    tb_buffer fresh[TB_SIM_BODY_BUFFER_COUNT];
    memset(fresh, 0, sizeof fresh);
    tb_result r = check_range(sim, body_bytes(sim, TB_SIM_SOLVER_BODIES, capacity, 0), "bodies");
    if (!r) r = tb_transfer_begin(t, 0);
    if (r) return r;
    for (int b = 0; b < TB_SIM_BODY_BUFFER_COUNT && !r; b++) {
        VkDeviceSize keep = b == TB_SIM_BODY_PAIRS ? body_bytes(sim, b, sim->body_capacity, 0) : 0;
        VkBufferCopy region = { 0, 0, keep };
        /* Claims start free (all ones: any claim is smaller). */
        uint32_t fill = b == TB_SIM_BODY_CLAIM ? 0xffffffffu : 0u;
        r = replace(sim, t, &sim->body[b], body_bytes(sim, b, capacity, 1u << bits), &region,
                    keep ? 1 : 0, fill, &fresh[b]);
    }
    r = finish(sim, t, sim->body, fresh, body_binding, TB_SIM_BODY_BUFFER_COUNT, r);
    if (r) return r;
    sim->body_capacity = capacity;
    sim->table_bits = bits;
    sim->table_size = 1u << bits;
    sim->growths++;
    return TB_OK;
}

tb_result tb_sim_reserve_bodies(tb_sim* sim, tb_transfer* t, uint32_t capacity)
{
    if (capacity <= sim->body_capacity && sim->body[0].buffer) return TB_OK;
    return resize_bodies(sim, t, capacity);
}

/* New pair buffers for `pairs` pairs a half, the pairs and last step's manifolds kept. */
static tb_result resize_pairs(tb_sim* sim, tb_transfer* t, uint32_t pairs)
{
    if (pairs > tb_sim_pair_limit(sim))
        return tb_fail(diag_of(sim), TB_ERROR_CAPACITY, "%u pairs are more than the %u this "
                       "device's buffers (and the solver's colouring) can hold", pairs,
                       tb_sim_pair_limit(sim));
    tb_buffer fresh[TB_SIM_PAIR_BUFFER_COUNT];
    memset(fresh, 0, sizeof fresh);
    tb_result r = tb_transfer_begin(t, 0);
    if (r) return r;
    for (int b = 0; b < TB_SIM_PAIR_BUFFER_COUNT && !r; b++) {
        /* Both halves of the pairs move to their new places (half h starts at h * capacity);
         * both manifold arrays (one is last step's) keep their indices. */
        VkDeviceSize old = pair_bytes(sim, b, sim->pair_capacity);
        VkDeviceSize half_old = old / 2, half_new = pair_bytes(sim, b, pairs) / 2;
        VkBufferCopy halves[2] = { { 0, 0, half_old }, { half_old, half_new, half_old } };
        VkBufferCopy whole = { 0, 0, old };
        uint32_t n = !old ? 0 : b == TB_SIM_PAIRS ? 2 : tb_sim_is_manifolds(b) ? 1 : 0;
        r = replace(sim, t, &sim->pair[b], pair_bytes(sim, b, pairs), b == TB_SIM_PAIRS ? halves : &whole,
                    n, 0, &fresh[b]);
    }
    r = finish(sim, t, sim->pair, fresh, pair_binding, TB_SIM_PAIR_BUFFER_COUNT, r);
    if (r) return r;
    sim->pair_capacity = pairs;
    sim->growths++;
    return TB_OK;
}

tb_result tb_sim_reserve_pairs(tb_sim* sim, tb_transfer* t, uint32_t pairs)
{
    if (pairs <= sim->pair_capacity && sim->pair[0].buffer) return TB_OK;
    return resize_pairs(sim, t, pairs);
}

tb_result tb_sim_reserve_joints(tb_sim* sim, tb_transfer* t, uint32_t joints)
{
    if (joints <= sim->joint_capacity) return TB_OK;
    uint32_t before = sim->joint_capacity;
    sim->joint_capacity = joints;
    tb_buffer fresh = { 0 };
    tb_result r = tb_transfer_begin(t, 0);
    if (r) {
        sim->joint_capacity = before;
        return r;
    }
    r = replace(sim, t, &sim->pair[TB_SIM_BLOCK_ENTRIES],
                pair_bytes(sim, TB_SIM_BLOCK_ENTRIES, sim->pair_capacity), NULL, 0, 0, &fresh);
    uint32_t binding = UINT32_MAX;
    r = finish(sim, t, &sim->pair[TB_SIM_BLOCK_ENTRIES], &fresh, &binding, 1, r);
    if (r) sim->joint_capacity = before;
    return r;
}

tb_result tb_sim_set_block_lists(tb_sim* sim, tb_transfer* t, int on)
{
    /* Buffers sized for the lists serve a world without them as well: turning them off
     * only sizes later growth without them. */
    if (!on || sim->block_lists) {
        sim->block_lists = on;
        return TB_OK;
    }
    uint32_t pairs = sim->pair_capacity;
    sim->block_lists = 1;
    uint32_t limit = tb_sim_pair_limit(sim);
    tb_result r = resize_bodies(sim, t, sim->body_capacity);
    if (!r) r = resize_pairs(sim, t, pairs < limit ? pairs : limit);
    if (r) sim->block_lists = 0;
    return r;
}

tb_result tb_sim_init(tb_sim* sim, tb_memory* memory, tb_pipelines* pipelines, tb_prims* prims,
                      tb_transfer* t, uint32_t body_capacity, uint64_t pair_capacity,
                      int block_lists)
{
    memset(sim, 0, sizeof *sim);
    sim->block_lists = block_lists;
    sim->memory = memory;
    sim->pipelines = pipelines;
    sim->prims = prims;
    tb_result r = tb_buffer_create(memory, sizeof(tb_gpu_counters), USAGE, 0, &sim->counters);
    if (!r) r = tb_buffer_create(memory, sizeof(tb_gpu_counters),
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, 1, &sim->readback);
    if (r) return r;
    memset(sim->readback.mapped, 0, sizeof(tb_gpu_counters));
    tb_pipelines_bind(pipelines, TB_BIND_COUNTERS, sim->counters.buffer);
    r = tb_transfer_begin(t, 0);
    if (r) return r;
    vkCmdFillBuffer(t->cb, sim->counters.buffer, 0, VK_WHOLE_SIZE, 0);
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(memory->gpu, &t->cb, 1);
    if (!r) r = tb_sim_reserve_bodies(sim, t, body_capacity);
    uint32_t limit = tb_sim_pair_limit(sim);
    if (!r) r = tb_sim_reserve_pairs(sim, t, pair_capacity < limit ? (uint32_t)pair_capacity : limit);
    sim->growths = 0;
    return r;
}

void tb_sim_destroy(tb_sim* sim)
{
    if (!sim->memory) return;
    for (int b = 0; b < TB_SIM_BODY_BUFFER_COUNT; b++) tb_buffer_destroy(sim->memory, &sim->body[b]);
    for (int b = 0; b < TB_SIM_PAIR_BUFFER_COUNT; b++) tb_buffer_destroy(sim->memory, &sim->pair[b]);
    tb_buffer_destroy(sim->memory, &sim->counters);
    tb_buffer_destroy(sim->memory, &sim->readback);
    memset(sim, 0, sizeof *sim);
}

const tb_gpu_counters* tb_sim_counters(const tb_sim* sim)
{
    return (const tb_gpu_counters*)sim->readback.mapped;
}
