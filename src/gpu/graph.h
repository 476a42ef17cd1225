/* The step graph: an ordered list of compute stages recorded into ONE command buffer.
 *
 * Each stage is a pipeline, a dispatch rule and optional push constants. Between stages the
 * recording puts one global memory barrier; around each a timestamp. The command buffer is
 * recorded again only when the structure changes (a stage is inserted, a buffer grew and
 * the descriptor set was rewritten): tb_graph_invalidate() marks that, and the next step
 * records before it submits. A step of n substeps submits the same command buffer n times
 * in one vkQueueSubmit, so it is recorded with SIMULTANEOUS_USE.
 */
#ifndef TB_GRAPH_H
#define TB_GRAPH_H

#include "gpu/pipeline.h"
#include "tumble.h"

typedef enum tb_dispatch_rule {
    TB_DISPATCH_PER_BODY,  ///< one thread per body slot, sized by tb_gpu_params.body_dispatch
    TB_DISPATCH_FIXED,     ///< `groups` workgroups
    TB_DISPATCH_INDIRECT,  ///< VkDispatchIndirectCommand at indirect/indirect_offset
} tb_dispatch_rule;

/// One dispatch: a pipeline, its push constants and how many workgroups.
typedef struct tb_pass {
    VkPipeline pipeline;
    tb_dispatch_rule rule;
    uint32_t groups[3];
    VkBuffer indirect;
    VkDeviceSize indirect_offset;
    uint32_t push_size;
    unsigned char push[TB_PUSH_CONSTANT_BYTES];
    /// The pass writes no dispatch arguments, nor any bound buffer that holds some (the
    /// counters: synchronization validation takes a shader's write to a binding as a write
    /// of all of it), so the barrier after it need not hold back the next dispatch's
    /// indirect read (on an H100 that wait costs about 3 us a barrier).
    int writes_no_arguments;
} tb_pass;

/// A growable list of passes, as the parallel primitives and multi-pass stages build them.
typedef struct tb_pass_list {
    tb_pass* passes;
    uint32_t count, capacity;
} tb_pass_list;

/// A pass of the step's kernels: one workgroup when FIXED, `indirect` at `offset` when
/// INDIRECT, and the push constants tb_gpu_push (x, y, z) of layout.h.
tb_pass tb_pass_with_args(VkPipeline pipeline, tb_dispatch_rule rule, VkBuffer indirect,
                          VkDeviceSize offset, uint32_t x, uint32_t y, uint32_t z);

/// Append a pass (copied). Fails only when host memory runs out.
tb_result tb_pass_list_add(tb_pass_list* list, tb_diag* diag, const tb_pass* pass);
void tb_pass_list_free(tb_pass_list* list);

/// Record passes in order with one global memory barrier between consecutive passes (none
/// before the first or after the last); after a pass that writes no dispatch arguments it
/// covers shader access only. `params` holds the per-body dispatch arguments.
void tb_passes_record(VkCommandBuffer cb, VkPipelineLayout layout, const tb_pass* passes,
                      uint32_t count, VkBuffer params);

/// A stage of the step: a sequence of passes timed as one (the graph owns the array, not
/// the passes' pipelines).
typedef struct tb_stage {
    const char* name;          ///< the stats key, e.g. "broadphase/grid"
    tb_pass* passes;
    uint32_t pass_count;
} tb_stage;

/// A copy recorded after the last stage of every step (counters to a host-visible buffer).
typedef struct tb_tail_copy { VkBuffer src, dst; VkDeviceSize size; } tb_tail_copy;

/// Two adjacent 8-byte values of `buffer` at `offset` swapped after every step, through
/// `scratch` (TB_GRAPH_SWAP_SCRATCH_BYTES): the manifold arrays' addresses in the params,
/// so that the steps of one submission alternate between them.
typedef struct tb_tail_swap { VkBuffer buffer, scratch; VkDeviceSize offset; } tb_tail_swap;
#define TB_GRAPH_SWAP_SCRATCH_BYTES 24

typedef struct tb_graph {
    tb_gpu* gpu;
    tb_pipelines* pipelines;
    VkBuffer params;           ///< holds the per-body dispatch arguments
    tb_stage stages[TB_MAX_STAGES];
    uint32_t count;
    VkCommandBuffer cb;
    VkQueryPool queries;       ///< count + 1 timestamps; VK_NULL_HANDLE without timestamps
    tb_tail_copy tail;         ///< recorded after the last stage when src is set
    tb_tail_swap swap;         ///< recorded after the tail copy when buffer is set
    int needs_record;
    uint64_t records;
} tb_graph;

tb_result tb_graph_init(tb_graph* graph, tb_gpu* gpu, tb_pipelines* pipelines);
void tb_graph_destroy(tb_graph* graph);

/// Insert a stage before position `at` (count appends). The graph takes its pass array.
tb_result tb_graph_insert(tb_graph* graph, uint32_t at, const tb_stage* stage);

/// Append a stage made of a pass list; the graph takes the list's array (list is emptied).
tb_result tb_graph_append_passes(tb_graph* graph, const char* name, tb_pass_list* list);
/// Remove every stage (before the step is built again).
void tb_graph_clear(tb_graph* graph);

/// The structure changed: record again before the next submission.
void tb_graph_invalidate(tb_graph* graph);
/// Record the command buffer if it needs it.
tb_result tb_graph_prepare(tb_graph* graph, VkBuffer params);

/// GPU milliseconds of each stage and of the whole of the last executed step.
void tb_graph_read_times(const tb_graph* graph, double* stage_ms, double* total_ms);

#endif
