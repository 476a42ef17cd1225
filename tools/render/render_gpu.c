/* The renderer's own Vulkan objects on the world's device: command buffer and fence, the
 * render pass, offscreen colour and depth images with their framebuffer, the host-visible
 * read-back buffer, and the unit meshes. A renderer owns few allocations, so each image and
 * buffer gets its own vkAllocateMemory. */
#include <string.h>

#include "render_internal.h"

#define COLOR_FORMAT VK_FORMAT_R8G8B8A8_UNORM

/* A memory type allowed by `bits` with every `required` flag, preferring `preferred`. */
static int memory_type(const tr_renderer* r, uint32_t bits, VkMemoryPropertyFlags required,
                       VkMemoryPropertyFlags preferred, uint32_t* out)
{
    const VkPhysicalDeviceMemoryProperties* p = &r->memory_properties;
    for (int pass = 0; pass < 2; pass++) {
        VkMemoryPropertyFlags want = pass == 0 ? required | preferred : required;
        for (uint32_t i = 0; i < p->memoryTypeCount; i++) {
            if ((bits & (1u << i)) && (p->memoryTypes[i].propertyFlags & want) == want) {
                *out = i;
                return 1;
            }
        }
    }
    return 0;
}

static tb_result allocate(tr_renderer* r, VkMemoryRequirements req, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred, VkDeviceMemory* out)
{
    uint32_t type;
    if (!memory_type(r, req.memoryTypeBits, required, preferred, &type))
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "the device has no memory type with flags "
                       "0x%x for this resource", (unsigned)required);
    VkMemoryAllocateInfo info = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size, .memoryTypeIndex = type,
    };
    return tr_vk(r, vkAllocateMemory(r->dev.device, &info, NULL, out), "vkAllocateMemory");
}

/* The first depth format the device can render to; D32 first for precision. */
static VkFormat pick_depth_format(VkPhysicalDevice pd)
{
    const VkFormat candidates[] = { VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT,
                                    VK_FORMAT_D16_UNORM };
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(pd, candidates[i], &props);
        if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)
            return candidates[i];
    }
    return VK_FORMAT_UNDEFINED;
}

static VkImageAspectFlags depth_aspects(VkFormat format)
{
    return format == VK_FORMAT_D24_UNORM_S8_UINT
               ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT
               : VK_IMAGE_ASPECT_DEPTH_BIT;
}

/* One subpass: colour cleared and left in TRANSFER_SRC_OPTIMAL for the copy that follows,
 * depth cleared and discarded. The dependencies order this frame's clears after the last
 * frame's copy and depth writes, and the copy after the colour writes. */
static tb_result create_render_pass(tr_renderer* r)
{
    VkAttachmentDescription attachments[2] = {
        { .format = COLOR_FORMAT, .samples = VK_SAMPLE_COUNT_1_BIT,
          .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR, .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
          .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
          .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
          .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
          .finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL },
        { .format = r->depth_format, .samples = VK_SAMPLE_COUNT_1_BIT,
          .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR, .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
          .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
          .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
          .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
          .finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL },
    };
    VkAttachmentReference color_ref = { 0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL };
    VkAttachmentReference depth_ref = { 1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL };
    VkSubpassDescription subpass = {
        .pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
        .colorAttachmentCount = 1, .pColorAttachments = &color_ref,
        .pDepthStencilAttachment = &depth_ref,
    };
    const VkPipelineStageFlags attachment_stages = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubpassDependency dependencies[2] = {
        { .srcSubpass = VK_SUBPASS_EXTERNAL, .dstSubpass = 0,
          .srcStageMask = attachment_stages | VK_PIPELINE_STAGE_TRANSFER_BIT,
          .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
          .dstStageMask = attachment_stages,
          .dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                           VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT },
        { .srcSubpass = 0, .dstSubpass = VK_SUBPASS_EXTERNAL,
          .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
          .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
          .dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
          .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT },
    };
    VkRenderPassCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
        .attachmentCount = 2, .pAttachments = attachments,
        .subpassCount = 1, .pSubpasses = &subpass,
        .dependencyCount = 2, .pDependencies = dependencies,
    };
    return tr_vk(r, vkCreateRenderPass(r->dev.device, &info, NULL, &r->render_pass),
                 "vkCreateRenderPass");
}

