/* Body arrays on the GPU and their host mirror. */
#include "world/body_store.h"

#include <stdlib.h>
#include <string.h>

#define ELEMENT ((VkDeviceSize)sizeof(tb_gpu_vec4))

typedef char binding_order_check[(TB_BIND_BODY_POS + TB_ARRAY_AABB_MAX == TB_BIND_BODY_AABB_MAX &&
                                  TB_BIND_BODY_POS + TB_ARRAY_INFO == TB_BIND_BODY_INFO) ? 1 : -1];

static tb_diag* diag_of(const tb_body_store* s)
{
    return s->memory->gpu->diag;
}

/* Grow every host-side array to `capacity` slots, zeroing the new part. */
static tb_result grow_mirror(tb_body_store* s, uint32_t capacity)
{
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        tb_gpu_vec4* grown = realloc(s->host[a], capacity * sizeof(tb_gpu_vec4));
        if (!grown) return tb_fail(diag_of(s), TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        memset(grown + s->capacity, 0, (capacity - s->capacity) * sizeof(tb_gpu_vec4));
        s->host[a] = grown;
    }
    uint8_t* dirty = realloc(s->dirty, capacity);
    uint32_t* list = realloc(s->dirty_slots, capacity * sizeof *list);
    if (dirty) s->dirty = dirty;
    if (list) s->dirty_slots = list;
    if (!dirty || !list) return tb_fail(diag_of(s), TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    memset(s->dirty + s->capacity, 0, capacity - s->capacity);
    return TB_OK;
}

/* New GPU arrays of `capacity` slots holding the old contents, zero beyond them. */
static tb_result grow_gpu(tb_body_store* s, tb_transfer* t, uint32_t capacity)
{
    tb_buffer fresh[TB_ARRAY_COUNT] = { 0 };
    tb_result r = TB_OK;
    for (int a = 0; a < TB_ARRAY_COUNT && !r; a++)
        r = tb_buffer_create(s->memory, capacity * ELEMENT,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                             VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, &fresh[a]);
    if (!r) r = tb_transfer_begin(t, 0);
    if (r) {
        for (int a = 0; a < TB_ARRAY_COUNT; a++) tb_buffer_destroy(s->memory, &fresh[a]);
        return r;
    }
    VkDeviceSize old_bytes = s->capacity * ELEMENT;
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        vkCmdFillBuffer(t->cb, fresh[a].buffer, old_bytes, VK_WHOLE_SIZE, 0);
        if (old_bytes) {
            VkBufferCopy all = { 0, 0, old_bytes };
            vkCmdCopyBuffer(t->cb, s->gpu[a].buffer, fresh[a].buffer, 1, &all);
        }
    }
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(s->memory->gpu, &t->cb, 1);
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        tb_buffer* keep = r ? &fresh[a] : &s->gpu[a];
        tb_buffer_destroy(s->memory, keep);
        if (!r) {
            s->gpu[a] = fresh[a];
            tb_pipelines_bind(s->pipelines, TB_BIND_BODY_POS + (uint32_t)a, s->gpu[a].buffer);
        }
    }
    return r;
}

static tb_result grow(tb_body_store* s, tb_transfer* t, uint32_t capacity)
{
    VkDeviceSize range = s->memory->gpu->props.limits.maxStorageBufferRange;
    if (capacity * ELEMENT > range)
        return tb_fail(diag_of(s), TB_ERROR_CAPACITY,
                       "%u bodies need %llu-byte arrays, beyond this device's storage buffer "
                       "range of %llu bytes", capacity, (unsigned long long)(capacity * ELEMENT),
                       (unsigned long long)range);
    tb_result r = grow_mirror(s, capacity);
    if (!r) r = grow_gpu(s, t, capacity);
    if (r) return r;
    if (s->capacity) s->growths++;
    s->capacity = capacity;
    return TB_OK;
}

tb_result tb_body_store_init(tb_body_store* s, tb_memory* memory, tb_pipelines* pipelines,
                             tb_transfer* t, uint32_t capacity)
{
    memset(s, 0, sizeof *s);
    s->memory = memory;
    s->pipelines = pipelines;
    s->fresh = ~0u;
    return grow(s, t, capacity ? capacity : 1);
}

