/* A window for the renderer (GLFW). Frames are rendered offscreen as always, then copied
 * into the swapchain image: the window adds presentation, not a second way to draw.
 * Without GLFW at build time, or without a display, the calls fail with a sentence. */
#include "render.h"

#include <stdlib.h>
#include <string.h>

#ifndef TR_HAVE_GLFW

tb_result tr_window_prepare(tr_window_extensions* out, const char** why)
{
    memset(out, 0, sizeof *out);
    *why = "this build has no window support (install libglfw3-dev and rebuild)";
    return TB_ERROR_NO_DEVICE;
}

tb_result tr_window_run(tr_renderer* r, tb_world* world, uint32_t width, uint32_t height,
                        const char* title, tr_frame_fn* frame, void* user, const char** why)
{
    (void)r; (void)world; (void)width; (void)height; (void)title; (void)frame; (void)user;
    *why = "this build has no window support (install libglfw3-dev and rebuild)";
    return TB_ERROR_NO_DEVICE;
}

#else

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "tumble_vulkan.h"

#define MAX_IMAGES 8

typedef struct window {
    tb_vulkan_device dev;
    GLFWwindow* glfw;
    VkSurfaceKHR surface;
    VkSwapchainKHR swapchain;
    VkFormat format;
    VkExtent2D extent;
    VkImage images[MAX_IMAGES];
    VkSemaphore presentable[MAX_IMAGES]; ///< per image: present waits on it
    uint32_t image_count;
    VkSemaphore acquired;
    VkFence fence;
    VkCommandPool pool;
    VkCommandBuffer cb;
    VkBuffer staging;
    VkDeviceMemory staging_memory;
    uint8_t* pixels;
    uint32_t width, height;
} window;

tb_result tr_window_prepare(tr_window_extensions* out, const char** why)
{
    memset(out, 0, sizeof *out);
    if (!glfwInit()) { *why = "no display: GLFW could not start"; return TB_ERROR_NO_DEVICE; }
    if (!glfwVulkanSupported()) { *why = "GLFW finds no Vulkan loader"; return TB_ERROR_NO_DEVICE; }
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    if (!names || n > 16) { *why = "GLFW cannot present with Vulkan here"; return TB_ERROR_NO_DEVICE; }
    for (uint32_t i = 0; i < n; i++) out->instance[i] = names[i];
    out->instance_count = n;
    out->device[0] = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    out->device_count = 1;
    return TB_OK;
}

