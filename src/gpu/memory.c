/* Arenas: first-fit sub-allocation from a few large VkDeviceMemory blocks. */
#include "gpu/memory.h"

#include <stdlib.h>
#include <string.h>

#define DEFAULT_BLOCK_SIZE ((VkDeviceSize)64 << 20)

static int find_memory_type(const tb_gpu* gpu, uint32_t allowed, VkMemoryPropertyFlags want,
                            uint32_t* out)
{
    const VkPhysicalDeviceMemoryProperties* mp = &gpu->memory_props;
    for (uint32_t i = 0; i < mp->memoryTypeCount; i++) {
        if ((allowed & (1u << i)) && (mp->memoryTypes[i].propertyFlags & want) == want) {
            *out = i;
            return 1;
        }
    }
    return 0;
}

/* Memory types a storage/transfer buffer may use on this device. */
static uint32_t buffer_memory_types(tb_gpu* gpu)
{
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 256,
        .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT,
    };
    VkBuffer probe;
    if (vkCreateBuffer(gpu->device, &info, NULL, &probe) != VK_SUCCESS) return ~0u;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(gpu->device, probe, &req);
    vkDestroyBuffer(gpu->device, probe, NULL);
    return req.memoryTypeBits;
}

tb_result tb_memory_init(tb_memory* memory, tb_gpu* gpu)
{
    memset(memory, 0, sizeof *memory);
    memory->gpu = gpu;
    uint32_t allowed = buffer_memory_types(gpu);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (!find_memory_type(gpu, allowed, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                          &memory->device_local.memory_type) &&
        !find_memory_type(gpu, allowed, 0, &memory->device_local.memory_type))
        return tb_fail(gpu->diag, TB_ERROR_DEVICE, "no memory type for storage buffers");
    if (!find_memory_type(gpu, allowed, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT,
                          &memory->host.memory_type) &&
        !find_memory_type(gpu, allowed, host, &memory->host.memory_type))
        return tb_fail(gpu->diag, TB_ERROR_DEVICE, "no host-visible coherent memory type");
    memory->host.host_visible = 1;
    memory->device_local.block_size = DEFAULT_BLOCK_SIZE;
    memory->host.block_size = DEFAULT_BLOCK_SIZE;
    return TB_OK;
}

static void free_block(tb_gpu* gpu, tb_block* block)
{
    if (block->mapped) vkUnmapMemory(gpu->device, block->memory);
    if (block->memory) vkFreeMemory(gpu->device, block->memory, NULL);
    free(block->free);
    memset(block, 0, sizeof *block);
}

void tb_memory_destroy(tb_memory* memory)
{
    tb_arena* arenas[2] = { &memory->device_local, &memory->host };
    for (int a = 0; a < 2; a++) {
        for (uint32_t i = 0; i < arenas[a]->block_count; i++)
            free_block(memory->gpu, &arenas[a]->blocks[i]);
        free(arenas[a]->blocks);
        arenas[a]->blocks = NULL;
        arenas[a]->block_count = 0;
    }
}

static int free_list_insert(tb_block* block, uint32_t at, tb_range range)
{
    if (block->free_count == block->free_capacity) {
        uint32_t cap = block->free_capacity ? block->free_capacity * 2 : 16;
        tb_range* grown = realloc(block->free, cap * sizeof *grown);
        if (!grown) return 0;
        block->free = grown;
        block->free_capacity = cap;
    }
    memmove(block->free + at + 1, block->free + at, (block->free_count - at) * sizeof(tb_range));
    block->free[at] = range;
    block->free_count++;
    return 1;
}

static void free_list_remove(tb_block* block, uint32_t at)
{
    memmove(block->free + at, block->free + at + 1,
            (block->free_count - at - 1) * sizeof(tb_range));
    block->free_count--;
}

/* First fit: carve [offset, offset + size) out of a free range, keeping the alignment gap. */
static int block_take(tb_block* block, VkDeviceSize size, VkDeviceSize align,
                      VkDeviceSize* out)
{
    for (uint32_t i = 0; i < block->free_count; i++) {
        tb_range r = block->free[i];
        VkDeviceSize start = (r.offset + align - 1) / align * align;
        if (start + size > r.offset + r.size) continue;
        VkDeviceSize end = r.offset + r.size;
        free_list_remove(block, i);
        if (end > start + size && !free_list_insert(block, i, (tb_range){ start + size, end - start - size }))
            return 0;
        if (start > r.offset && !free_list_insert(block, i, (tb_range){ r.offset, start - r.offset }))
            return 0;
        *out = start;
        return 1;
    }
    return 0;
}

