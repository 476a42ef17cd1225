/* The broadphase: from the bodies' world AABBs to this step's pair list.
 *
 * Every broadphase writes the same output, so the narrowphase, the warm start and the
 * solver do not know which one ran:
 * - each pair whose AABBs overlap (each grown by half the contact margin) and that is not
 *   static-static, exactly once, as pairs[half base + p] = (a, b, TB_NO_COLOUR, 0); a pair
 *   with a mesh or compound body once as TB_PAIR_UNSPLIT, which the midphase split
 *   (pair_split.h) then divides by triangle or by children;
 * - grouped by a "finder" body, which is a or b of each of its pairs: body_pairs[finder]
 *   holds the run's (offset, count) of this half (xy for even steps, zw for odd), for every
 *   body slot (count 0 when it found none), so last step's pair (a, b) is found in the run
 *   of a or of b (glsl/narrowphase/manifold.glsl);
 * - a pair's order (a, b) depends on the two bodies only, never on where they were found,
 *   so a pair keeps its orientation (and its normal's sign) from step to step;
 * - counters.state.z the number of pairs; on overflow the step is abandoned through
 *   broadphase/pair_check (TB_ABORT_PAIRS) and the host grows the pair buffers.
 * The way there is two passes over the same search (glsl/broadphase/pairs.glsl): count
 * each finder's pairs, scan the counts into offsets, check the capacity, write. Pairs are
 * then deterministic: in finder order.
 *
 * Each broadphase is a tb_broadphase_ops: it owns its kernels and buffers (device
 * addresses through push constants, tb_gpu_broadphase_push, so none needs a binding of the
 * world's set), grows them with the body capacity, and records its passes as the stage
 * "broadphase/<name>" (what it builds to search in: sorted keys, a tree, ...); it hands
 * its search's count and write passes to the step, which records the pair output around
 * them as the stage "broadphase/pairs", so the stats tell building from searching.
 *
 * Reads: the bodies' world AABBs (broadphase/world_aabb writes them from poses and shapes)
 * and the step's body slot count. Writes: the pair list, the per-body pair runs, the pair
 * count. A broadphase sees the world only through tb_broadphase_ctx: the GPU plumbing, its
 * own state, and the buffers of tb_broadphase_io.
 */
#ifndef TB_BROADPHASE_H
#define TB_BROADPHASE_H

#include "gpu/gpu.h"
#include "layout.h"
#include "tumble.h"

/// The step's buffers a broadphase reads and writes. They move when they grow, so the
/// world fills this in again before each call.
typedef struct tb_broadphase_io {
    uint32_t body_capacity;        ///< body slots the per-body arrays hold
    uint32_t grid_key_bits;        ///< bits of the grid's sort keys (cell hash and large flag)
    tb_gpu_ptr slots;              ///< uint: this step's body slots (counters.grid.z)
    tb_gpu_ptr large_count;        ///< uint: large bodies the grid lists (counters.grid.y)
    tb_gpu_ptr pair_count;         ///< uint: pairs found (counters.state.z)
    tb_gpu_ptr abandoned;          ///< uint: nonzero once the step is abandoned (counters.state.x)
    tb_gpu_ptr body_pair_counts;   ///< uint per body: each finder's pairs, scanned in place
    tb_gpu_ptr scratch;            ///< sort, scan and compaction scratch for the body capacity
    tb_gpu_ptr grid_keys, grid_bodies, large_flags, large_list;   ///< the grid's arrays
    tb_gpu_ptr aabb_min, aabb_max; ///< the bodies' world boxes, a vec4 per slot
} tb_broadphase_io;

/// What a broadphase sees of the world.
typedef struct tb_broadphase_ctx {
    tb_gpu_kit kit;
    void* state;                   ///< the broadphase's own (kernels, buffers)
    VkPipeline pair_check;         ///< broadphase/pair_check, shared by all
    VkPipeline world_aabb;         ///< broadphase/world_aabb, the boxes every one searches
    tb_broadphase_io io;
} tb_broadphase_ctx;

/// A broadphase's pair search as the pair output runs it: its count and write passes, one
/// of each per search (several when each step runs one of several, as isap does).
#define TB_BROADPHASE_MAX_SEARCHES 2
typedef struct tb_broadphase_search {
    tb_pass counts[TB_BROADPHASE_MAX_SEARCHES];
    tb_pass writes[TB_BROADPHASE_MAX_SEARCHES];
    uint32_t n;
} tb_broadphase_search;

