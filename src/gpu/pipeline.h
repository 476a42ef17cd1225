/* Compute pipelines: one layout for the world's descriptor set, specialization constants
 * for workgroup and subgroup size, and a pipeline cache that can persist in a file. */
#ifndef TB_PIPELINE_H
#define TB_PIPELINE_H

#include "gpu/device.h"

#define TB_PUSH_CONSTANT_BYTES 128

typedef struct tb_pipelines {
    tb_gpu* gpu;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkDescriptorPool descriptor_pool;
    VkDescriptorSet set;           ///< the world's set 0
    VkPipelineCache cache;
    const char* cache_path;        ///< NULL: the cache lives in memory only
} tb_pipelines;

tb_result tb_pipelines_init(tb_pipelines* p, tb_gpu* gpu, const char* cache_path);
/// Save the cache (if a path was given) and destroy everything.
void tb_pipelines_destroy(tb_pipelines* p);

/// Build the compute pipeline of an embedded shader.
tb_result tb_pipeline_create(tb_pipelines* p, const char* shader, uint32_t workgroup_size,
                             VkPipeline* out);
/// Build a compute pipeline from SPIR-V (`size` bytes); `name` names it in errors.
tb_result tb_pipeline_create_from(tb_pipelines* p, const char* name, const uint32_t* code,
                                  size_t size, uint32_t workgroup_size, VkPipeline* out);

/// Point binding `binding` of the world's set at a whole buffer.
void tb_pipelines_bind(tb_pipelines* p, uint32_t binding, VkBuffer buffer);
/// Point it at `range` bytes from `offset` (a multiple of minStorageBufferOffsetAlignment).
void tb_pipelines_bind_range(tb_pipelines* p, uint32_t binding, VkBuffer buffer,
                             VkDeviceSize offset, VkDeviceSize range);

#endif
