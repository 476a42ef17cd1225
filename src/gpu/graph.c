/* Recording the step graph into one command buffer. */
#include "gpu/graph.h"

#include <stdlib.h>
#include <string.h>

#include "layout.h"

tb_result tb_graph_init(tb_graph* graph, tb_gpu* gpu, tb_pipelines* pipelines)
{
    memset(graph, 0, sizeof *graph);
    graph->gpu = gpu;
    graph->pipelines = pipelines;
    graph->needs_record = 1;
    return tb_gpu_command_buffer(gpu, &graph->cb);
}

static void destroy_queries(tb_graph* graph)
{
    if (graph->queries) vkDestroyQueryPool(graph->gpu->device, graph->queries, NULL);
    graph->queries = VK_NULL_HANDLE;
}

static void release_stage(tb_stage* stage)
{
    free(stage->passes);
    memset(stage, 0, sizeof *stage);
}

void tb_graph_clear(tb_graph* graph)
{
    for (uint32_t i = 0; i < graph->count; i++) release_stage(&graph->stages[i]);
    graph->count = 0;
    tb_graph_invalidate(graph);
}

void tb_graph_destroy(tb_graph* graph)
{
    if (!graph->gpu) return;
    tb_graph_clear(graph);
    destroy_queries(graph);
    if (graph->cb) vkFreeCommandBuffers(graph->gpu->device, graph->gpu->command_pool, 1, &graph->cb);
    memset(graph, 0, sizeof *graph);
}

tb_result tb_graph_insert(tb_graph* graph, uint32_t at, const tb_stage* stage)
{
    if (graph->count == TB_MAX_STAGES || at > graph->count) {
        tb_stage dropped = *stage;
        release_stage(&dropped);
        return tb_fail(graph->gpu->diag, TB_ERROR_CAPACITY,
                       "the step graph holds at most %d stages", TB_MAX_STAGES);
    }
    memmove(&graph->stages[at + 1], &graph->stages[at], (graph->count - at) * sizeof(tb_stage));
    graph->stages[at] = *stage;
    graph->count++;
    tb_graph_invalidate(graph);
    return TB_OK;
}

tb_result tb_graph_append_passes(tb_graph* graph, const char* name, tb_pass_list* list)
{
    tb_stage stage = { .name = name, .passes = list->passes, .pass_count = list->count };
    memset(list, 0, sizeof *list);
    return tb_graph_insert(graph, graph->count, &stage);
}

tb_pass tb_pass_with_args(VkPipeline pipeline, tb_dispatch_rule rule, VkBuffer indirect,
                          VkDeviceSize offset, uint32_t x, uint32_t y, uint32_t z)
{
    tb_pass pass = { .pipeline = pipeline, .rule = rule, .groups = { 1, 1, 1 },
                     .indirect = indirect, .indirect_offset = offset,
                     .push_size = sizeof(tb_gpu_push) };
    tb_gpu_push push = { { x, y, z, 0 } };
    memcpy(pass.push, &push, sizeof push);
    return pass;
}

tb_result tb_pass_list_add(tb_pass_list* list, tb_diag* diag, const tb_pass* pass)
{
    /* A stage whose pipeline was never made (pipelines made on first use) would crash the
     * driver when the step runs. */
    if (!pass->pipeline)
        return tb_fail(diag, TB_ERROR_DEVICE, "a pass of the step has no pipeline (a bug in "
                       "Tumble: a stage recorded before its pipeline was made)");
    if (list->count == list->capacity) {
        uint32_t cap = list->capacity ? list->capacity * 2 : 16;
        tb_pass* grown = realloc(list->passes, cap * sizeof *grown);
        if (!grown) return tb_fail(diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        list->passes = grown;
        list->capacity = cap;
    }
    list->passes[list->count++] = *pass;
    return TB_OK;
}

void tb_pass_list_free(tb_pass_list* list)
{
    free(list->passes);
    memset(list, 0, sizeof *list);
}

void tb_graph_invalidate(tb_graph* graph)
{
    graph->needs_record = 1;
}

static tb_result ensure_queries(tb_graph* graph)
{
    destroy_queries(graph);
    if (!graph->gpu->timestamp_valid_bits) return TB_OK;
    VkQueryPoolCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = graph->count + 1,
    };
    return tb_vk_check(graph->gpu->diag,
                       vkCreateQueryPool(graph->gpu->device, &info, NULL, &graph->queries),
                       "vkCreateQueryPool");
}

static void memory_barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkAccessFlags src_access,
                           VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = src_access, .dstAccessMask = dst_access,
    };
    vkCmdPipelineBarrier(cb, src, dst, 0, 1, &barrier, 0, NULL, 0, NULL);
}

/* What a stage may read or write: storage, uniforms, and indirect arguments. */
#define STAGE_READS (VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | \
                     VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT)
#define STAGE_STAGES (VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT)
/* The same without the indirect arguments. */
#define SHADER_READS (VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | \
                      VK_ACCESS_UNIFORM_READ_BIT)

static void record_dispatch(VkCommandBuffer cb, const tb_pass* s, VkBuffer params)
{
    switch (s->rule) {
    case TB_DISPATCH_PER_BODY:
        vkCmdDispatchIndirect(cb, params, TB_PARAMS_BODY_DISPATCH_OFFSET);
        break;
    case TB_DISPATCH_FIXED:
        vkCmdDispatch(cb, s->groups[0], s->groups[1], s->groups[2]);
        break;
    case TB_DISPATCH_INDIRECT:
        vkCmdDispatchIndirect(cb, s->indirect, s->indirect_offset);
        break;
    }
}

