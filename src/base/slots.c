/* Slot tables: indices handed out densely, reused last-in first-out after release. */
#include <stdlib.h>

#include "base/slots.h"

tb_result tb_slots_take(tb_slots* slots, uint32_t* out)
{
    if (slots->free_count) {
        *out = slots->free[--slots->free_count];
    } else {
        *out = slots->used++;
    }
    slots->live++;
    return TB_OK;
}

void tb_slots_give(tb_slots* slots, uint32_t slot)
{
    if (slots->free_count == slots->capacity) {
        uint32_t cap = slots->capacity ? slots->capacity * 2 : 64;
        uint32_t* grown = realloc(slots->free, cap * sizeof *grown);
        if (!grown) { slots->live--; return; } /* the slot is not reused: no harm but memory */
        slots->free = grown;
        slots->capacity = cap;
    }
    slots->free[slots->free_count++] = slot;
    slots->live--;
}

void tb_slots_free(tb_slots* slots)
{
    free(slots->free);
    slots->free = NULL;
    slots->free_count = slots->capacity = 0;
}
