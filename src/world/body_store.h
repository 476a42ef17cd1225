/* Body data on the GPU (structure of arrays, one buffer per array, see layout.h) and its
 * host mirror.
 *
 * The host writes into the mirror and marks (slot, array) dirty; the next submission
 * uploads exactly the dirty runs. The GPU writes poses, velocities and AABBs during a step;
 * after a step those arrays of the mirror are stale until a read brings them back in one
 * download. Growth doubles every array on the GPU (a device-side copy keeps the contents)
 * and re-points the descriptor set, which makes the step graph record again.
 */
#ifndef TB_WORLD_BODY_STORE_H
#define TB_WORLD_BODY_STORE_H

#include "gpu/pipeline.h"
#include "gpu/transfer.h"
#include "layout.h"

typedef enum tb_body_array {
    TB_ARRAY_POS, TB_ARRAY_ROT, TB_ARRAY_LINVEL, TB_ARRAY_ANGVEL, TB_ARRAY_INV_INERTIA,
    TB_ARRAY_INFO, TB_ARRAY_AABB_MIN, TB_ARRAY_AABB_MAX, TB_ARRAY_COUNT
} tb_body_array;

#define TB_ARRAY_BIT(a) (1u << (a))
/// Arrays a step writes on the GPU.
#define TB_ARRAYS_STEPPED (TB_ARRAY_BIT(TB_ARRAY_POS) | TB_ARRAY_BIT(TB_ARRAY_ROT) | \
    TB_ARRAY_BIT(TB_ARRAY_LINVEL) | TB_ARRAY_BIT(TB_ARRAY_ANGVEL) | \
    TB_ARRAY_BIT(TB_ARRAY_AABB_MIN) | TB_ARRAY_BIT(TB_ARRAY_AABB_MAX))

typedef struct tb_body_store {
    tb_memory* memory;
    tb_pipelines* pipelines;
    uint32_t capacity;                    ///< slots the GPU arrays hold
    uint32_t slots;                       ///< slots in use, dead ones included (high-water)
    tb_buffer gpu[TB_ARRAY_COUNT];
    tb_gpu_vec4* host[TB_ARRAY_COUNT];    ///< mirror; TB_ARRAY_INFO holds tb_gpu_uvec4
    uint8_t* dirty;                       ///< per slot: bit a set when array a awaits upload
    uint32_t* dirty_slots;                ///< slots with any dirty bit, each listed once
    uint32_t dirty_count;
    uint32_t fresh;                       ///< bit a: the mirror of array a equals the GPU
    uint64_t growths;
} tb_body_store;

tb_result tb_body_store_init(tb_body_store* s, tb_memory* memory, tb_pipelines* pipelines,
                             tb_transfer* t, uint32_t capacity);
void tb_body_store_destroy(tb_body_store* s);

/// Make room for `slots` slots; grows (and returns 1 in *grew) when needed.
tb_result tb_body_store_reserve(tb_body_store* s, tb_transfer* t, uint32_t slots, int* grew);

/// The mirror element of `slot` in `array`, marked for upload. The caller fills it.
tb_gpu_vec4* tb_body_store_write(tb_body_store* s, tb_body_array array, uint32_t slot);

/// Staging bytes needed to upload what is dirty.
VkDeviceSize tb_body_store_upload_bytes(const tb_body_store* s);
/// Record the uploads of everything dirty into the transfer; clears the dirty marks.
void tb_body_store_record_uploads(tb_body_store* s, tb_transfer* t);

/// Staging bytes needed to download the stale arrays among `mask`.
VkDeviceSize tb_body_store_download_bytes(const tb_body_store* s, uint32_t mask);
/// Record downloads of the stale arrays among `mask`; returns where each will land.
void tb_body_store_record_downloads(tb_body_store* s, tb_transfer* t, uint32_t mask,
                                    const void* landing[TB_ARRAY_COUNT]);
/// After the submission: copy landed arrays into the mirror and mark them fresh.
void tb_body_store_take_downloads(tb_body_store* s, uint32_t mask,
                                  const void* const landing[TB_ARRAY_COUNT]);

/// A step ran: the arrays it writes are stale in the mirror.
void tb_body_store_stepped(tb_body_store* s);

#endif