static void record_pass(VkCommandBuffer cb, VkPipelineLayout layout, const tb_pass* pass,
                        VkBuffer params)
{
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline);
    if (pass->push_size)
        vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pass->push_size, pass->push);
    record_dispatch(cb, pass, params);
}

void tb_passes_record(VkCommandBuffer cb, VkPipelineLayout layout, const tb_pass* passes,
                      uint32_t count, VkBuffer params)
{
    for (uint32_t i = 0; i < count; i++) {
        if (i && passes[i - 1].writes_no_arguments)
            memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, SHADER_READS);
        else if (i)
            memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           STAGE_STAGES, STAGE_READS);
        record_pass(cb, layout, &passes[i], params);
    }
}

static void record_stage(const tb_graph* graph, VkCommandBuffer cb, uint32_t i, VkBuffer params)
{
    const tb_stage* s = &graph->stages[i];
    int plain = s->pass_count && s->passes[s->pass_count - 1].writes_no_arguments;
    if (graph->gpu->begin_label) {
        VkDebugUtilsLabelEXT label = { .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT,
                                       .pLabelName = s->name };
        graph->gpu->begin_label(cb, &label);
    }
    tb_passes_record(cb, graph->pipelines->layout, s->passes, s->pass_count, params);
    if (graph->gpu->end_label) graph->gpu->end_label(cb);
    if (graph->queries)
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, graph->queries, i + 1);
    if (i + 1 < graph->count)
        memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       plain ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT : STAGE_STAGES,
                       plain ? SHADER_READS : STAGE_READS);
}

/* (a, b) at the offset become (b, a): the scratch takes (a, b, a), then gives back (b, a). The
 * barrier before it held the step's shader reads of the buffer back. */
static void record_swap(VkCommandBuffer cb, const tb_tail_swap* s)
{
    VkBufferCopy out[2] = { { s->offset, 0, 16 }, { s->offset, 16, 8 } };
    vkCmdCopyBuffer(cb, s->buffer, s->scratch, 2, out);
    memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy back = { 8, s->offset, 16 };
    vkCmdCopyBuffer(cb, s->scratch, s->buffer, 1, &back);
}

static tb_result record(tb_graph* graph, VkBuffer params)
{
    VkCommandBuffer cb = graph->cb;
    tb_result r = tb_vk_check(graph->gpu->diag, vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
    if (r) return r;
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_SIMULTANEOUS_USE_BIT,
    };
    vkBeginCommandBuffer(cb, &begin);
    /* Uploads of this submission, and the previous step's writes, come before anything. */
    memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                   STAGE_STAGES, STAGE_READS);
    if (graph->queries) {
        vkCmdResetQueryPool(cb, graph->queries, 0, graph->count + 1);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, graph->queries, 0);
    }
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, graph->pipelines->layout, 0, 1,
                            &graph->pipelines->set, 0, NULL);
    for (uint32_t i = 0; i < graph->count; i++) record_stage(graph, cb, i, params);
    if (graph->tail.src) {
        memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy copy = { 0, 0, graph->tail.size };
        vkCmdCopyBuffer(cb, graph->tail.src, graph->tail.dst, 1, &copy);
        if (graph->swap.buffer) record_swap(cb, &graph->swap);
        memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    }
    /* Results go to transfers (read-back, growth copies) and the host. */
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                   VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                   VK_ACCESS_HOST_READ_BIT);
    return tb_vk_check(graph->gpu->diag, vkEndCommandBuffer(cb), "vkEndCommandBuffer");
}

tb_result tb_graph_prepare(tb_graph* graph, VkBuffer params)
{
    if (!graph->needs_record && params == graph->params) return TB_OK;
    tb_result r = ensure_queries(graph);
    if (!r) r = record(graph, params);
    if (r) return r;
    graph->params = params;
    graph->needs_record = 0;
    graph->records++;
    uint32_t dispatches = 0;
    for (uint32_t i = 0; i < graph->count; i++) dispatches += graph->stages[i].pass_count;
    tb_log(graph->gpu->diag, TB_LOG_DEBUG, "step recorded: %u stages, %u dispatches",
           graph->count, dispatches);
    return TB_OK;
}

void tb_graph_read_times(const tb_graph* graph, double* stage_ms, double* total_ms)
{
    uint64_t ticks[TB_MAX_STAGES + 1] = { 0 };
    *total_ms = 0;
    for (uint32_t i = 0; i < graph->count; i++) stage_ms[i] = 0;
    if (!graph->queries || graph->records == 0) return;
    if (vkGetQueryPoolResults(graph->gpu->device, graph->queries, 0, graph->count + 1,
                              sizeof ticks, ticks, sizeof ticks[0], VK_QUERY_RESULT_64_BIT) != VK_SUCCESS)
        return;
    uint64_t mask = graph->gpu->timestamp_valid_bits >= 64
                        ? ~0ull : ((1ull << graph->gpu->timestamp_valid_bits) - 1);
    double ns_per_tick = graph->gpu->props.limits.timestampPeriod;
    for (uint32_t i = 0; i < graph->count; i++)
        stage_ms[i] = (double)((ticks[i + 1] - ticks[i]) & mask) * ns_per_tick * 1e-6;
    *total_ms = (double)((ticks[graph->count] - ticks[0]) & mask) * ns_per_tick * 1e-6;
}
