/* Device memory: arenas of large VkDeviceMemory blocks, sub-allocated for buffers.
 *
 * Nothing allocates memory per body: body data lives in a few arrays that grow by doubling,
 * and every buffer is a sub-range of a block. Two arenas: device-local memory for what the
 * GPU works on, host-visible coherent memory (persistently mapped) for staging.
 */
#ifndef TB_MEMORY_H
#define TB_MEMORY_H

#include "gpu/device.h"

typedef struct tb_range { VkDeviceSize offset, size; } tb_range;

typedef struct tb_block {
    VkDeviceMemory memory;
    VkDeviceSize size;
    void* mapped;         ///< host address of offset 0, or NULL
    tb_range* free;       ///< free ranges sorted by offset, merged when adjacent
    uint32_t free_count, free_capacity;
} tb_block;

typedef struct tb_arena {
    uint32_t memory_type;
    int host_visible;
    VkDeviceSize block_size;   ///< size of an ordinary block; larger requests get their own
    tb_block* blocks;
    uint32_t block_count;
} tb_arena;

typedef struct tb_memory {
    tb_gpu* gpu;
    tb_arena device_local;
    tb_arena host;             ///< host-visible, coherent; cached when the device offers it
} tb_memory;

typedef struct tb_buffer {
    VkBuffer buffer;
    VkDeviceSize size;
    tb_arena* arena;
    uint32_t block;
    VkDeviceSize offset;       ///< offset of the buffer in its block
    VkDeviceSize reserved;     ///< bytes reserved in the block (size rounded up)
    void* mapped;              ///< host address for host buffers, else NULL
    VkDeviceAddress address;   ///< device address (device-local and host storage buffers), else 0
} tb_buffer;

tb_result tb_memory_init(tb_memory* memory, tb_gpu* gpu);
void tb_memory_destroy(tb_memory* memory);

/// Create a buffer of `size` bytes (> 0) in device-local or host-visible memory.
tb_result tb_buffer_create(tb_memory* memory, VkDeviceSize size, VkBufferUsageFlags usage,
                           int host_visible, tb_buffer* out);
/// Destroy a buffer and return its range to the arena. A zeroed buffer is ignored.
void tb_buffer_destroy(tb_memory* memory, tb_buffer* buffer);

/// Bytes held in device memory blocks, for stats and tests.
VkDeviceSize tb_memory_reserved(const tb_memory* memory);

#endif