static int memory_type(VkPhysicalDevice pd, uint32_t allowed, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(pd, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; i++)
        if ((allowed & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return (int)i;
    return -1;
}

static VkSurfaceFormatKHR pick_format(window* w)
{
    VkSurfaceFormatKHR formats[32];
    uint32_t n = 32;
    vkGetPhysicalDeviceSurfaceFormatsKHR(w->dev.physical_device, w->surface, &n, formats);
    for (uint32_t i = 0; i < n; i++)
        if (formats[i].format == VK_FORMAT_B8G8R8A8_UNORM || formats[i].format == VK_FORMAT_R8G8B8A8_UNORM)
            return formats[i];
    return formats[0];
}

static int create_swapchain(window* w, const char** why)
{
    VkSurfaceCapabilitiesKHR caps;
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(w->dev.physical_device, w->surface, &caps);
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
        *why = "the window's images cannot be copied into";
        return 0;
    }
    VkSurfaceFormatKHR format = pick_format(w);
    w->format = format.format;
    w->extent = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent
                                                       : (VkExtent2D){ w->width, w->height };
    uint32_t count = caps.minImageCount + 1;
    if (caps.maxImageCount && count > caps.maxImageCount) count = caps.maxImageCount;
    VkSwapchainCreateInfoKHR info = {
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR, .surface = w->surface,
        .minImageCount = count, .imageFormat = format.format, .imageColorSpace = format.colorSpace,
        .imageExtent = w->extent, .imageArrayLayers = 1,
        .imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
        .presentMode = VK_PRESENT_MODE_FIFO_KHR, .clipped = VK_TRUE,
    };
    if (vkCreateSwapchainKHR(w->dev.device, &info, NULL, &w->swapchain) != VK_SUCCESS) {
        *why = "vkCreateSwapchainKHR failed";
        return 0;
    }
    w->image_count = MAX_IMAGES;
    vkGetSwapchainImagesKHR(w->dev.device, w->swapchain, &w->image_count, w->images);
    VkSemaphoreCreateInfo sem = { .sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO };
    for (uint32_t i = 0; i < w->image_count; i++)
        vkCreateSemaphore(w->dev.device, &sem, NULL, &w->presentable[i]);
    return 1;
}

static int create_staging(window* w, const char** why)
{
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = (VkDeviceSize)w->width * w->height * 4,
        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
    };
    vkCreateBuffer(w->dev.device, &info, NULL, &w->staging);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(w->dev.device, w->staging, &req);
    int type = memory_type(w->dev.physical_device, req.memoryTypeBits,
                           VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkMemoryAllocateInfo alloc = { .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                   .allocationSize = req.size, .memoryTypeIndex = (uint32_t)type };
    if (type < 0 || vkAllocateMemory(w->dev.device, &alloc, NULL, &w->staging_memory) != VK_SUCCESS) {
        *why = "no host-visible memory for the window's staging buffer";
        return 0;
    }
    vkBindBufferMemory(w->dev.device, w->staging, w->staging_memory, 0);
    vkMapMemory(w->dev.device, w->staging_memory, 0, VK_WHOLE_SIZE, 0, (void**)&w->pixels);
    return 1;
}

static int open_window(window* w, tb_world* world, const char* title, const char** why)
{
    tb_world_vulkan_device(world, &w->dev);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    w->glfw = glfwCreateWindow((int)w->width, (int)w->height, title, NULL, NULL);
    if (!w->glfw) { *why = "GLFW could not open a window"; return 0; }
    if (glfwCreateWindowSurface(w->dev.instance, w->glfw, NULL, &w->surface) != VK_SUCCESS) {
        *why = "no Vulkan surface for the window (was the world made with tr_window_prepare's "
               "extensions?)";
        return 0;
    }
    VkBool32 can_present = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(w->dev.physical_device, w->dev.queue_family, w->surface,
                                         &can_present);
    if (!can_present) { *why = "the world's queue cannot present to this window"; return 0; }
    VkCommandPoolCreateInfo pool = { .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                     .queueFamilyIndex = w->dev.queue_family };
    vkCreateCommandPool(w->dev.device, &pool, NULL, &w->pool);
    VkCommandBufferAllocateInfo cb = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                       .commandPool = w->pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                       .commandBufferCount = 1 };
    vkAllocateCommandBuffers(w->dev.device, &cb, &w->cb);
    VkSemaphoreCreateInfo sem = { .sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO };
    vkCreateSemaphore(w->dev.device, &sem, NULL, &w->acquired);
    VkFenceCreateInfo fence = { .sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO };
    vkCreateFence(w->dev.device, &fence, NULL, &w->fence);
    return create_swapchain(w, why) && create_staging(w, why);
}

static void close_window(window* w)
{
    VkDevice d = w->dev.device;
    if (d) vkDeviceWaitIdle(d);
    for (uint32_t i = 0; i < w->image_count; i++) vkDestroySemaphore(d, w->presentable[i], NULL);
    if (w->swapchain) vkDestroySwapchainKHR(d, w->swapchain, NULL);
    if (w->staging) vkDestroyBuffer(d, w->staging, NULL);
    if (w->staging_memory) vkFreeMemory(d, w->staging_memory, NULL);
    if (w->acquired) vkDestroySemaphore(d, w->acquired, NULL);
    if (w->fence) vkDestroyFence(d, w->fence, NULL);
    if (w->pool) vkDestroyCommandPool(d, w->pool, NULL);
    if (w->surface) vkDestroySurfaceKHR(w->dev.instance, w->surface, NULL);
    if (w->glfw) glfwDestroyWindow(w->glfw);
    glfwTerminate();
}

