/* Transfers between host and GPU through one persistently mapped staging buffer.
 *
 * A transfer is one command buffer: uploads (staging -> device buffers), then optionally
 * downloads (device buffers -> staging). Its size is declared up front so the staging
 * buffer grows before any pointer into it is handed out. Copies into the same buffer are
 * gathered into one vkCmdCopyBuffer with many regions.
 */
#ifndef TB_TRANSFER_H
#define TB_TRANSFER_H

#include "gpu/memory.h"

#define TB_TRANSFER_MAX_REGIONS 256

typedef struct tb_transfer {
    tb_memory* memory;
    tb_buffer staging;
    VkCommandBuffer cb;
    VkDeviceSize used;              ///< staging bytes handed out in this transfer
    VkDeviceSize limit;             ///< bytes declared at begin
    VkBuffer pending;               ///< device buffer of the gathered regions
    int pending_download;
    VkBufferCopy regions[TB_TRANSFER_MAX_REGIONS];
    uint32_t region_count;
    uint64_t staging_growths;
} tb_transfer;

tb_result tb_transfer_init(tb_transfer* t, tb_memory* memory);
void tb_transfer_destroy(tb_transfer* t);

/// Start recording a transfer that moves at most `bytes` through staging.
tb_result tb_transfer_begin(tb_transfer* t, VkDeviceSize bytes);
/// Staging memory of `size` bytes that will be copied to dst at dst_offset.
void* tb_transfer_upload(tb_transfer* t, VkBuffer dst, VkDeviceSize dst_offset, VkDeviceSize size);
/// Staging memory that, after the submission, holds src[src_offset, +size).
const void* tb_transfer_download(tb_transfer* t, VkBuffer src, VkDeviceSize src_offset,
                                 VkDeviceSize size);
/// Order everything uploaded so far before what follows (uploads before downloads).
void tb_transfer_barrier(tb_transfer* t);
/// Finish recording; the caller submits t->cb (with whatever follows it).
tb_result tb_transfer_end(tb_transfer* t);

#endif
