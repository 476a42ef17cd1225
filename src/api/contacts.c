/* Contacts through the API (the world reads them back: src/world/readback.c). */
#include "world/world.h"

tb_result tb_world_read_contacts(tb_world* w, tb_contact* out, uint32_t capacity, uint32_t* count)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!count || (capacity && !out))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_read_contacts: count is "
                       "NULL, or out is NULL with capacity %u", capacity);
    return tb_world_contacts(w, out, capacity, count);
}
