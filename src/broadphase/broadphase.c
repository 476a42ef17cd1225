/* What every broadphase shares: the choice, the pair output's passes, push constants,
 * buffers. */
#include "broadphase/broadphase.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* The library's choice for TB_BROADPHASE_DEFAULT (README, performance): the LBVH was the
 * fastest on every pile of 100k and 1M bodies measured, mixed sizes included, and within
 * 0.12 ms of the best at 10k; no scene makes it degrade as mixed sizes do the grid and
 * dense piles the sort and sweep. */
#define DEFAULT_BROADPHASE TB_BROADPHASE_LBVH

static const tb_broadphase_ops* const ops_table[] = {
    [TB_BROADPHASE_GRID] = &tb_broadphase_grid,
    [TB_BROADPHASE_SAP] = &tb_broadphase_sap,
    [TB_BROADPHASE_LBVH] = &tb_broadphase_lbvh,
    [TB_BROADPHASE_ISAP] = &tb_broadphase_isap,
};
#define KINDS (sizeof ops_table / sizeof ops_table[0])

const char* tb_broadphase_name(tb_broadphase kind)
{
    static const char* const names[] = { "default", "grid", "sap", "lbvh", "isap" };
    return (uint32_t)kind < sizeof names / sizeof names[0] ? names[kind] : NULL;
}

const tb_broadphase_ops* tb_broadphase_ops_of(tb_broadphase kind)
{
    return kind > TB_BROADPHASE_DEFAULT && (uint32_t)kind < KINDS ? ops_table[kind] : NULL;
}

tb_result tb_broadphase_resolve(tb_diag* diag, tb_broadphase asked, tb_broadphase* out)
{
    *out = asked;
    if (asked != TB_BROADPHASE_DEFAULT) {
        if (tb_broadphase_ops_of(asked)) return TB_OK;
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "broadphase %d is not one of "
                       "TB_BROADPHASE_GRID, _SAP, _LBVH or _ISAP", (int)asked);
    }
    *out = DEFAULT_BROADPHASE;
    const char* env = getenv("TUMBLE_BROADPHASE");
    if (!env || !*env) return TB_OK;
    for (uint32_t k = 1; k < KINDS; k++)
        if (strcasecmp(env, tb_broadphase_name((tb_broadphase)k)) == 0 && ops_table[k]) {
            *out = (tb_broadphase)k;
            return TB_OK;
        }
    return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "TUMBLE_BROADPHASE is '%s'; it must be "
                   "grid, sap, lbvh or isap", env);
}

tb_result tb_broadphase_shared_create(tb_broadphase_ctx* bp)
{
    tb_result r = tb_pipeline_create(bp->kit.pipelines, "broadphase/world_aabb",
                                     TB_WORKGROUP_SIZE, &bp->world_aabb);
    if (!r) r = tb_pipeline_create(bp->kit.pipelines, "broadphase/pair_check",
                                   TB_WORKGROUP_SIZE, &bp->pair_check);
    return r;
}

void tb_broadphase_destroy_pipelines(tb_broadphase_ctx* bp, const VkPipeline* pipelines, size_t count)
{
    for (size_t i = 0; i < count; i++)
        tb_pipeline_destroy(bp->kit.pipelines, pipelines[i]);
}

void tb_broadphase_shared_destroy(tb_broadphase_ctx* bp)
{
    VkPipeline shared[] = { bp->world_aabb, bp->pair_check };
    tb_broadphase_destroy_pipelines(bp, shared, 2);
    bp->world_aabb = bp->pair_check = VK_NULL_HANDLE;
}

tb_pass tb_broadphase_pass(VkPipeline pipeline, tb_dispatch_rule rule, uint32_t groups,
                           tb_gpu_ptr indirect, const tb_gpu_broadphase_push* push)
{
    tb_pass pass;
    memset(&pass, 0, sizeof pass);
    pass.pipeline = pipeline;
    pass.rule = rule;
    pass.groups[0] = groups ? groups : 1;
    pass.groups[1] = pass.groups[2] = 1;
    pass.indirect = indirect.buffer;
    pass.indirect_offset = indirect.offset;
    pass.push_size = sizeof *push;
    memcpy(pass.push, push, sizeof *push);
    return pass;
}

tb_result tb_broadphase_add(tb_broadphase_ctx* bp, tb_pass_list* list, VkPipeline pipeline,
                            tb_dispatch_rule rule, uint32_t groups, tb_gpu_ptr indirect,
                            const tb_gpu_broadphase_push* push)
{
    tb_pass pass = tb_broadphase_pass(pipeline, rule, groups, indirect, push);
    return tb_pass_list_add(list, bp->kit.diag, &pass);
}

tb_result tb_broadphase_record_world_aabb(tb_broadphase_ctx* bp, tb_pass_list* list,
                                          VkBuffer counters)
{
    tb_pass pass = tb_pass_with_args(bp->world_aabb, TB_DISPATCH_PER_BODY, counters, 0, 0, 0, 0);
    return tb_pass_list_add(list, bp->kit.diag, &pass);
}

tb_result tb_broadphase_record_pair_output(tb_broadphase_ctx* bp, tb_pass_list* list,
                                           const tb_broadphase_search* search)
{
    const tb_broadphase_io* io = &bp->io;
    tb_gpu_ptr counts = io->body_pair_counts;
    tb_pass check = tb_pass_with_args(bp->pair_check, TB_DISPATCH_FIXED, VK_NULL_HANDLE, 0, 0, 0, 0);
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < search->n && !r; i++)
        r = tb_pass_list_add(list, bp->kit.diag, &search->counts[i]);
    if (!r) r = tb_prims_scan(bp->kit.prims, list, counts, counts, io->slots, io->body_capacity,
                              io->pair_count, io->scratch);
    if (!r) r = tb_pass_list_add(list, bp->kit.diag, &check);
    for (uint32_t i = 0; i < search->n && !r; i++)
        r = tb_pass_list_add(list, bp->kit.diag, &search->writes[i]);
    return r;
}

tb_result tb_broadphase_buffer(tb_broadphase_ctx* bp, VkDeviceSize bytes, tb_buffer* out)
{
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    return tb_buffer_create(bp->kit.memory, bytes, usage, 0, out);
}
