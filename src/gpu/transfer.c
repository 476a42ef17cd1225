/* Staging-buffer transfers. */
#include "gpu/transfer.h"

#include <string.h>

#define STAGING_ALIGN 16
#define MIN_STAGING ((VkDeviceSize)1 << 20)

tb_result tb_transfer_init(tb_transfer* t, tb_memory* memory)
{
    memset(t, 0, sizeof *t);
    t->memory = memory;
    return tb_gpu_command_buffer(memory->gpu, &t->cb);
}

void tb_transfer_destroy(tb_transfer* t)
{
    if (!t->memory) return;
    tb_buffer_destroy(t->memory, &t->staging);
    if (t->cb) vkFreeCommandBuffers(t->memory->gpu->device, t->memory->gpu->command_pool, 1, &t->cb);
    memset(t, 0, sizeof *t);
}

static tb_result ensure_staging(tb_transfer* t, VkDeviceSize bytes)
{
    if (t->staging.buffer && t->staging.size >= bytes) return TB_OK;
    VkDeviceSize size = t->staging.size ? t->staging.size : MIN_STAGING;
    while (size < bytes) size *= 2;
    tb_buffer_destroy(t->memory, &t->staging);
    t->staging_growths++;
    return tb_buffer_create(t->memory, size,
                            VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            1, &t->staging);
}

tb_result tb_transfer_begin(tb_transfer* t, VkDeviceSize bytes)
{
    tb_diag* diag = t->memory->gpu->diag;
    tb_result r = ensure_staging(t, bytes + STAGING_ALIGN);
    if (r) return r;
    r = tb_vk_check(diag, vkResetCommandBuffer(t->cb, 0), "vkResetCommandBuffer");
    if (r) return r;
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    t->used = 0;
    t->limit = t->staging.size;
    t->pending = VK_NULL_HANDLE;
    t->region_count = 0;
    return tb_vk_check(diag, vkBeginCommandBuffer(t->cb, &begin), "vkBeginCommandBuffer");
}

static void flush_regions(tb_transfer* t)
{
    if (!t->region_count) return;
    if (t->pending_download)
        vkCmdCopyBuffer(t->cb, t->pending, t->staging.buffer, t->region_count, t->regions);
    else
        vkCmdCopyBuffer(t->cb, t->staging.buffer, t->pending, t->region_count, t->regions);
    t->region_count = 0;
    t->pending = VK_NULL_HANDLE;
}

/* Take `size` bytes of staging and add a region between it and the device buffer. */
static VkDeviceSize add_region(tb_transfer* t, VkBuffer buffer, VkDeviceSize offset,
                               VkDeviceSize size, int download)
{
    if (t->pending != buffer || t->pending_download != download ||
        t->region_count == TB_TRANSFER_MAX_REGIONS)
        flush_regions(t);
    VkDeviceSize at = t->used;
    t->used = (t->used + size + STAGING_ALIGN - 1) / STAGING_ALIGN * STAGING_ALIGN;
    t->pending = buffer;
    t->pending_download = download;
    VkBufferCopy* region = &t->regions[t->region_count++];
    region->srcOffset = download ? offset : at;
    region->dstOffset = download ? at : offset;
    region->size = size;
    return at;
}

void* tb_transfer_upload(tb_transfer* t, VkBuffer dst, VkDeviceSize dst_offset, VkDeviceSize size)
{
    if (t->used + size > t->limit) return NULL; /* the caller declared too little: a bug */
    return (char*)t->staging.mapped + add_region(t, dst, dst_offset, size, 0);
}

const void* tb_transfer_download(tb_transfer* t, VkBuffer src, VkDeviceSize src_offset,
                                 VkDeviceSize size)
{
    if (t->used + size > t->limit) return NULL;
    return (const char*)t->staging.mapped + add_region(t, src, src_offset, size, 1);
}

void tb_transfer_barrier(tb_transfer* t)
{
    flush_regions(t);
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
    };
    vkCmdPipelineBarrier(t->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         1, &barrier, 0, NULL, 0, NULL);
}

tb_result tb_transfer_end(tb_transfer* t)
{
    flush_regions(t);
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
    };
    vkCmdPipelineBarrier(t->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &barrier, 0, NULL, 0, NULL);
    return tb_vk_check(t->memory->gpu->diag, vkEndCommandBuffer(t->cb), "vkEndCommandBuffer");
}