static tb_result create_commands(tr_renderer* r)
{
    VkCommandPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = r->dev.queue_family,
    };
    tb_result res = tr_vk(r, vkCreateCommandPool(r->dev.device, &pool, NULL, &r->command_pool),
                          "vkCreateCommandPool");
    if (res) return res;
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = r->command_pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    res = tr_vk(r, vkAllocateCommandBuffers(r->dev.device, &alloc, &r->cb),
                "vkAllocateCommandBuffers");
    if (res) return res;
    VkFenceCreateInfo fence = { .sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO };
    return tr_vk(r, vkCreateFence(r->dev.device, &fence, NULL, &r->fence), "vkCreateFence");
}

tb_result tr_gpu_init(tr_renderer* r)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(r->dev.physical_device, &props);
    vkGetPhysicalDeviceMemoryProperties(r->dev.physical_device, &r->memory_properties);
    r->max_image_size = props.limits.maxImageDimension2D;
    r->max_storage_range = props.limits.maxStorageBufferRange;
    /* The set shows the vertex and compute stages 12 storage buffers (7 body arrays, the
     * manifolds, 3 for the mesh lists, the joint lines); the guaranteed minimum is only 4. */
    if (props.limits.maxPerStageDescriptorStorageBuffers < 12)
        return tr_fail(r, TB_ERROR_DEVICE, "the renderer needs 12 storage buffers per shader "
                       "stage; %s allows %u", props.deviceName,
                       props.limits.maxPerStageDescriptorStorageBuffers);
    r->depth_format = pick_depth_format(r->dev.physical_device);
    if (r->depth_format == VK_FORMAT_UNDEFINED)
        return tr_fail(r, TB_ERROR_DEVICE, "%s renders to none of the depth formats D32, "
                       "D24S8, D16", props.deviceName);
    tb_result res = create_commands(r);
    return res ? res : create_render_pass(r);
}

static tb_result create_image(tr_renderer* r, VkFormat format, VkImageUsageFlags usage,
                              VkImageAspectFlags aspects, tr_image* out)
{
    VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D, .format = format,
        .extent = { r->options.width, r->options.height, 1 },
        .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE, .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    VkDevice d = r->dev.device;
    tb_result res = tr_vk(r, vkCreateImage(d, &info, NULL, &out->image), "vkCreateImage");
    if (res) return res;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d, out->image, &req);
    res = allocate(r, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, &out->memory);
    if (!res) res = tr_vk(r, vkBindImageMemory(d, out->image, out->memory, 0), "vkBindImageMemory");
    if (res) return res;
    VkImageViewCreateInfo view = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = out->image, .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
        .subresourceRange = { aspects, 0, 1, 0, 1 },
    };
    return tr_vk(r, vkCreateImageView(d, &view, NULL, &out->view), "vkCreateImageView");
}

static void destroy_image(tr_renderer* r, tr_image* img)
{
    VkDevice d = r->dev.device;
    if (img->view) vkDestroyImageView(d, img->view, NULL);
    if (img->image) vkDestroyImage(d, img->image, NULL);
    if (img->memory) vkFreeMemory(d, img->memory, NULL);
    memset(img, 0, sizeof *img);
}

tb_result tr_host_buffer(tr_renderer* r, VkDeviceSize size, VkBufferUsageFlags usage,
                         tr_buffer* out)
{
    VkDevice d = r->dev.device;
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    tb_result res = tr_vk(r, vkCreateBuffer(d, &info, NULL, &out->buffer), "vkCreateBuffer");
    if (res) return res;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d, out->buffer, &req);
    /* Coherent, so neither flushes nor invalidations are needed; cached reads faster. */
    res = allocate(r, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                   (usage & VK_BUFFER_USAGE_TRANSFER_DST_BIT) ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0,
                   &out->memory);
    if (!res) res = tr_vk(r, vkBindBufferMemory(d, out->buffer, out->memory, 0), "vkBindBufferMemory");
    if (!res) res = tr_vk(r, vkMapMemory(d, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped),
                          "vkMapMemory");
    return res;
}

