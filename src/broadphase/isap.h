/* The incremental 3-axis sort and sweep (src/broadphase/isap.c), as tests see its state. */
#ifndef TB_ISAP_H
#define TB_ISAP_H

#include "broadphase/lbvh.h"

/// The buffer holds, in this order: the control (tb_gpu_isap_control), the sort keys and
/// the sorted endpoints (3 axes each), then per half the orders, the places and the boxes.
typedef struct tb_isap_state {
    VkPipeline keys, ranks, measure, decide, pairs;
    tb_lbvh_search* scratch_search; ///< the search from scratch, skipped in incremental steps
    tb_buffer state;           ///< everything the steps keep (see above)
    tb_buffer scratch;         ///< the sorts' scratch
    uint32_t capacity;         ///< body slots the buffers hold
} tb_isap_state;

/// Byte offset of the control in the state buffer (its counts: tb_gpu_isap_control).
#define TB_ISAP_CONTROL_OFFSET 0

#endif
