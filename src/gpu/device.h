/* The Vulkan instance, the chosen device and its compute queue. */
#ifndef TB_DEVICE_H
#define TB_DEVICE_H

#include <vulkan/vulkan.h>
#include "base/diag.h"

typedef struct tb_gpu {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;          ///< graphics + compute when the device has one
    VkQueueFlags queue_flags;       ///< what that family can do
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties memory_props;
    char driver[2 * VK_MAX_DRIVER_NAME_SIZE + VK_MAX_DRIVER_INFO_SIZE];
    uint32_t subgroup_size;
    VkDeviceSize max_allocation;     ///< maxMemoryAllocationSize: the largest single buffer
    uint32_t timestamp_valid_bits;  ///< 0: the queue has no timestamps
    int is_cpu;
    /// The kernels' CPU_DEVICE (glsl/common/world.glsl): is_cpu, unless TUMBLE_GPU_LANES=1
    /// runs a CPU device's kernels as a GPU's (the sweeps' lanes a body, the subgroup
    /// sums), so that tests on lavapipe cover them too.
    int kernels_for_cpu;
    VkCommandPool command_pool;     ///< resettable command buffers, compute queue
    VkFence fence;                  ///< one submission in flight at a time
    PFN_vkCmdBeginDebugUtilsLabelEXT begin_label; ///< NULL without debug utils
    PFN_vkCmdEndDebugUtilsLabelEXT end_label;
    /// TUMBLE_KERNEL_STATS set and VK_KHR_pipeline_executable_properties there: each
    /// pipeline's compiler statistics (registers, local memory, ...) go to stderr.
    PFN_vkGetPipelineExecutablePropertiesKHR executable_properties;
    PFN_vkGetPipelineExecutableStatisticsKHR executable_statistics;
    tb_diag* diag;                  ///< where messages go (the world's)
} tb_gpu;

#define TB_MAX_EXTRA_EXTENSIONS 16

typedef struct tb_gpu_options {
    const char* device;   ///< index or name substring; NULL: TUMBLE_DEVICE, then the best
    int validation;       ///< enable the Khronos validation layer + synchronization checks
    /// Extensions an embedder needs besides ours (a renderer's surface and swapchain).
    const char* const* instance_extensions;
    uint32_t instance_extension_count;
    const char* const* device_extensions;
    uint32_t device_extension_count;
} tb_gpu_options;

tb_result tb_gpu_create(tb_gpu* gpu, const tb_gpu_options* options, tb_diag* diag);
void tb_gpu_destroy(tb_gpu* gpu);

/// Check a Vulkan result; on failure record an error naming `what`.
tb_result tb_vk_check(tb_diag* diag, VkResult vr, const char* what);

/// Submit command buffers in one vkQueueSubmit and wait for them.
tb_result tb_gpu_submit_wait(tb_gpu* gpu, const VkCommandBuffer* cbs, uint32_t count);

/// Allocate a primary command buffer from the gpu's pool.
tb_result tb_gpu_command_buffer(tb_gpu* gpu, VkCommandBuffer* out);

#endif
