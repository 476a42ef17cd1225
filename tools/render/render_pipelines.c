/* The descriptor set that shows the world's body arrays (and its contact manifolds, the
 * mesh shapes' body lists and the joint overlay's lines) to the shaders, the six graphics
 * pipelines: instanced meshes, the same see-through (static bodies), plane quads with grid,
 * AABB lines, contact lines, joint lines; and the compute pipeline that lists the bodies of
 * each mesh shape. Viewport and scissor are dynamic so that a size change keeps the
 * pipelines. */
#include <stddef.h>
#include <string.h>

#include "layout.h"
#include "render_internal.h"
#include "render_shaders.h"

/* The world's arrays the shaders read, at the world's own binding numbers. */
static const uint32_t BODY_BINDINGS[] = {
    TB_BIND_BODY_POS, TB_BIND_BODY_ROT, TB_BIND_BODY_LINVEL, TB_BIND_BODY_INFO,
    TB_BIND_BODY_AABB_MIN, TB_BIND_BODY_AABB_MAX, TB_BIND_SHAPES,
};
#define BODY_BINDING_COUNT (sizeof BODY_BINDINGS / sizeof BODY_BINDINGS[0])
/* Plus the manifolds, written only once contacts are shown: until then no bound pipeline
 * uses the binding, so it may stay unwritten; the mesh lists (render_meshes.c); and the
 * joint lines, likewise written only once there are joints to draw (render_joints.c). */
static const uint32_t OWN_BINDINGS[] = {
    TR_BIND_MANIFOLDS, TR_BIND_MESH_OF_SHAPE, TR_BIND_MESH_COMMANDS, TR_BIND_MESH_INSTANCES,
    TR_BIND_JOINT_LINES,
};
#define BINDING_COUNT (BODY_BINDING_COUNT + sizeof OWN_BINDINGS / sizeof OWN_BINDINGS[0])

/* The vertex shaders read every binding; mesh_lists.comp some body arrays and the lists. */
static VkDescriptorSetLayoutBinding storage(uint32_t binding)
{
    return (VkDescriptorSetLayoutBinding){
        .binding = binding, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
        .descriptorCount = 1,
        .stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT,
    };
}

static tb_result create_layouts(tr_renderer* r)
{
    VkDescriptorSetLayoutBinding bindings[BINDING_COUNT];
    for (uint32_t i = 0; i < BINDING_COUNT; i++)
        bindings[i] = storage(i < BODY_BINDING_COUNT ? BODY_BINDINGS[i]
                                                     : OWN_BINDINGS[i - BODY_BINDING_COUNT]);
    VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = BINDING_COUNT, .pBindings = bindings,
    };
    VkDevice d = r->dev.device;
    tb_result res = tr_vk(r, vkCreateDescriptorSetLayout(d, &set_info, NULL, &r->set_layout),
                          "vkCreateDescriptorSetLayout");
    if (res) return res;
    VkPushConstantRange push = { .stageFlags = TR_PUSH_STAGES, .offset = 0, .size = sizeof(tr_push) };
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1, .pSetLayouts = &r->set_layout,
        .pushConstantRangeCount = 1, .pPushConstantRanges = &push,
    };
    return tr_vk(r, vkCreatePipelineLayout(d, &layout_info, NULL, &r->pipeline_layout),
                 "vkCreatePipelineLayout");
}

static tb_result create_descriptor_set(tr_renderer* r)
{
    VkDescriptorPoolSize size = { VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, BINDING_COUNT };
    VkDescriptorPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1, .poolSizeCount = 1, .pPoolSizes = &size,
    };
    VkDevice d = r->dev.device;
    tb_result res = tr_vk(r, vkCreateDescriptorPool(d, &pool, NULL, &r->descriptor_pool),
                          "vkCreateDescriptorPool");
    if (res) return res;
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = r->descriptor_pool, .descriptorSetCount = 1,
        .pSetLayouts = &r->set_layout,
    };
    return tr_vk(r, vkAllocateDescriptorSets(d, &alloc, &r->set), "vkAllocateDescriptorSets");
}

/* Point the set at the world's current buffers; only when they were replaced (the set is
 * never in use here: every frame waits for its fence). */