static void image_barrier(VkCommandBuffer cb, VkImage image, VkImageLayout from, VkImageLayout to,
                          VkPipelineStageFlags src, VkAccessFlags src_access,
                          VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkImageMemoryBarrier b = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src_access,
        .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image, .subresourceRange = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1 },
    };
    vkCmdPipelineBarrier(cb, src, dst, 0, 0, NULL, 0, NULL, 1, &b);
}

/* Copy the staged frame (RGBA rows) into swapchain image i. */
static void record_copy(window* w, uint32_t i)
{
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT };
    vkResetCommandBuffer(w->cb, 0);
    vkBeginCommandBuffer(w->cb, &begin);
    image_barrier(w->cb, w->images[i], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region = {
        .bufferRowLength = w->width,
        .imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 },
        .imageExtent = { w->extent.width < w->width ? w->extent.width : w->width,
                         w->extent.height < w->height ? w->extent.height : w->height, 1 },
    };
    vkCmdCopyBufferToImage(w->cb, w->staging, w->images[i], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    image_barrier(w->cb, w->images[i], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
    vkEndCommandBuffer(w->cb);
}

/* RGBA -> the swapchain's byte order. */
static void swizzle_for(window* w)
{
    if (w->format != VK_FORMAT_B8G8R8A8_UNORM && w->format != VK_FORMAT_B8G8R8A8_SRGB) return;
    size_t n = (size_t)w->width * w->height;
    for (size_t i = 0; i < n; i++) {
        uint8_t r = w->pixels[4 * i];
        w->pixels[4 * i] = w->pixels[4 * i + 2];
        w->pixels[4 * i + 2] = r;
    }
}

static tb_result show_frame(window* w, tr_renderer* r, const char** why)
{
    tb_result res = tr_render(r);
    if (!res) res = tr_read_pixels(r, w->pixels);
    if (res) { *why = tr_last_error(r); return res; }
    swizzle_for(w);
    uint32_t i;
    VkResult vr = vkAcquireNextImageKHR(w->dev.device, w->swapchain, UINT64_MAX, w->acquired,
                                        VK_NULL_HANDLE, &i);
    if (vr != VK_SUCCESS && vr != VK_SUBOPTIMAL_KHR) { *why = "the window's image was lost"; return TB_ERROR_DEVICE; }
    record_copy(w, i);
    VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .waitSemaphoreCount = 1,
        .pWaitSemaphores = &w->acquired, .pWaitDstStageMask = &wait_stage,
        .commandBufferCount = 1, .pCommandBuffers = &w->cb,
        .signalSemaphoreCount = 1, .pSignalSemaphores = &w->presentable[i],
    };
    vkQueueSubmit(w->dev.queue, 1, &submit, w->fence);
    vkWaitForFences(w->dev.device, 1, &w->fence, VK_TRUE, UINT64_MAX);
    vkResetFences(w->dev.device, 1, &w->fence);
    VkPresentInfoKHR present = {
        .sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .waitSemaphoreCount = 1,
        .pWaitSemaphores = &w->presentable[i], .swapchainCount = 1, .pSwapchains = &w->swapchain,
        .pImageIndices = &i,
    };
    vkQueuePresentKHR(w->dev.queue, &present);
    return TB_OK;
}

tb_result tr_window_run(tr_renderer* r, tb_world* world, uint32_t width, uint32_t height,
                        const char* title, tr_frame_fn* frame, void* user, const char** why)
{
    window w;
    memset(&w, 0, sizeof w);
    w.width = width;
    w.height = height;
    tb_result res = open_window(&w, world, title, why) ? TB_OK : TB_ERROR_DEVICE;
    while (!res && !glfwWindowShouldClose(w.glfw) && frame(user)) {
        glfwPollEvents();
        res = show_frame(&w, r, why);
    }
    close_window(&w);
    return res;
}

#endif