void tr_buffer_destroy(tr_renderer* r, tr_buffer* b)
{
    VkDevice d = r->dev.device;
    if (b->buffer) vkDestroyBuffer(d, b->buffer, NULL);
    if (b->memory) vkFreeMemory(d, b->memory, NULL);
    memset(b, 0, sizeof *b);
}

tb_result tr_targets_create(tr_renderer* r)
{
    tb_result res = create_image(r, COLOR_FORMAT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                                 &r->color);
    if (!res) res = create_image(r, r->depth_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                 depth_aspects(r->depth_format), &r->depth);
    if (res) return res;
    VkImageView views[2] = { r->color.view, r->depth.view };
    VkFramebufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
        .renderPass = r->render_pass, .attachmentCount = 2, .pAttachments = views,
        .width = r->options.width, .height = r->options.height, .layers = 1,
    };
    res = tr_vk(r, vkCreateFramebuffer(r->dev.device, &info, NULL, &r->framebuffer),
                "vkCreateFramebuffer");
    if (res) return res;
    VkDeviceSize bytes = (VkDeviceSize)r->options.width * r->options.height * 4;
    return tr_host_buffer(r, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &r->readback);
}

void tr_targets_destroy(tr_renderer* r)
{
    if (r->framebuffer) vkDestroyFramebuffer(r->dev.device, r->framebuffer, NULL);
    r->framebuffer = VK_NULL_HANDLE;
    destroy_image(r, &r->color);
    destroy_image(r, &r->depth);
    tr_buffer_destroy(r, &r->readback);
    r->has_frame = 0;
}

/* The unit meshes in one host-visible vertex buffer and one index buffer, written once
 * before any submission reads them (so no barrier is needed). */
tb_result tr_meshes_create(tr_renderer* r)
{
    static const struct { uint32_t type; tr_unit_mesh_fn* build; } units[] = {
        { TB_GPU_SHAPE_SPHERE, tr_sphere_mesh }, { TB_GPU_SHAPE_BOX, tr_cube_mesh },
        { TB_GPU_SHAPE_CAPSULE, tr_capsule_mesh }, { TB_GPU_SHAPE_CYLINDER, tr_cylinder_mesh },
        { TB_GPU_SHAPE_CONE, tr_cone_mesh },
    };
    tb_result res = tr_host_buffer(r, TR_UNIT_VERTICES * sizeof(tr_vertex),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &r->vertices);
    if (!res) res = tr_host_buffer(r, TR_UNIT_INDICES * sizeof(uint32_t),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &r->indices);
    if (res) return res;
    tr_vertex* v = r->vertices.mapped;
    uint32_t* idx = r->indices.mapped;
    uint32_t nv = 0, ni = 0;
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
        uint32_t count;
        uint32_t vertices = units[i].build(v + nv, idx + ni, &count);
        r->units[units[i].type] = (tr_mesh){ ni, count, (int32_t)nv };
        nv += vertices;
        ni += count;
    }
    if (nv != TR_UNIT_VERTICES || ni != TR_UNIT_INDICES)
        return tr_fail(r, TB_ERROR_DEVICE, "the unit meshes have %u vertices and %u indices, "
                       "not %u and %u", nv, ni, TR_UNIT_VERTICES, TR_UNIT_INDICES);
    return TB_OK;
}

void tr_gpu_destroy(tr_renderer* r)
{
    VkDevice d = r->dev.device;
    tr_targets_destroy(r);
    tr_buffer_destroy(r, &r->vertices);
    tr_buffer_destroy(r, &r->indices);
    if (r->render_pass) vkDestroyRenderPass(d, r->render_pass, NULL);
    if (r->fence) vkDestroyFence(d, r->fence, NULL);
    if (r->command_pool) vkDestroyCommandPool(d, r->command_pool, NULL);
    r->render_pass = VK_NULL_HANDLE;
    r->fence = VK_NULL_HANDLE;
    r->command_pool = VK_NULL_HANDLE;
}
