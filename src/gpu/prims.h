/* Parallel primitives on the GPU: key-value radix sort, exclusive scan, stream compaction,
 * fill, and counters -> indirect dispatch arguments.
 *
 * Every primitive works on any buffer: its operands are device addresses (tb_gpu_ptr),
 * passed to the shaders as push constants (GL_EXT_buffer_reference). Element counts are
 * read on the GPU from a uint at `count`, so passes recorded once serve any count up to
 * `max_count` without the host knowing it; workgroup counts come from indirect arguments
 * the primitives compute on the GPU into their scratch memory.
 *
 * The record functions append passes to a tb_pass_list; the caller records the list (as a
 * stage of the step graph, or alone in a test) with one barrier between passes. Kernels
 * use the device's subgroup size (specialization constant) and are correct for every count,
 * 0 and 1 included. Counts above max_count are clamped to it; elements at and beyond the
 * count are never written.
 *
 * Operands: 4-byte aligned addresses in device-local buffers (every such buffer has one).
 * Scratch: a device-local buffer with VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT (dispatches are
 * read from its first bytes), offset a multiple of 4, of the size the *_scratch function
 * gives; primitives recorded one after another in a list may share one scratch. Counts:
 * max_count at most 2^31.
 *
 * Passes (the scratch's dispatch command drives those marked indirect):
 *   fill            1: fill (fixed)
 *   indirect_args   1: indirect_args (fixed, 1 group)
 *   scan, compact   4: indirect_args, scan_reduce (indirect), scan_spine (1 group),
 *                      scan_down or compact_scatter (indirect)
 *   sort            1 + 3 per 8 key bits (+ 1 when that is odd): sort_args (1 group), then
 *                      per pass sort_histogram, sort_spine, sort_scatter (all indirect),
 *                      and copy (indirect) when the last pass wrote the temporary arrays
 */
#ifndef TB_PRIMS_H
#define TB_PRIMS_H

#include "gpu/graph.h"
#include "gpu/memory.h"
#include "layout.h"

/// A place in device memory: the buffer and offset (for indirect arguments and copies) and
/// the device address of that same byte (for the shaders).
typedef struct tb_gpu_ptr {
    VkBuffer buffer;
    VkDeviceSize offset;
    VkDeviceAddress address;
} tb_gpu_ptr;

/// The same place `bytes` further on (buffer offset and address alike).
tb_gpu_ptr tb_gpu_ptr_add(tb_gpu_ptr p, VkDeviceSize bytes);

/// Two device addresses as the shaders read them (a uvec4): (low, high) of a, then of b.
tb_gpu_uvec4 tb_gpu_addresses(VkDeviceAddress a, VkDeviceAddress b);

/// The pointer to byte `offset` of a device-local buffer.
tb_gpu_ptr tb_gpu_ptr_of(const tb_buffer* buffer, VkDeviceSize offset);

typedef struct tb_prims {
    tb_pipelines* pipelines;
    tb_diag* diag;
    uint32_t subgroup_size;
    uint32_t group_size;       ///< invocations per workgroup of every kernel but the sort's
    /// Invocations per workgroup of the sort's histogram, scatter and copy: at most 16
    /// subgroups, so the per-subgroup digit counters fit in shared memory at any width.
    uint32_t sort_group_size;
    uint32_t max_groups_x;     ///< maxComputeWorkGroupCount[0]
    /// Most workgroups of a sort pass (TB_PRIMS_SORT_MAX_BLOCKS); larger sorts give each a
    /// block of several tiles. Tests lower it (and max_groups_x) to reach those paths with
    /// small inputs; lowering it after sizing scratch is safe.
    uint32_t sort_max_blocks;
    VkPipeline fill, indirect_args;
    VkPipeline scan_reduce, scan_spine, scan_down;
    VkPipeline sort_args, sort_histogram, sort_spine, sort_scatter, copy;
    VkPipeline compact_scatter;
} tb_prims;

tb_result tb_prims_init(tb_prims* prims, tb_pipelines* pipelines);
void tb_prims_destroy(tb_prims* prims);

/// dst[i] = value for i < count: the uint at `count`, or `fixed_count` when count.address
/// is 0. With a GPU count, a nonzero fixed_count is the most it can be (it clamps the count
/// and sizes the dispatch); 0 means unknown. One pass, fixed dispatch, grid-stride loop.
tb_result tb_prims_fill(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr dst, tb_gpu_ptr count,
                        uint32_t fixed_count, uint32_t value);

/// Write the VkDispatchIndirectCommand that covers `*count` threads with workgroups of
/// `group_size` threads to `args` (x never beyond the device limit; rows in y when needed,
/// so shaders compute their index as y * num_groups.x + x and skip groups past the end:
/// fewer than y of them). A count of 0 gives (0, 1, 1).
tb_result tb_prims_indirect_args(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr count,
                                 uint32_t group_size, tb_gpu_ptr args);

/// Scratch bytes the scan of up to max_count elements needs.
VkDeviceSize tb_prims_scan_scratch(const tb_prims* prims, uint32_t max_count);
/// Exclusive prefix sum of uint: out[i] = in[0] + ... + in[i-1] for i < *count. `out` may
/// equal `in`. When total.address is not 0 the sum of all elements is stored there.
tb_result tb_prims_scan(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr in, tb_gpu_ptr out,
                        tb_gpu_ptr count, uint32_t max_count, tb_gpu_ptr total,
                        tb_gpu_ptr scratch);

/// Scratch bytes the sort of up to max_count pairs needs (temporary keys and values too).
VkDeviceSize tb_prims_sort_scratch(const tb_prims* prims, uint32_t max_count);
/// Stable ascending sort of *count (key, value) uint pairs by the low `key_bits` bits of
/// the key (1..32); keys and values are sorted in place (the keys keep their other bits).
/// LSD radix sort, 8 bits per pass: fewer key bits, fewer passes.
tb_result tb_prims_sort(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr keys, tb_gpu_ptr values,
                        tb_gpu_ptr count, uint32_t max_count, uint32_t key_bits,
                        tb_gpu_ptr scratch);

/// Scratch bytes the compaction of up to max_count elements needs.
VkDeviceSize tb_prims_compact_scratch(const tb_prims* prims, uint32_t max_count);
/// Stream compaction: the indices i < *count with flags[i] != 0, in increasing order, go to
/// out[0..k); k is stored at out_count.
tb_result tb_prims_compact(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr flags, tb_gpu_ptr out,
                           tb_gpu_ptr count, uint32_t max_count, tb_gpu_ptr out_count,
                           tb_gpu_ptr scratch);

#endif
