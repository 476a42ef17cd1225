/* Slot tables: the indices behind ids. An id is (slot + 1, world serial, generation); the
 * slot table hands indices out densely and reuses released ones last-in first-out, and each
 * owner bumps a slot's generation when it reuses it, so a stale id is detected, never
 * dereferenced. */
#ifndef TB_BASE_SLOTS_H
#define TB_BASE_SLOTS_H

#include <stdint.h>

#include "tumble.h"

/// Generic slot table bookkeeping: free slots are reused last-in first-out.
typedef struct tb_slots {
    uint32_t used;          ///< slots handed out at least once (high-water)
    uint32_t live;
    uint32_t* free;
    uint32_t free_count, capacity;
} tb_slots;

tb_result tb_slots_take(tb_slots* slots, uint32_t* out);
void tb_slots_give(tb_slots* slots, uint32_t slot);
void tb_slots_free(tb_slots* slots);

/// The generation a reused slot gets: one more, never 0 (0 marks an id that never lived).
static inline uint16_t tb_next_generation(uint16_t generation)
{
    uint16_t next = (uint16_t)(generation + 1);
    return next ? next : 1;
}

#endif
