/* Compute pipelines: one layout for the world's descriptor set, specialization constants
 * for workgroup and subgroup size, and a pipeline cache that can persist in a file.
 * Every pipeline built from a shader (embedded, or a plugin's GLSL) is recorded with the
 * place its owner keeps it, so shader hot-reload can build it again and swap it in there
 * (src/gpu/reload.c); owners give pipelines back with tb_pipeline_destroy. */
#ifndef TB_PIPELINE_H
#define TB_PIPELINE_H

#include "gpu/device.h"
#include "gpu/watch.h"

#define TB_PUSH_CONSTANT_BYTES 128

/// A check of SPIR-V before a pipeline is made of it (`what` names it in the error).
typedef tb_result tb_spirv_check(tb_diag* diag, const char* what, const uint32_t* code,
                                 size_t size);

/// The check every SPIR-V not built with the library gets (spirv_check.c): valid for Vulkan
/// 1.2, a compute entry point "main", its resources in set 0 at the world's bindings.
tb_result tb_spirv_check_module(tb_diag* diag, const char* what, const uint32_t* code,
                                size_t size);

/// A pipeline and where its code comes from.
typedef struct tb_pipeline_source {
    VkPipeline pipeline;          ///< the one in use
    VkPipeline* slot;             ///< where its owner keeps it (rewritten by a swap)
    char* name;                   ///< the embedded shader ("integrate/substep"), or a stage's
    char* glsl_path;              ///< a plugin stage's GLSL file; NULL for an embedded shader
    uint32_t workgroup_size;
    tb_spirv_check* check;        ///< run on a plugin stage's SPIR-V, or NULL (compiled from
                                  ///< a shader directory, tb_spirv_check_module)
    uint64_t code_hash;           ///< of the SPIR-V in use
    char** files;                 ///< the files its GLSL in use was compiled from (canonical)
    uint32_t file_count;
} tb_pipeline_source;

typedef struct tb_pipelines {
    tb_gpu* gpu;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkDescriptorPool descriptor_pool;
    VkDescriptorSet set;           ///< the world's set 0
    VkPipelineCache cache;
    const char* cache_path;        ///< NULL: the cache lives in memory only
    tb_pipeline_source* sources;   ///< every pipeline built from a shader
    uint32_t source_count, source_capacity;
    char* shader_dir;              ///< hot-reload: GLSL compiled from here; NULL: embedded
    tb_watch watch;                ///< the files of the sources, while shader_dir is set
} tb_pipelines;

tb_result tb_pipelines_init(tb_pipelines* p, tb_gpu* gpu, const char* cache_path);
/// Save the cache (if a path was given) and destroy everything.
void tb_pipelines_destroy(tb_pipelines* p);

/// Build the compute pipeline of a shader of glsl/ ("integrate/substep") into *out, where
/// its owner keeps it: embedded SPIR-V, or with a shader directory its GLSL there.
tb_result tb_pipeline_create(tb_pipelines* p, const char* shader, uint32_t workgroup_size,
                             VkPipeline* out);
/// The same for a pipeline made on first use: nothing when *out is already made.
tb_result tb_pipeline_create_once(tb_pipelines* p, const char* shader, uint32_t workgroup_size,
                                  VkPipeline* out);
/// Build a compute pipeline from the GLSL file at `path`, its SPIR-V passed by `check`
/// (may be NULL) first; `name` names it in errors. Hot-reload rebuilds it too.
tb_result tb_pipeline_create_glsl(tb_pipelines* p, const char* name, const char* path,
                                  tb_spirv_check* check, uint32_t workgroup_size,
                                  VkPipeline* out);
/// Build a compute pipeline from SPIR-V (`size` bytes); `name` names it in errors. It has
/// no source to reload.
tb_result tb_pipeline_create_from(tb_pipelines* p, const char* name, const uint32_t* code,
                                  size_t size, uint32_t workgroup_size, VkPipeline* out);
/// Destroy a pipeline made by the functions above (VK_NULL_HANDLE: nothing).
void tb_pipeline_destroy(tb_pipelines* p, VkPipeline pipeline);

/// A stage's kernel as its owner lists them: the shader, its workgroup size, and where in
/// the owner's struct the pipeline goes (offsetof).
typedef struct tb_pipeline_slot {
    const char* shader;
    uint32_t workgroup;
    size_t field;
} tb_pipeline_slot;
/// Build the pipeline of each of `count` slots into `owner`; on failure destroys those built.
tb_result tb_pipeline_create_slots(tb_pipelines* p, const tb_pipeline_slot* slots, size_t count,
                                   void* owner);
/// Destroy the pipelines of each slot in `owner` (VK_NULL_HANDLE ones: nothing).
void tb_pipeline_destroy_slots(tb_pipelines* p, const tb_pipeline_slot* slots, size_t count,
                               void* owner);

/* reload.c: shader hot-reload (DESIGN.md §5) */
/// Compile shaders from GLSL under `dir` from now on (NULL: stop watching; the pipelines in
/// use stay): every pipeline of an embedded shader is built again from it and the files
/// are watched. Sets *swapped to the pipelines replaced (the step must be recorded again).
tb_result tb_pipelines_set_shader_dir(tb_pipelines* p, const char* dir, uint32_t* swapped);
/// Between steps: build again the pipelines whose files changed since the last call; one
/// that fails to compile keeps its pipeline and logs file:line: message. Returns how many
/// pipelines were replaced.
uint32_t tb_pipelines_reload(tb_pipelines* p);
/// Build a source's pipeline (from the shader directory when one is set) into *out.
tb_result tb_pipeline_source_build(tb_pipelines* p, tb_pipeline_source* s, VkPipeline* out);
void tb_pipeline_source_free(tb_pipeline_source* s);

/// Point binding `binding` of the world's set at a whole buffer.
void tb_pipelines_bind(tb_pipelines* p, uint32_t binding, VkBuffer buffer);
/// Point it at `range` bytes from `offset` (a multiple of minStorageBufferOffsetAlignment).
void tb_pipelines_bind_range(tb_pipelines* p, uint32_t binding, VkBuffer buffer,
                             VkDeviceSize offset, VkDeviceSize range);

#endif