tb_result tr_bind_bodies(tr_renderer* r, const tb_vulkan_bodies* b)
{
    if (r->set_written && r->set_generation == b->generation) return TB_OK;
    const VkBuffer buffers[BODY_BINDING_COUNT] = {
        b->position, b->rotation, b->linear_velocity, b->info, b->aabb_min, b->aabb_max,
        b->shapes,
    };
    VkDescriptorBufferInfo infos[BODY_BINDING_COUNT];
    VkWriteDescriptorSet writes[BODY_BINDING_COUNT];
    for (uint32_t i = 0; i < BODY_BINDING_COUNT; i++) {
        if (!buffers[i])
            return tr_fail(r, TB_ERROR_DEVICE, "the world has no GPU buffer for binding %u",
                           BODY_BINDINGS[i]);
        infos[i] = (VkDescriptorBufferInfo){ buffers[i], 0, VK_WHOLE_SIZE };
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->set,
            .dstBinding = BODY_BINDINGS[i], .descriptorCount = 1,
            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &infos[i],
        };
    }
    vkUpdateDescriptorSets(r->dev.device, BODY_BINDING_COUNT, writes, 0, NULL);
    r->set_written = 1;
    r->set_generation = b->generation;
    return TB_OK;
}

/* Point the manifold binding at the world's manifold buffer, whole: the last step's half
 * changes with every step (the shader gets its first manifold in the push constants), so
 * the descriptor changes only when the world replaces the buffer. */
tb_result tr_bind_contacts(tr_renderer* r, const tb_vulkan_contacts* c)
{
    if (r->contacts_written && r->contacts_generation == c->generation &&
        r->contacts_buffer == c->manifolds)
        return TB_OK;
    if (!c->manifolds)
        return tr_fail(r, TB_ERROR_DEVICE, "the world has no GPU buffer for its manifolds");
    VkDeviceSize range = c->size < r->max_storage_range ? c->size : r->max_storage_range;
    VkDescriptorBufferInfo info = { c->manifolds, 0, range - range % c->stride };
    VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->set,
        .dstBinding = TR_BIND_MANIFOLDS, .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &info,
    };
    vkUpdateDescriptorSets(r->dev.device, 1, &write, 0, NULL);
    r->contacts_written = 1;
    r->contacts_generation = c->generation;
    r->contacts_buffer = c->manifolds;
    return TB_OK;
}

static tb_result shader_module(tr_renderer* r, const char* name, VkShaderModule* out)
{
    for (uint32_t i = 0; i < tr_shader_blob_count; i++) {
        if (strcmp(tr_shader_blobs[i].name, name) != 0) continue;
        VkShaderModuleCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
            .codeSize = tr_shader_blobs[i].size, .pCode = tr_shader_blobs[i].code,
        };
        return tr_vk(r, vkCreateShaderModule(r->dev.device, &info, NULL, out),
                     "vkCreateShaderModule");
    }
    return tr_fail(r, TB_ERROR_DEVICE, "render shader %s is not embedded (build problem)", name);
}

typedef struct pipeline_desc {
    const char* vert;
    const char* frag;
    VkPrimitiveTopology topology;
    int mesh_input;     /* tr_vertex attributes from binding 0 */
    int blend;          /* alpha blending over what is there (planes fading, see-through) */
    int no_depth_write; /* depth-tested only (see-through static bodies) */
    int no_depth_test;  /* drawn over everything, depth neither tested nor written */
} pipeline_desc;

static tb_result create_pipeline(tr_renderer* r, const pipeline_desc* p, VkPipeline* out)
{
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    tb_result res = shader_module(r, p->vert, &vert);
    if (!res) res = shader_module(r, p->frag, &frag);
    VkPipelineShaderStageCreateInfo stages[2] = {
        { .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
          .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = vert, .pName = "main" },
        { .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
          .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = frag, .pName = "main" },
    };
    VkVertexInputBindingDescription binding = { 0, sizeof(tr_vertex), VK_VERTEX_INPUT_RATE_VERTEX };
    VkVertexInputAttributeDescription attributes[2] = {
        { 0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(tr_vertex, position) },
        { 1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(tr_vertex, normal) },
    };
    VkPipelineVertexInputStateCreateInfo input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = p->mesh_input ? 1 : 0,
        .pVertexBindingDescriptions = &binding,
        .vertexAttributeDescriptionCount = p->mesh_input ? 2 : 0,
        .pVertexAttributeDescriptions = attributes,
    };
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = p->topology,
    };
    VkPipelineViewportStateCreateInfo viewport = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1, .scissorCount = 1,
    };
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL, .cullMode = VK_CULL_MODE_NONE,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE, .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT,
    };
    VkPipelineDepthStencilStateCreateInfo depth = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = p->no_depth_test ? VK_FALSE : VK_TRUE,
        .depthWriteEnable = p->no_depth_write || p->no_depth_test ? VK_FALSE : VK_TRUE,
        .depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL,
    };
    /* Blending keeps the destination alpha (1 from the clear), so the frame stays opaque. */
    VkPipelineColorBlendAttachmentState blend = {
        .blendEnable = p->blend ? VK_TRUE : VK_FALSE,
        .srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA,
        .dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
        .colorBlendOp = VK_BLEND_OP_ADD,
        .srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO, .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
        .alphaBlendOp = VK_BLEND_OP_ADD,
        .colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                          VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT,
    };
    VkPipelineColorBlendStateCreateInfo blending = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = 1, .pAttachments = &blend,
    };
    const VkDynamicState dynamic_states[2] = { VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR };
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = 2, .pDynamicStates = dynamic_states,
    };
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .stageCount = 2, .pStages = stages,
        .pVertexInputState = &input, .pInputAssemblyState = &assembly,
        .pViewportState = &viewport, .pRasterizationState = &raster,
        .pMultisampleState = &multisample, .pDepthStencilState = &depth,
        .pColorBlendState = &blending, .pDynamicState = &dynamic,
        .layout = r->pipeline_layout, .renderPass = r->render_pass, .subpass = 0,
    };
    if (!res)
        res = tr_vk(r, vkCreateGraphicsPipelines(r->dev.device, VK_NULL_HANDLE, 1, &info, NULL,
                                                 out), "vkCreateGraphicsPipelines");
    if (vert) vkDestroyShaderModule(r->dev.device, vert, NULL);
    if (frag) vkDestroyShaderModule(r->dev.device, frag, NULL);
    return res;
}

