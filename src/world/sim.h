/* The GPU-only buffers of the step: counters, per-body scratch of the broadphase and the
 * solver, the grid, and the pair, manifold and constraint arrays.
 *
 * Two capacities size them: the body capacity (equal to the body store's) and the pair
 * capacity. Growth replaces buffers (keeping what the next step needs for warm starting:
 * both halves of the pairs, last step's manifolds and the per-body pair ranges), re-points the
 * descriptor set and makes the step graph record again.
 */
#ifndef TB_WORLD_SIM_H
#define TB_WORLD_SIM_H

#include "gpu/pipeline.h"
#include "gpu/prims.h"
#include "gpu/transfer.h"
#include "layout.h"

typedef enum tb_sim_body_buffer {
    TB_SIM_BODY_PAIRS, TB_SIM_SOLVER_BODIES, TB_SIM_BODY_CLAIM, TB_SIM_BODY_PAIR_COUNT,
    TB_SIM_GRID_KEYS, TB_SIM_GRID_BODIES, TB_SIM_GRID_TABLE, TB_SIM_LARGE_FLAGS,
    TB_SIM_LARGE_LIST, TB_SIM_BODY_SCRATCH, TB_SIM_BLOCK_START, TB_SIM_BLOCK_FILL,
    TB_SIM_BODY_COLOUR, TB_SIM_BLOCK_LIST, TB_SIM_BLOCK_TARGET, TB_SIM_BODY_BUFFER_COUNT
} tb_sim_body_buffer;

typedef enum tb_sim_pair_buffer {
    TB_SIM_PAIRS, TB_SIM_MANIFOLDS_EVEN, TB_SIM_CONSTRAINTS, TB_SIM_COLOUR_LIST, TB_SIM_COLOUR_WORK,
    TB_SIM_MANIFOLDS_ODD, TB_SIM_TAIL_SCRATCH, TB_SIM_EVENT_MARKS, TB_SIM_BLOCK_ENTRIES,
    TB_SIM_SPLIT, TB_SIM_PAIR_BUFFER_COUNT
} tb_sim_pair_buffer;

typedef struct tb_sim {
    tb_memory* memory;
    tb_pipelines* pipelines;
    tb_prims* prims;
    tb_buffer counters;           ///< tb_gpu_counters, device-local
    tb_buffer readback;           ///< host-visible copy of the counters after each step
    tb_buffer body[TB_SIM_BODY_BUFFER_COUNT];
    tb_buffer pair[TB_SIM_PAIR_BUFFER_COUNT];
    uint32_t body_capacity;
    uint32_t table_size;          ///< grid hash table entries, a power of two
    uint32_t table_bits;          ///< log2(table_size)
    uint32_t pair_capacity;       ///< pairs per half
    uint64_t growths;
    int block_lists;              ///< the block solver's contact lists are sized (else empty)
    uint32_t joint_capacity;      ///< joints the block solver's lists have room for
} tb_sim;

/// `block_lists`: the world uses the block solver, which needs TB_SIM_BLOCK_ENTRIES.
tb_result tb_sim_init(tb_sim* sim, tb_memory* memory, tb_pipelines* pipelines, tb_prims* prims,
                      tb_transfer* t, uint32_t body_capacity, uint64_t pair_capacity,
                      int block_lists);
void tb_sim_destroy(tb_sim* sim);

/// Match the body capacity (after the body store grew). Keeps the per-body pair ranges.
tb_result tb_sim_reserve_bodies(tb_sim* sim, tb_transfer* t, uint32_t capacity);
/// Most pairs per half this device can hold: the bound pair array within the storage
/// buffer range, the addressed contact arrays within one allocation, the colouring's index.
uint32_t tb_sim_pair_limit(const tb_sim* sim);
/// Hold at least `pairs` pairs per half (at most tb_sim_pair_limit). Keeps both halves of pairs and manifolds.
tb_result tb_sim_reserve_pairs(tb_sim* sim, tb_transfer* t, uint32_t pairs);

/// Room in the block solver's lists for the entries of `joints` joints (two each).
tb_result tb_sim_reserve_joints(tb_sim* sim, tb_transfer* t, uint32_t joints);

/// The counters as the last executed step left them.
/// Size the block solver's lists (`on`: every buffer is made anew at the present capacities,
/// the pairs fewer when the lists lower the limit) or stop sizing them (the buffers stay as
/// they are until they grow). For a world that has not stepped yet: what the step buffers
/// held is not kept.
tb_result tb_sim_set_block_lists(tb_sim* sim, tb_transfer* t, int on);

const tb_gpu_counters* tb_sim_counters(const tb_sim* sim);

/// Whether pair buffer b is one of the two manifold arrays.
static inline int tb_sim_is_manifolds(tb_sim_pair_buffer b)
{
    return b == TB_SIM_MANIFOLDS_EVEN || b == TB_SIM_MANIFOLDS_ODD;
}

/// The manifold array the step after `steps` completed steps writes (the step's parity, as
/// the GPU's current_half()); the other holds the manifolds of the step before.
static inline const tb_buffer* tb_sim_manifolds_of_step(const tb_sim* sim, uint64_t steps)
{
    return &sim->pair[steps & 1u ? TB_SIM_MANIFOLDS_ODD : TB_SIM_MANIFOLDS_EVEN];
}

#endif
