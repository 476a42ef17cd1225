/* Distance queries between convex shapes placed by poses (tb_world_query_distances): the
 * queries go to a host-visible buffer, query/distance runs one thread per query (in
 * dispatches of at most 65,535 workgroups), and the results are read where the GPU wrote
 * them. The shapes and hulls go to the GPU first, as a step would send them. */
#include <string.h>

#include "gpu/prims.h"
#include "world/world.h"

#define QUERY_WORKGROUP 64u
#define QUERY_GROUPS_PER_DISPATCH 65535u

static void results_to_host(VkCommandBuffer cb)
{
    VkMemoryBarrier barrier = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT };
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                         1, &barrier, 0, NULL, 0, NULL);
}

/* One dispatch of up to QUERY_GROUPS_PER_DISPATCH workgroups from query `first` on. */
static void record_dispatch(tb_world* w, VkCommandBuffer cb, const tb_buffer* queries,
                            const tb_buffer* results, uint32_t first, uint32_t count)
{
    uint32_t left = count - first, per = QUERY_GROUPS_PER_DISPATCH * QUERY_WORKGROUP;
    uint32_t n = left < per ? left : per;
    tb_gpu_distance_push push = {
        .arrays = tb_gpu_addresses(queries->address, results->address),
        .range = { first, count, 0, 0 },
    };
    tb_pass pass = { .pipeline = w->distance_query, .rule = TB_DISPATCH_FIXED,
                     .groups = { (n + QUERY_WORKGROUP - 1) / QUERY_WORKGROUP, 1, 1 },
                     .push_size = sizeof push };
    memcpy(pass.push, &push, sizeof push);
    tb_passes_record(cb, w->pipelines.layout, &pass, 1, w->params_buffer.buffer);
}

static tb_result run_queries(tb_world* w, const tb_buffer* queries, const tb_buffer* results,
                             uint32_t count)
{
    tb_result r = w->query_cb ? TB_OK : tb_gpu_command_buffer(&w->gpu, &w->query_cb);
    if (r) return r;
    VkCommandBuffer cb = w->query_cb;
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT };
    r = tb_vk_check(&w->diag, vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
    if (r) return r;
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, w->pipelines.layout, 0, 1,
                            &w->pipelines.set, 0, NULL);
    for (uint32_t first = 0; first < count;
         first += QUERY_GROUPS_PER_DISPATCH * QUERY_WORKGROUP)
        record_dispatch(w, cb, queries, results, first, count);
    results_to_host(cb);
    r = tb_vk_check(&w->diag, vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    return r ? r : tb_gpu_submit_wait(&w->gpu, &cb, 1);
}

tb_result tb_world_distances(tb_world* w, const tb_gpu_distance_query* in, uint32_t count,
                             tb_gpu_distance_result* out)
{
    tb_result r = tb_world_flush(w);
    if (!r && !w->distance_query)
        r = tb_pipeline_create(&w->pipelines, "query/distance", QUERY_WORKGROUP,
                               &w->distance_query);
    if (r || !count) return r;
    tb_buffer queries = { 0 }, results = { 0 };
    r = tb_buffer_create(&w->memory, (VkDeviceSize)count * sizeof *in,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, &queries);
    if (!r) r = tb_buffer_create(&w->memory, (VkDeviceSize)count * sizeof *out,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, &results);
    if (!r) {
        memcpy(queries.mapped, in, (size_t)count * sizeof *in);
        r = run_queries(w, &queries, &results, count);
    }
    if (!r) memcpy(out, results.mapped, (size_t)count * sizeof *out);
    tb_buffer_destroy(&w->memory, &queries);
    tb_buffer_destroy(&w->memory, &results);
    return r;
}