typedef struct tb_broadphase_ops {
    const char* name;                 ///< "grid", "sap", "lbvh" or "isap"
    const char* stage;                ///< its stage's name: "broadphase/<name>"
    /// Create kernels and buffers for the world's current body capacity; may set
    /// bp->state.
    tb_result (*create)(tb_broadphase_ctx* bp);
    /// The body capacity grew to `capacity` (also called at creation after create).
    tb_result (*reserve)(tb_broadphase_ctx* bp, uint32_t capacity);
    /// Append the broadphase's passes (world_aabb has run) and give its search's passes
    /// (the step records the pair output around them).
    tb_result (*record)(tb_broadphase_ctx* bp, tb_pass_list* list, tb_broadphase_search* search);
    void (*destroy)(tb_broadphase_ctx* bp);
    /// Its search starts from last step's pairs (isap): the midphase split keeps a body pair
    /// none of whose parts touch (pair_split.h), so the pair stays in that list.
    int reads_last_pairs;
    /// The bytes of its own it keeps from one step for the next (the world's snapshots
    /// carry them): the start of one of its buffers; NULL for none. sap's are its header;
    /// isap's its whole state, sized by the body capacity: a snapshot restored where the
    /// capacity differs starts isap afresh instead.
    void (*kept)(const tb_broadphase_ctx* bp, VkBuffer* buffer, VkDeviceSize* bytes);
} tb_broadphase_ops;

extern const tb_broadphase_ops tb_broadphase_grid;
extern const tb_broadphase_ops tb_broadphase_sap;
extern const tb_broadphase_ops tb_broadphase_lbvh;
extern const tb_broadphase_ops tb_broadphase_isap;

/// The operations of a broadphase (TB_BROADPHASE_DEFAULT resolved first), or NULL.
const tb_broadphase_ops* tb_broadphase_ops_of(tb_broadphase kind);
/// What TB_BROADPHASE_DEFAULT means now (the environment variable, else the default).
/// Fails with a message when TUMBLE_BROADPHASE names none.
tb_result tb_broadphase_resolve(tb_diag* diag, tb_broadphase asked, tb_broadphase* out);

/// Destroy the pipelines a broadphase made (null ones are skipped).
void tb_broadphase_destroy_pipelines(tb_broadphase_ctx* bp, const VkPipeline* pipelines,
                                     size_t count);

/// Shared kernels: broadphase/world_aabb and the pair output's broadphase/pair_check.
tb_result tb_broadphase_shared_create(tb_broadphase_ctx* bp);
void tb_broadphase_shared_destroy(tb_broadphase_ctx* bp);

/// A pass of a broadphase kernel with the given push constants, dispatched per body slot
/// (TB_DISPATCH_PER_BODY), FIXED (`groups` workgroups) or INDIRECT (the command at
/// `indirect`; unused otherwise).
tb_pass tb_broadphase_pass(VkPipeline pipeline, tb_dispatch_rule rule, uint32_t groups,
                           tb_gpu_ptr indirect, const tb_gpu_broadphase_push* push);
/// Append such a pass to the list.
tb_result tb_broadphase_add(tb_broadphase_ctx* bp, tb_pass_list* list, VkPipeline pipeline,
                            tb_dispatch_rule rule, uint32_t groups, tb_gpu_ptr indirect,
                            const tb_gpu_broadphase_push* push);

/// The pair output of the searches: every count pass, the scan of the counts into offsets,
/// pair_check, then every write pass (each step runs one search; the others skip).
tb_result tb_broadphase_record_pair_output(tb_broadphase_ctx* bp, tb_pass_list* list,
                                           const tb_broadphase_search* search);

/// A device-local buffer for a broadphase's kernels: storage, transfers, indirect arguments
/// (its address goes into tb_gpu_broadphase_push with tb_gpu_addresses).
tb_result tb_broadphase_buffer(tb_broadphase_ctx* bp, VkDeviceSize bytes, tb_buffer* out);
/// The world boxes of the bodies (broadphase/world_aabb), per body slot: `counters` is the
/// buffer bound at TB_BIND_COUNTERS.
tb_result tb_broadphase_record_world_aabb(tb_broadphase_ctx* bp, tb_pass_list* list,
                                          VkBuffer counters);

#endif
