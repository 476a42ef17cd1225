/* The linear BVH pair search (src/broadphase/lbvh.c) as a part other broadphases can run:
 * the incremental sort and sweep runs it as its search from scratch, skipped on the GPU in
 * the steps that search incrementally. */
#ifndef TB_BROADPHASE_LBVH_H
#define TB_BROADPHASE_LBVH_H

#include "broadphase/broadphase.h"

typedef struct tb_lbvh_search tb_lbvh_search;

tb_result tb_lbvh_search_create(tb_broadphase_ctx* bp, tb_lbvh_search** out);
/// Arrays for `capacity` body slots (grown, never shrunk).
tb_result tb_lbvh_search_reserve(tb_broadphase_ctx* bp, tb_lbvh_search* s, uint32_t capacity);
void tb_lbvh_search_destroy(tb_broadphase_ctx* bp, tb_lbvh_search* s);

/// Append the build (bounds, keys, sort, hierarchy, refit) and give the pair search's count
/// and write passes for the pair output (tb_broadphase_search). `count`: the uint holding the
/// body slots to sort (0 sorts nothing). `skip` (address 0: never): a uint that, when
/// nonzero, makes every pass do nothing, the count and write passes included, so another
/// search can write the pair output in that step.
tb_result tb_lbvh_search_record(tb_broadphase_ctx* bp, tb_lbvh_search* s, tb_pass_list* list,
                                tb_gpu_ptr count, tb_gpu_ptr skip, tb_pass* count_pass,
                                tb_pass* write_pass);

#endif
