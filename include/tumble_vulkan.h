/* Tumble's Vulkan interop: for embedders that draw or compute on the world's own device
 * (tools/render does). Optional: tumble.h stays free of Vulkan types, and a user who never
 * includes this header never needs the Vulkan headers.
 *
 * Threads and timing: call between steps, from the thread that steps the world. Work the
 * embedder submits to the world's queue runs after every step already returned (steps wait
 * for their fence), but needs a barrier from compute-shader writes to its own first reads.
 */
#ifndef TUMBLE_VULKAN_H
#define TUMBLE_VULKAN_H

#include <vulkan/vulkan.h>
#include "tumble.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Extra extensions a world enables for its embedder (e.g. surface + swapchain).
typedef struct tb_vulkan_extensions {
    const char* const* instance_extensions; ///< at most 16
    uint32_t instance_extension_count;
    const char* const* device_extensions;
    uint32_t device_extension_count;
} tb_vulkan_extensions;

/// tb_world_create with extra Vulkan extensions enabled on the world's instance and device.
TB_API tb_result tb_world_create_vulkan(const tb_world_def* def, const tb_vulkan_extensions* ext,
                                        tb_world** out);

typedef struct tb_vulkan_device {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;              ///< the world's queue; graphics-capable when has_graphics
    uint32_t queue_family;
    int has_graphics;
} tb_vulkan_device;

TB_API tb_result tb_world_vulkan_device(const tb_world* world, tb_vulkan_device* out);

/// The world's GPU body arrays (layouts in glsl/common/layout.h; every element 16 bytes),
/// valid until the next call that adds bodies or shapes (growth replaces buffers: compare
/// `generation` to know). Pending host writes are uploaded first, so the buffers hold what
/// the API says.
typedef struct tb_vulkan_bodies {
    VkBuffer position;          ///< vec4: xyz centre, w inverse mass
    VkBuffer rotation;          ///< vec4 quaternion
    VkBuffer linear_velocity;   ///< vec4: xyz, w damping
    VkBuffer info;              ///< uvec4: x shape index, y TB_BODY_FLAG_*, z the body's
                                ///< rank in the joint graph's colouring, w reserved
    VkBuffer aabb_min, aabb_max;
    VkBuffer shapes;            ///< tb_gpu_shape[shape_slots]
    uint32_t slots;             ///< body slots in use (dead ones included)
    uint32_t shape_slots;
    uint64_t generation;        ///< changes whenever any buffer above is replaced
} tb_vulkan_bodies;

TB_API tb_result tb_world_vulkan_bodies(tb_world* world, tb_vulkan_bodies* out);

/// The contact manifolds of the last step on the GPU (tb_gpu_manifold in
/// glsl/common/layout.h: one per broadphase pair, info.x of them hold points). Valid until
/// the next step.
typedef struct tb_vulkan_contacts {
    VkBuffer manifolds;
    VkDeviceSize offset;        ///< byte offset of the last step's first manifold
    uint32_t count;             ///< manifolds of the last step
    uint32_t stride;            ///< bytes per manifold
    uint64_t generation;        ///< changes whenever the buffer is replaced
    VkDeviceSize size;          ///< bytes of the buffer (it may pass maxStorageBufferRange)
} tb_vulkan_contacts;

TB_API tb_result tb_world_vulkan_contacts(tb_world* world, tb_vulkan_contacts* out);

#ifdef __cplusplus
}
#endif
#endif
