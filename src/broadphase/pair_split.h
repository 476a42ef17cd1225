/* The midphase split: the midphase of mesh and compound bodies, after the broadphase's pair
 * output.
 *
 * The broadphase reports a pair with a mesh or compound body once, as (a, b, TB_NO_COLOUR,
 * TB_PAIR_UNSPLIT). The split replaces each such record by convex pairs, one thread a
 * record (glsl/midphase/split.glsl): against a mesh or heightfield one pair per triangle
 * near the other body (its BVH walked, or its cells found by row and column), and between
 * compounds one pair per pair of parts (children, or the body itself) whose boxes may
 * touch within the step. It keeps the pair output's promises (broadphase.h): each finder's
 * run whole and in order, body_pairs and counters.state.z for the split pairs, and on
 * overflow the step abandoned (TB_ABORT_PAIRS, the pairs needed in counters.state.w) for
 * the host to grow the pair buffers. A body pair without a convex pair near is dropped,
 * unless the broadphase starts from last step's pairs (isap) and it has no mesh body: it
 * keeps its record then (the narrowphase gives it an empty manifold), so the pair stays in
 * the list the next step's search starts from. Its passes, the stage midphase/split,
 * recorded only while the world has mesh or compound shapes:
 *   midphase/split_count   how many pairs each record becomes
 *   scan                   the counts into offsets, their sum into counters.grid.w
 *   midphase/split_check   the capacity; the sum becomes counters.state.z
 *   midphase/split_write   each record's pairs at its offset in the split buffer
 *   midphase/split_runs    each finder's run moved to its pairs' place; pair_dispatch
 *   midphase/split_copy    the split pairs into this step's half of the pair array
 * The split buffer (the step's TB_SIM_SPLIT) holds, for the pair capacity, the split pairs
 * (16 bytes each), the counts (4 bytes each) and the scan's scratch.
 */
#ifndef TB_BROADPHASE_PAIR_SPLIT_H
#define TB_BROADPHASE_PAIR_SPLIT_H

#include "gpu/gpu.h"
#include "gpu/prims.h"

typedef struct tb_pair_split {
    tb_gpu_kit kit;
    VkPipeline count, check, write, runs, copy;   ///< made when first recorded
} tb_pair_split;

/// Bytes of the split buffer for `pair_capacity` pairs.
VkDeviceSize tb_pair_split_bytes(const tb_prims* prims, uint32_t pair_capacity);

/// What the split reads and writes.
typedef struct tb_pair_split_io {
    const tb_buffer* counters;   ///< the buffer bound at TB_BIND_COUNTERS
    const tb_buffer* split;      ///< the split buffer, sized for pair_capacity
    uint32_t pair_capacity;
    int keep_apart;              ///< keep body pairs none of whose parts touch, unsplit (isap)
} tb_pair_split_io;

/// Append the stage's passes.
tb_result tb_pair_split_record(tb_pair_split* s, tb_pass_list* list, const tb_pair_split_io* io);

void tb_pair_split_destroy(tb_pair_split* s);

#endif