void tb_body_store_destroy(tb_body_store* s)
{
    if (!s->memory) return;
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        tb_buffer_destroy(s->memory, &s->gpu[a]);
        free(s->host[a]);
    }
    free(s->dirty);
    free(s->dirty_slots);
    memset(s, 0, sizeof *s);
}

tb_result tb_body_store_reserve(tb_body_store* s, tb_transfer* t, uint32_t slots, int* grew)
{
    *grew = 0;
    if (slots <= s->capacity) return TB_OK;
    uint64_t capacity = s->capacity;
    while (capacity < slots) capacity *= 2;
    VkDeviceSize range = s->memory->gpu->props.limits.maxStorageBufferRange;
    if (capacity * ELEMENT > range && slots * ELEMENT <= range) capacity = range / ELEMENT;
    if (capacity > UINT32_MAX) capacity = UINT32_MAX;
    tb_result r = grow(s, t, (uint32_t)capacity);
    *grew = !r;
    return r;
}

tb_gpu_vec4* tb_body_store_write(tb_body_store* s, tb_body_array array, uint32_t slot)
{
    if (!s->dirty[slot]) s->dirty_slots[s->dirty_count++] = slot;
    s->dirty[slot] |= (uint8_t)TB_ARRAY_BIT(array);
    if (slot >= s->slots) s->slots = slot + 1;
    return &s->host[array][slot];
}

VkDeviceSize tb_body_store_upload_bytes(const tb_body_store* s)
{
    /* Each run is rounded up to 16 bytes of staging: at most one element per slot per array. */
    return (VkDeviceSize)s->dirty_count * TB_ARRAY_COUNT * ELEMENT;
}

static int compare_u32(const void* a, const void* b)
{
    uint32_t x = *(const uint32_t*)a, y = *(const uint32_t*)b;
    return (x > y) - (x < y);
}

/* Upload the runs of consecutive dirty slots of one array. */
static void upload_array(tb_body_store* s, tb_transfer* t, int a)
{
    uint32_t i = 0;
    while (i < s->dirty_count) {
        uint32_t first = s->dirty_slots[i];
        if (!(s->dirty[first] & TB_ARRAY_BIT(a))) { i++; continue; }
        uint32_t n = 1;
        while (i + n < s->dirty_count && s->dirty_slots[i + n] == first + n &&
               (s->dirty[first + n] & TB_ARRAY_BIT(a)))
            n++;
        void* dst = tb_transfer_upload(t, s->gpu[a].buffer, first * ELEMENT, n * ELEMENT);
        if (dst) memcpy(dst, &s->host[a][first], n * ELEMENT);
        i += n;
    }
}

void tb_body_store_record_uploads(tb_body_store* s, tb_transfer* t)
{
    if (!s->dirty_count) return;
    qsort(s->dirty_slots, s->dirty_count, sizeof(uint32_t), compare_u32);
    for (int a = 0; a < TB_ARRAY_COUNT; a++) upload_array(s, t, a);
    for (uint32_t i = 0; i < s->dirty_count; i++) s->dirty[s->dirty_slots[i]] = 0;
    s->dirty_count = 0;
}

VkDeviceSize tb_body_store_download_bytes(const tb_body_store* s, uint32_t mask)
{
    VkDeviceSize bytes = 0;
    for (int a = 0; a < TB_ARRAY_COUNT; a++)
        if ((mask & ~s->fresh) & TB_ARRAY_BIT(a)) bytes += s->slots * ELEMENT + 16;
    return bytes;
}

void tb_body_store_record_downloads(tb_body_store* s, tb_transfer* t, uint32_t mask,
                                    const void* landing[TB_ARRAY_COUNT])
{
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        landing[a] = NULL;
        if (!((mask & ~s->fresh) & TB_ARRAY_BIT(a)) || !s->slots) continue;
        landing[a] = tb_transfer_download(t, s->gpu[a].buffer, 0, s->slots * ELEMENT);
    }
}

void tb_body_store_take_downloads(tb_body_store* s, uint32_t mask,
                                  const void* const landing[TB_ARRAY_COUNT])
{
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        if (landing[a]) memcpy(s->host[a], landing[a], s->slots * ELEMENT);
    }
    s->fresh |= mask;
}

void tb_body_store_stepped(tb_body_store* s)
{
    s->fresh &= ~TB_ARRAYS_STEPPED;
}
