/* Pipelines, the world's descriptor set and the pipeline cache. */
#include "gpu/pipeline.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "gpu/shaders.h"
#include "layout.h"

const tb_shader_blob* tb_shader_find(const char* name)
{
    for (uint32_t i = 0; i < tb_shader_blob_count; i++)
        if (strcmp(tb_shader_blobs[i].name, name) == 0) return &tb_shader_blobs[i];
    return NULL;
}

static VkDescriptorType binding_type(uint32_t binding)
{
    return binding == TB_BIND_PARAMS ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                     : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

static tb_result create_layouts(tb_pipelines* p)
{
    VkDescriptorSetLayoutBinding bindings[TB_BIND_COUNT];
    for (uint32_t b = 0; b < TB_BIND_COUNT; b++) {
        bindings[b] = (VkDescriptorSetLayoutBinding){
            .binding = b, .descriptorType = binding_type(b), .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
        };
    }
    VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = TB_BIND_COUNT, .pBindings = bindings,
    };
    tb_diag* diag = p->gpu->diag;
    tb_result r = tb_vk_check(diag, vkCreateDescriptorSetLayout(p->gpu->device, &set_info, NULL,
                                                               &p->set_layout),
                              "vkCreateDescriptorSetLayout");
    if (r) return r;
    VkPushConstantRange push = { VK_SHADER_STAGE_COMPUTE_BIT, 0, TB_PUSH_CONSTANT_BYTES };
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1, .pSetLayouts = &p->set_layout,
        .pushConstantRangeCount = 1, .pPushConstantRanges = &push,
    };
    return tb_vk_check(diag, vkCreatePipelineLayout(p->gpu->device, &layout_info, NULL, &p->layout),
                       "vkCreatePipelineLayout");
}

static tb_result create_set(tb_pipelines* p)
{
    VkDescriptorPoolSize sizes[] = {
        { VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1 },
        { VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, TB_BIND_COUNT - 1 },
    };
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1, .poolSizeCount = 2, .pPoolSizes = sizes,
    };
    tb_diag* diag = p->gpu->diag;
    tb_result r = tb_vk_check(diag, vkCreateDescriptorPool(p->gpu->device, &pool_info, NULL,
                                                          &p->descriptor_pool),
                              "vkCreateDescriptorPool");
    if (r) return r;
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = p->descriptor_pool, .descriptorSetCount = 1, .pSetLayouts = &p->set_layout,
    };
    return tb_vk_check(diag, vkAllocateDescriptorSets(p->gpu->device, &alloc, &p->set),
                       "vkAllocateDescriptorSets");
}

/* A cache file is only handed to the driver when its header names this very device:
 * drivers are supposed to check, but a foreign blob is not worth the risk. */
