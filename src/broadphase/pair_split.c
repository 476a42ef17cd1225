/* The midphase split's passes (pair_split.h). */
#include "broadphase/pair_split.h"

#include <stddef.h>
#include <string.h>

#include "broadphase/broadphase.h"
#include "layout.h"

/* Where the split buffer's parts start. */
static VkDeviceSize counts_at(uint32_t capacity)
{
    return (VkDeviceSize)capacity * 16;
}

static VkDeviceSize scratch_at(uint32_t capacity)
{
    VkDeviceSize end = counts_at(capacity) + (VkDeviceSize)capacity * 4;
    return (end + 255) & ~(VkDeviceSize)255;
}

VkDeviceSize tb_pair_split_bytes(const tb_prims* prims, uint32_t pair_capacity)
{
    return scratch_at(pair_capacity) + tb_prims_scan_scratch(prims, pair_capacity);
}

static tb_result make(tb_pair_split* s, const char* name, VkPipeline* out)
{
    if (*out) return TB_OK;
    return tb_pipeline_create(s->kit.pipelines, name, TB_WORKGROUP_SIZE, out);
}

static tb_result make_all(tb_pair_split* s)
{
    tb_result r = make(s, "midphase/split_count", &s->count);
    if (!r) r = make(s, "midphase/split_check", &s->check);
    if (!r) r = make(s, "midphase/split_write", &s->write);
    if (!r) r = make(s, "midphase/split_runs", &s->runs);
    if (!r) r = make(s, "midphase/split_copy", &s->copy);
    return r;
}

/* A pass of a split kernel (tb_broadphase_pass): whether apart body pairs are kept, and
 * the split pairs' and counts' addresses, in its push constants; indirect passes run over
 * counters.pair_dispatch. */
static tb_result add(tb_pair_split* s, tb_pass_list* list, VkPipeline pipeline,
                     tb_dispatch_rule rule, const tb_pair_split_io* io)
{
    tb_gpu_broadphase_push push;
    memset(&push, 0, sizeof push);
    push.args.x = io->keep_apart ? 1u : 0u;
    push.address[0] = tb_gpu_addresses(tb_gpu_ptr_of(io->split, 0).address,
                                       tb_gpu_ptr_of(io->split, counts_at(io->pair_capacity)).address);
    tb_gpu_ptr dispatch = tb_gpu_ptr_of(io->counters, TB_COUNTERS_PAIR_DISPATCH_OFFSET);
    tb_pass pass = tb_broadphase_pass(pipeline, rule, 1, dispatch, &push);
    return tb_pass_list_add(list, s->kit.diag, &pass);
}

tb_result tb_pair_split_record(tb_pair_split* s, tb_pass_list* list, const tb_pair_split_io* io)
{
    tb_result r = make_all(s);
    uint32_t capacity = io->pair_capacity;
    tb_gpu_ptr counts = tb_gpu_ptr_of(io->split, counts_at(capacity));
    tb_gpu_ptr scratch = tb_gpu_ptr_of(io->split, scratch_at(capacity));
    tb_gpu_ptr records = tb_gpu_ptr_of(io->counters, offsetof(tb_gpu_counters, state) + 8);
    tb_gpu_ptr total = tb_gpu_ptr_of(io->counters, offsetof(tb_gpu_counters, grid) + 12);
    if (!r) r = add(s, list, s->count, TB_DISPATCH_INDIRECT, io);
    if (!r) r = tb_prims_scan(s->kit.prims, list, counts, counts, records, capacity, total,
                              scratch);
    if (!r) r = add(s, list, s->check, TB_DISPATCH_FIXED, io);
    if (!r) r = add(s, list, s->write, TB_DISPATCH_INDIRECT, io);
    if (!r) r = add(s, list, s->runs, TB_DISPATCH_PER_BODY, io);
    if (!r) r = add(s, list, s->copy, TB_DISPATCH_INDIRECT, io);
    return r;
}

void tb_pair_split_destroy(tb_pair_split* s)
{
    VkPipeline all[] = { s->count, s->check, s->write, s->runs, s->copy };
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        tb_pipeline_destroy(s->kit.pipelines, all[i]);
    *s = (tb_pair_split){ .kit = s->kit };
}