static void block_give(tb_block* block, tb_range range)
{
    uint32_t at = 0;
    while (at < block->free_count && block->free[at].offset < range.offset) at++;
    if (!free_list_insert(block, at, range)) return; /* leak the range rather than corrupt */
    if (at + 1 < block->free_count &&
        block->free[at].offset + block->free[at].size == block->free[at + 1].offset) {
        block->free[at].size += block->free[at + 1].size;
        free_list_remove(block, at + 1);
    }
    if (at > 0 && block->free[at - 1].offset + block->free[at - 1].size == block->free[at].offset) {
        block->free[at - 1].size += block->free[at].size;
        free_list_remove(block, at);
    }
}

static tb_result arena_new_block(tb_gpu* gpu, tb_arena* arena, VkDeviceSize size)
{
    tb_block* grown = realloc(arena->blocks, (arena->block_count + 1) * sizeof *grown);
    if (!grown) return tb_fail(gpu->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    arena->blocks = grown;
    tb_block* block = &arena->blocks[arena->block_count];
    memset(block, 0, sizeof *block);
    VkMemoryAllocateFlagsInfo flags = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT,
    };
    VkMemoryAllocateInfo info = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = &flags,
        .allocationSize = size, .memoryTypeIndex = arena->memory_type,
    };
    tb_result r = tb_vk_check(gpu->diag, vkAllocateMemory(gpu->device, &info, NULL, &block->memory),
                              "vkAllocateMemory");
    if (!r && arena->host_visible)
        r = tb_vk_check(gpu->diag, vkMapMemory(gpu->device, block->memory, 0, size, 0,
                                               &block->mapped), "vkMapMemory");
    block->size = size;
    if (!r && !free_list_insert(block, 0, (tb_range){ 0, size }))
        r = tb_fail(gpu->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    if (r) { free_block(gpu, block); return r; }
    arena->block_count++;
    return TB_OK;
}

static tb_result arena_alloc(tb_gpu* gpu, tb_arena* arena, VkMemoryRequirements req,
                             uint32_t* block_index, VkDeviceSize* offset)
{
    if (!(req.memoryTypeBits & (1u << arena->memory_type)))
        return tb_fail(gpu->diag, TB_ERROR_DEVICE, "buffer cannot live in the arena's memory type");
    for (uint32_t i = 0; i < arena->block_count; i++) {
        if (block_take(&arena->blocks[i], req.size, req.alignment, offset)) {
            *block_index = i;
            return TB_OK;
        }
    }
    VkDeviceSize size = req.size > arena->block_size ? req.size : arena->block_size;
    tb_result r = arena_new_block(gpu, arena, size);
    if (r) return r;
    *block_index = arena->block_count - 1;
    if (!block_take(&arena->blocks[*block_index], req.size, req.alignment, offset))
        return tb_fail(gpu->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    return TB_OK;
}

tb_result tb_buffer_create(tb_memory* memory, VkDeviceSize size, VkBufferUsageFlags usage,
                           int host_visible, tb_buffer* out)
{
    tb_gpu* gpu = memory->gpu;
    memset(out, 0, sizeof *out);
    /* Device-local buffers all have an address: the primitives take them as pointers, and
     * the step reaches its largest arrays through addresses (no descriptor range limits
     * them). Host-visible storage buffers (test rigs) get one too. */
    int addressed = !host_visible || (usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (addressed) usage |= VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    tb_result r = tb_vk_check(gpu->diag, vkCreateBuffer(gpu->device, &info, NULL, &out->buffer),
                              "vkCreateBuffer");
    if (r) return r;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(gpu->device, out->buffer, &req);
    out->arena = host_visible ? &memory->host : &memory->device_local;
    r = arena_alloc(gpu, out->arena, req, &out->block, &out->offset);
    if (r) { vkDestroyBuffer(gpu->device, out->buffer, NULL); out->buffer = VK_NULL_HANDLE; return r; }
    tb_block* block = &out->arena->blocks[out->block];
    out->size = size;
    out->reserved = req.size;
    out->mapped = block->mapped ? (char*)block->mapped + out->offset : NULL;
    r = tb_vk_check(gpu->diag, vkBindBufferMemory(gpu->device, out->buffer, block->memory,
                                                 out->offset), "vkBindBufferMemory");
    if (!r && addressed) {
        VkBufferDeviceAddressInfo address = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = out->buffer };
        out->address = vkGetBufferDeviceAddress(gpu->device, &address);
    }
    return r;
}

void tb_buffer_destroy(tb_memory* memory, tb_buffer* buffer)
{
    if (!buffer->buffer) return;
    vkDestroyBuffer(memory->gpu->device, buffer->buffer, NULL);
    block_give(&buffer->arena->blocks[buffer->block], (tb_range){ buffer->offset, buffer->reserved });
    memset(buffer, 0, sizeof *buffer);
}

VkDeviceSize tb_memory_reserved(const tb_memory* memory)
{
    VkDeviceSize total = 0;
    for (uint32_t i = 0; i < memory->device_local.block_count; i++)
        total += memory->device_local.blocks[i].size;
    return total;
}