static int cache_header_matches(const tb_gpu* gpu, const unsigned char* data, size_t size)
{
    VkPipelineCacheHeaderVersionOne header;
    if (size < sizeof header) return 0;
    memcpy(&header, data, sizeof header);
    return header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           header.vendorID == gpu->props.vendorID && header.deviceID == gpu->props.deviceID &&
           memcmp(header.pipelineCacheUUID, gpu->props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

/* The cache file's bytes when its header matches this device (at most 1 GiB), or NULL. */
static unsigned char* read_cache_file(const tb_gpu* gpu, const char* path, size_t* size)
{
    unsigned char* data = tb_file_read(path, (size_t)1 << 30, size);
    if (data && !cache_header_matches(gpu, data, *size)) {
        free(data);
        data = NULL;
    }
    if (!data) *size = 0;
    return data;
}

static tb_result create_cache(tb_pipelines* p)
{
    size_t size = 0;
    unsigned char* data = read_cache_file(p->gpu, p->cache_path, &size);
    VkPipelineCacheCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
        .initialDataSize = size, .pInitialData = data,
    };
    tb_result r = tb_vk_check(p->gpu->diag, vkCreatePipelineCache(p->gpu->device, &info, NULL, &p->cache),
                              "vkCreatePipelineCache");
    free(data);
    return r;
}

static void save_cache(tb_pipelines* p)
{
    size_t size = 0;
    if (!p->cache_path || vkGetPipelineCacheData(p->gpu->device, p->cache, &size, NULL) != VK_SUCCESS)
        return;
    unsigned char* data = malloc(size ? size : 1);
    FILE* f = NULL;
    if (data && vkGetPipelineCacheData(p->gpu->device, p->cache, &size, data) == VK_SUCCESS)
        f = fopen(p->cache_path, "wb");
    if (f) {
        if (fwrite(data, 1, size, f) != size)
            tb_log(p->gpu->diag, TB_LOG_WARNING, "could not write pipeline cache %s", p->cache_path);
        fclose(f);
    }
    free(data);
}

tb_result tb_pipelines_init(tb_pipelines* p, tb_gpu* gpu, const char* cache_path)
{
    memset(p, 0, sizeof *p);
    p->gpu = gpu;
    p->cache_path = cache_path;
    p->watch.fd = -1;
    tb_result r = create_layouts(p);
    if (!r) r = create_set(p);
    if (!r) r = create_cache(p);
    return r;
}

void tb_pipelines_destroy(tb_pipelines* p)
{
    VkDevice device = p->gpu ? p->gpu->device : VK_NULL_HANDLE;
    if (!device) return;
    if (p->cache) save_cache(p);
    for (uint32_t i = 0; i < p->source_count; i++) tb_pipeline_source_free(&p->sources[i]);
    free(p->sources);
    free(p->shader_dir);
    tb_watch_close(&p->watch);
    vkDestroyPipelineCache(device, p->cache, NULL);
    vkDestroyDescriptorPool(device, p->descriptor_pool, NULL);
    vkDestroyPipelineLayout(device, p->layout, NULL);
    vkDestroyDescriptorSetLayout(device, p->set_layout, NULL);
    memset(p, 0, sizeof *p);
}

/* ---- the sources of pipelines ---------------------------------------------------------- */

static tb_pipeline_source* add_source(tb_pipelines* p, const char* name, const char* glsl_path,
                                      tb_spirv_check* check, uint32_t workgroup_size,
                                      VkPipeline* slot)
{
    if (p->source_count == p->source_capacity) {
        uint32_t capacity = p->source_capacity ? 2 * p->source_capacity : 64;
        tb_pipeline_source* grown = realloc(p->sources, capacity * sizeof *grown);
        if (!grown) return NULL;
        p->sources = grown;
        p->source_capacity = capacity;
    }
    tb_pipeline_source* s = &p->sources[p->source_count];
    *s = (tb_pipeline_source){ .slot = slot, .workgroup_size = workgroup_size, .check = check };
    s->name = strdup(name);
    s->glsl_path = glsl_path ? strdup(glsl_path) : NULL;
    if (!s->name || (glsl_path && !s->glsl_path)) {
        tb_pipeline_source_free(s);
        return NULL;
    }
    p->source_count++;
    return s;
}

static void remove_source(tb_pipelines* p, uint32_t i)
{
    tb_pipeline_source_free(&p->sources[i]);
    p->sources[i] = p->sources[--p->source_count];
}

static tb_result create_with_source(tb_pipelines* p, const char* name, const char* glsl_path,
                                    tb_spirv_check* check, uint32_t workgroup_size,
                                    VkPipeline* out)
{
    *out = VK_NULL_HANDLE;
    tb_pipeline_source* s = add_source(p, name, glsl_path, check, workgroup_size, out);
    if (!s) return tb_fail(p->gpu->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_result r = tb_pipeline_source_build(p, s, out);
    if (r) remove_source(p, (uint32_t)(s - p->sources));
    else s->pipeline = *out;
    return r;
}

tb_result tb_pipeline_create(tb_pipelines* p, const char* shader, uint32_t workgroup_size,
                             VkPipeline* out)
{
    return create_with_source(p, shader, NULL, NULL, workgroup_size, out);
}

tb_result tb_pipeline_create_once(tb_pipelines* p, const char* shader, uint32_t workgroup_size,
                                  VkPipeline* out)
{
    return *out ? TB_OK : tb_pipeline_create(p, shader, workgroup_size, out);
}

tb_result tb_pipeline_create_glsl(tb_pipelines* p, const char* name, const char* path,
                                  tb_spirv_check* check, uint32_t workgroup_size,
                                  VkPipeline* out)
{
    return create_with_source(p, name, path, check, workgroup_size, out);
}

void tb_pipeline_destroy(tb_pipelines* p, VkPipeline pipeline)
{
    if (!pipeline) return;
    for (uint32_t i = 0; i < p->source_count; i++)
        if (p->sources[i].pipeline == pipeline) {
            remove_source(p, i);
            break;
        }
    vkDestroyPipeline(p->gpu->device, pipeline, NULL);
}

static VkPipeline* slot_in(void* owner, const tb_pipeline_slot* slot)
{
    return (VkPipeline*)((char*)owner + slot->field);
}

tb_result tb_pipeline_create_slots(tb_pipelines* p, const tb_pipeline_slot* slots, size_t count,
                                   void* owner)
{
    tb_result r = TB_OK;
    for (size_t k = 0; k < count && !r; k++)
        r = tb_pipeline_create(p, slots[k].shader, slots[k].workgroup, slot_in(owner, &slots[k]));
    if (r) tb_pipeline_destroy_slots(p, slots, count, owner);
    return r;
}

void tb_pipeline_destroy_slots(tb_pipelines* p, const tb_pipeline_slot* slots, size_t count,
                               void* owner)
{
    for (size_t k = 0; k < count; k++) {
        VkPipeline* pipeline = slot_in(owner, &slots[k]);
        tb_pipeline_destroy(p, *pipeline);
        *pipeline = VK_NULL_HANDLE;
    }
}

/* One line per executable of the pipeline: its name and the compiler's statistics. */
static void print_kernel_stats(const tb_gpu* gpu, const char* name, VkPipeline pipeline)
{
    VkPipelineInfoKHR info = { .sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = pipeline };
    VkPipelineExecutablePropertiesKHR props[4];
    uint32_t count = 4;
    for (uint32_t i = 0; i < count; i++)
        props[i] = (VkPipelineExecutablePropertiesKHR){
            .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR };
    if (gpu->executable_properties(gpu->device, &info, &count, props) < 0) return;
    for (uint32_t e = 0; e < count; e++) {
        VkPipelineExecutableInfoKHR exec = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, .pipeline = pipeline,
            .executableIndex = e };
        VkPipelineExecutableStatisticKHR stats[32];
        uint32_t n = 32;
        for (uint32_t i = 0; i < n; i++)
            stats[i] = (VkPipelineExecutableStatisticKHR){
                .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR };
        if (gpu->executable_statistics(gpu->device, &exec, &n, stats) < 0) continue;
        fprintf(stderr, "kernel %s [%s]:", name, props[e].name);
        for (uint32_t i = 0; i < n; i++) {
            const VkPipelineExecutableStatisticKHR* s = &stats[i];
            if (s->format == VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR)
                fprintf(stderr, " %s=%g", s->name, s->value.f64);
            else if (s->format == VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR)
                fprintf(stderr, " %s=%lld", s->name, (long long)s->value.i64);
            else if (s->format == VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR)
                fprintf(stderr, " %s=%llu", s->name, (unsigned long long)s->value.u64);
            else
                fprintf(stderr, " %s=%s", s->name, s->value.b32 ? "yes" : "no");
        }
        fprintf(stderr, "\n");
    }
}

tb_result tb_pipeline_create_from(tb_pipelines* p, const char* name, const uint32_t* code,
                                  size_t size, uint32_t workgroup_size, VkPipeline* out)
{
    tb_diag* diag = p->gpu->diag;
    VkShaderModuleCreateInfo module_info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = size, .pCode = code,
    };
    VkShaderModule module;
    tb_result r = tb_vk_check(diag, vkCreateShaderModule(p->gpu->device, &module_info, NULL, &module),
                              "vkCreateShaderModule");
    if (r) return r;
    uint32_t values[3] = { workgroup_size, p->gpu->subgroup_size, p->gpu->kernels_for_cpu ? 1u : 0u };
    VkSpecializationMapEntry entries[3] = {
        { TB_SPEC_WORKGROUP_SIZE, 0, sizeof(uint32_t) },
        { TB_SPEC_SUBGROUP_SIZE, sizeof(uint32_t), sizeof(uint32_t) },
        { TB_SPEC_CPU_DEVICE, 2 * sizeof(uint32_t), sizeof(uint32_t) },
    };
    VkSpecializationInfo spec = { 3, entries, sizeof values, values };
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main",
            .pSpecializationInfo = &spec,
        },
        .layout = p->layout,
    };
    if (p->gpu->executable_properties)
        info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    r = tb_vk_check(diag, vkCreateComputePipelines(p->gpu->device, p->cache, 1, &info, NULL, out),
                    name);
    vkDestroyShaderModule(p->gpu->device, module, NULL);
    if (!r && p->gpu->executable_properties) print_kernel_stats(p->gpu, name, *out);
    return r;
}

void tb_pipelines_bind(tb_pipelines* p, uint32_t binding, VkBuffer buffer)
{
    tb_pipelines_bind_range(p, binding, buffer, 0, VK_WHOLE_SIZE);
}

void tb_pipelines_bind_range(tb_pipelines* p, uint32_t binding, VkBuffer buffer,
                             VkDeviceSize offset, VkDeviceSize range)
{
    VkDescriptorBufferInfo info = { buffer, offset, range };
    VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = p->set, .dstBinding = binding, .descriptorCount = 1,
        .descriptorType = binding_type(binding), .pBufferInfo = &info,
    };
    vkUpdateDescriptorSets(p->gpu->device, 1, &write, 0, NULL);
}