static tb_result create_compute(tr_renderer* r, const char* name, VkPipeline* out)
{
    VkShaderModule module = VK_NULL_HANDLE;
    tb_result res = shader_module(r, name, &module);
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = { .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                   .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main" },
        .layout = r->pipeline_layout,
    };
    if (!res)
        res = tr_vk(r, vkCreateComputePipelines(r->dev.device, VK_NULL_HANDLE, 1, &info, NULL,
                                                out), "vkCreateComputePipelines");
    if (module) vkDestroyShaderModule(r->dev.device, module, NULL);
    return res;
}

tb_result tr_pipelines_create(tr_renderer* r)
{
    static const pipeline_desc mesh = { "mesh.vert", "mesh.frag",
                                        VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, 0, 0, 0 };
    static const pipeline_desc plane = { "plane.vert", "plane.frag",
                                         VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 0, 1, 0, 0 };
    static const pipeline_desc line = { "aabb.vert", "line.frag",
                                        VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 0, 0, 0, 0 };
    static const pipeline_desc contact = { "contacts.vert", "line.frag",
                                           VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 0, 0, 0, 0 };
    static const pipeline_desc see_through = { "mesh.vert", "mesh.frag",
                                               VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, 1, 1, 0 };
    static const pipeline_desc joints = { "joints.vert", "line.frag",
                                          VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 0, 0, 0, 1 };
    tb_result res = create_layouts(r);
    if (!res) res = create_descriptor_set(r);
    if (!res) res = create_pipeline(r, &mesh, &r->mesh_pipeline);
    if (!res) res = create_pipeline(r, &plane, &r->plane_pipeline);
    if (!res) res = create_pipeline(r, &line, &r->line_pipeline);
    if (!res) res = create_pipeline(r, &contact, &r->contact_pipeline);
    if (!res) res = create_pipeline(r, &see_through, &r->static_pipeline);
    if (!res) res = create_pipeline(r, &joints, &r->joint_pipeline);
    if (!res) res = create_compute(r, "mesh_lists.comp", &r->mesh_list_pipeline);
    return res;
}

void tr_pipelines_destroy(tr_renderer* r)
{
    VkDevice d = r->dev.device;
    VkPipeline* pipelines[7] = { &r->mesh_pipeline, &r->plane_pipeline, &r->line_pipeline,
                                 &r->contact_pipeline, &r->static_pipeline,
                                 &r->joint_pipeline, &r->mesh_list_pipeline };
    for (int i = 0; i < 7; i++) {
        if (*pipelines[i]) vkDestroyPipeline(d, *pipelines[i], NULL);
        *pipelines[i] = VK_NULL_HANDLE;
    }
    if (r->pipeline_layout) vkDestroyPipelineLayout(d, r->pipeline_layout, NULL);
    if (r->descriptor_pool) vkDestroyDescriptorPool(d, r->descriptor_pool, NULL);
    if (r->set_layout) vkDestroyDescriptorSetLayout(d, r->set_layout, NULL);
    r->pipeline_layout = VK_NULL_HANDLE;
    r->descriptor_pool = VK_NULL_HANDLE;
    r->set_layout = VK_NULL_HANDLE;
    r->set = VK_NULL_HANDLE;
    r->set_written = 0;
    r->contacts_written = 0;
}
