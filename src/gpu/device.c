/* Instance and device creation: headless, compute only.
 *
 * Device choice: an explicit choice (world def, else TUMBLE_DEVICE) is an index into the
 * device list or a case-insensitive substring of the name; otherwise the best by type:
 * discrete GPU, integrated GPU, virtual GPU, CPU (lavapipe). Devices below Vulkan 1.2 or
 * without a compute queue are never chosen: our SPIR-V targets Vulkan 1.2.
 */
#include "gpu/device.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"
#define MAX_DEVICES 16

tb_result tb_vk_check(tb_diag* diag, VkResult vr, const char* what)
{
    if (vr == VK_SUCCESS) return TB_OK;
    if (vr == VK_ERROR_OUT_OF_HOST_MEMORY || vr == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        return tb_fail(diag, TB_ERROR_OUT_OF_MEMORY, "%s: out of memory (VkResult %d)", what, vr);
    return tb_fail(diag, TB_ERROR_DEVICE, "%s failed (VkResult %d)", what, vr);
}

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user)
{
    (void)types;
    tb_diag* diag = user;
    int is_error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    diag->validation_messages++;
    tb_log(diag, is_error ? TB_LOG_ERROR : TB_LOG_WARNING, "vulkan validation: %s",
           data->pMessage);
    return VK_FALSE;
}

static int layer_available(const char* name)
{
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, NULL);
    VkLayerProperties* layers = calloc(count ? count : 1, sizeof *layers);
    if (!layers) return 0;
    vkEnumerateInstanceLayerProperties(&count, layers);
    int found = 0;
    for (uint32_t i = 0; i < count && !found; i++) found = strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_info(tb_diag* diag)
{
    VkDebugUtilsMessengerCreateInfoEXT info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation_message,
        .pUserData = diag,
    };
    return info;
}

/* Our extensions (debug utils with validation) followed by the embedder's. */
static uint32_t instance_extensions(const tb_gpu_options* o, const char** out)
{
    uint32_t n = 0;
    if (o->validation) out[n++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    for (uint32_t i = 0; i < o->instance_extension_count && n < TB_MAX_EXTRA_EXTENSIONS + 1; i++)
        out[n++] = o->instance_extensions[i];
    return n;
}

static tb_result create_instance(tb_gpu* gpu, const tb_gpu_options* options)
{
    int validation = options->validation;
    if (validation && !layer_available(VALIDATION_LAYER))
        return tb_fail(gpu->diag, TB_ERROR_NO_DEVICE,
                       "validation was asked for but %s is not installed "
                       "(Debian package vulkan-validationlayers)", VALIDATION_LAYER);
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "tumble", .pEngineName = "tumble",
        .apiVersion = VK_API_VERSION_1_2,
    };
    const char* layers[] = { VALIDATION_LAYER };
    const char* extensions[TB_MAX_EXTRA_EXTENSIONS + 1];
    uint32_t extension_count = instance_extensions(options, extensions);
    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
    };
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(gpu->diag);
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .pNext = &messenger,
        .enabledValidationFeatureCount = 1, .pEnabledValidationFeatures = enables,
    };
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? &features : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1 : 0, .ppEnabledLayerNames = layers,
        .enabledExtensionCount = extension_count, .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateInstance(&info, NULL, &gpu->instance);
    if (vr == VK_ERROR_EXTENSION_NOT_PRESENT)
        return tb_fail(gpu->diag, TB_ERROR_NO_DEVICE, "the Vulkan instance lacks an extension "
                       "asked for");
    if (vr == VK_ERROR_INCOMPATIBLE_DRIVER)
        return tb_fail(gpu->diag, TB_ERROR_NO_DEVICE,
                       "no Vulkan driver found (install mesa-vulkan-drivers for lavapipe)");
    if (vr != VK_SUCCESS) return tb_vk_check(gpu->diag, vr, "vkCreateInstance");
    if (!validation) return TB_OK;
    PFN_vkCreateDebugUtilsMessengerEXT create_messenger = (PFN_vkCreateDebugUtilsMessengerEXT)
        vkGetInstanceProcAddr(gpu->instance, "vkCreateDebugUtilsMessengerEXT");
    gpu->begin_label = (PFN_vkCmdBeginDebugUtilsLabelEXT)
        vkGetInstanceProcAddr(gpu->instance, "vkCmdBeginDebugUtilsLabelEXT");
    gpu->end_label = (PFN_vkCmdEndDebugUtilsLabelEXT)
        vkGetInstanceProcAddr(gpu->instance, "vkCmdEndDebugUtilsLabelEXT");
    if (!create_messenger)
        return tb_fail(gpu->diag, TB_ERROR_DEVICE, "VK_EXT_debug_utils is missing");
    return tb_vk_check(gpu->diag, create_messenger(gpu->instance, &messenger, NULL,
                                                  &gpu->messenger),
                       "vkCreateDebugUtilsMessengerEXT");
}

static int compute_queue_family(VkPhysicalDevice pd, uint32_t* family)
{
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, NULL);
    VkQueueFamilyProperties props[16];
    if (count > 16) count = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, props);
    /* A family that also draws lets a renderer share the world's queue; else compute only. */
    const VkQueueFlags both = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
    for (uint32_t i = 0; i < count; i++) {
        if ((props[i].queueFlags & both) == both) { *family = i; return 1; }
    }
    for (uint32_t i = 0; i < count; i++) {
        if (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) { *family = i; return 1; }
    }
    return 0;
}

static int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

static int usable(VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    uint32_t family;
    VkPhysicalDeviceVulkan12Features f12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES };
    VkPhysicalDeviceFeatures2 f = { .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                    .pNext = &f12 };
    if (p.apiVersion < VK_API_VERSION_1_2) return 0;
    vkGetPhysicalDeviceFeatures2(pd, &f);
    return f12.bufferDeviceAddress && compute_queue_family(pd, &family);
}

static int name_contains(const char* name, const char* want)
{
    size_t n = strlen(name), m = strlen(want);
    for (size_t i = 0; i + m <= n; i++) {
        size_t k = 0;
        while (k < m && tolower((unsigned char)name[i + k]) == tolower((unsigned char)want[k])) k++;
        if (k == m) return 1;
    }
    return 0;
}

static int all_digits(const char* s)
{
    if (!*s) return 0;
    for (; *s; s++) if (!isdigit((unsigned char)*s)) return 0;
    return 1;
}

/* The index of the device `choice` names, or of the best one when choice is NULL; -1 if none. */
static int pick_device(VkPhysicalDevice* devices, uint32_t count, const char* choice)
{
    int best = -1, best_rank = 0;
    for (uint32_t i = 0; i < count; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        if (!usable(devices[i])) continue;
        if (choice && all_digits(choice)) {
            if ((uint32_t)atoi(choice) == i) return (int)i;
        } else if (choice) {
            if (name_contains(p.deviceName, choice)) return (int)i;
        } else if (type_rank(p.deviceType) > best_rank) {
            best = (int)i;
            best_rank = type_rank(p.deviceType);
        }
    }
    return best;
}

static tb_result no_device_error(tb_gpu* gpu, VkPhysicalDevice* devices, uint32_t count,
                                 const char* choice)
{
    char names[TB_MESSAGE_SIZE] = "";
    for (uint32_t i = 0; i < count; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s[%u] %s (Vulkan %u.%u)", i ? ", " : "",
                 i, p.deviceName, VK_API_VERSION_MAJOR(p.apiVersion),
                 VK_API_VERSION_MINOR(p.apiVersion));
    }
    return tb_fail(gpu->diag, TB_ERROR_NO_DEVICE,
                   "no usable Vulkan 1.2 compute device%s%s%s; devices: %s",
                   choice ? " matches \"" : "", choice ? choice : "", choice ? "\"" : "",
                   count ? names : "none (install mesa-vulkan-drivers for lavapipe)");
}

static void read_device_facts(tb_gpu* gpu)
{
    VkPhysicalDeviceMaintenance3Properties maintenance3 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES };
    VkPhysicalDeviceDriverProperties driver = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, .pNext = &maintenance3 };
    VkPhysicalDeviceSubgroupProperties subgroup = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES, .pNext = &driver };
    VkPhysicalDeviceProperties2 props = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &subgroup };
    vkGetPhysicalDeviceProperties2(gpu->physical, &props);
    gpu->props = props.properties;
    gpu->subgroup_size = subgroup.subgroupSize;
    gpu->max_allocation = maintenance3.maxMemoryAllocationSize;
    gpu->is_cpu = gpu->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    const char* gpu_lanes = getenv("TUMBLE_GPU_LANES");
    gpu->kernels_for_cpu = gpu->is_cpu && !(gpu_lanes && strcmp(gpu_lanes, "1") == 0);
    snprintf(gpu->driver, sizeof gpu->driver, "%s %s", driver.driverName, driver.driverInfo);
    vkGetPhysicalDeviceMemoryProperties(gpu->physical, &gpu->memory_props);
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu->physical, &count, NULL);
    VkQueueFamilyProperties families[16];
    if (count > 16) count = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu->physical, &count, families);
    gpu->timestamp_valid_bits = families[gpu->queue_family].timestampValidBits;
    gpu->queue_flags = families[gpu->queue_family].queueFlags;
}

static tb_result choose_device(tb_gpu* gpu, const char* choice)
{
    VkPhysicalDevice devices[MAX_DEVICES];
    uint32_t count = MAX_DEVICES;
    VkResult vr = vkEnumeratePhysicalDevices(gpu->instance, &count, devices);
    if (vr != VK_SUCCESS && vr != VK_INCOMPLETE)
        return tb_vk_check(gpu->diag, vr, "vkEnumeratePhysicalDevices");
    int index = pick_device(devices, count, choice);
    if (index < 0) return no_device_error(gpu, devices, count, choice);
    gpu->physical = devices[index];
    compute_queue_family(gpu->physical, &gpu->queue_family);
    read_device_facts(gpu);
    return TB_OK;
}

/* Whether the device offers `name`. */
static int has_device_extension(VkPhysicalDevice pd, const char* name)
{
    VkExtensionProperties props[512];
    uint32_t count = 512;
    VkResult vr = vkEnumerateDeviceExtensionProperties(pd, NULL, &count, props);
    if (vr != VK_SUCCESS && vr != VK_INCOMPLETE) return 0;
    for (uint32_t i = 0; i < count; i++)
        if (!strcmp(props[i].extensionName, name)) return 1;
    return 0;
}

/* TUMBLE_KERNEL_STATS: a developer's view of what the compiler made of each kernel. */
static int wants_kernel_stats(VkPhysicalDevice pd)
{
    const char* env = getenv("TUMBLE_KERNEL_STATS");
    return env && *env && strcmp(env, "0") &&
           has_device_extension(pd, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
}

static void load_kernel_stats(tb_gpu* gpu)
{
    gpu->executable_properties = (PFN_vkGetPipelineExecutablePropertiesKHR)
        vkGetDeviceProcAddr(gpu->device, "vkGetPipelineExecutablePropertiesKHR");
    gpu->executable_statistics = (PFN_vkGetPipelineExecutableStatisticsKHR)
        vkGetDeviceProcAddr(gpu->device, "vkGetPipelineExecutableStatisticsKHR");
    if (!gpu->executable_properties || !gpu->executable_statistics)
        gpu->executable_properties = NULL;
}

static tb_result create_device(tb_gpu* gpu, const tb_gpu_options* options)
{
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = gpu->queue_family, .queueCount = 1, .pQueuePriorities = &priority,
    };
    /* Buffer device addresses let the parallel primitives work on any buffer. */
    VkPhysicalDeviceVulkan12Features features12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .bufferDeviceAddress = VK_TRUE,
    };
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
        .pNext = &features12, .pipelineExecutableInfo = VK_TRUE,
    };
    const char* extensions[TB_MAX_EXTRA_EXTENSIONS + 1];
    uint32_t count = options->device_extension_count;
    for (uint32_t i = 0; i < count; i++) extensions[i] = options->device_extensions[i];
    int stats = wants_kernel_stats(gpu->physical);
    if (stats) extensions[count++] = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = stats ? (void*)&executable : (void*)&features12,
        .queueCreateInfoCount = 1, .pQueueCreateInfos = &queue,
        .enabledExtensionCount = count, .ppEnabledExtensionNames = extensions,
    };
    tb_result r = tb_vk_check(gpu->diag, vkCreateDevice(gpu->physical, &info, NULL, &gpu->device),
                              "vkCreateDevice");
    if (r) return r;
    if (stats) load_kernel_stats(gpu);
    vkGetDeviceQueue(gpu->device, gpu->queue_family, 0, &gpu->queue);
    VkCommandPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = gpu->queue_family,
    };
    r = tb_vk_check(gpu->diag, vkCreateCommandPool(gpu->device, &pool, NULL, &gpu->command_pool),
                    "vkCreateCommandPool");
    if (r) return r;
    VkFenceCreateInfo fence = { .sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO };
    return tb_vk_check(gpu->diag, vkCreateFence(gpu->device, &fence, NULL, &gpu->fence),
                       "vkCreateFence");
}

tb_result tb_gpu_create(tb_gpu* gpu, const tb_gpu_options* options, tb_diag* diag)
{
    memset(gpu, 0, sizeof *gpu);
    gpu->diag = diag;
    const char* choice = options->device;
    if (!choice || !*choice) choice = getenv("TUMBLE_DEVICE");
    if (choice && !*choice) choice = NULL;
    if (options->instance_extension_count > TB_MAX_EXTRA_EXTENSIONS)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "at most %d extra instance extensions",
                       TB_MAX_EXTRA_EXTENSIONS);
    if (options->device_extension_count > TB_MAX_EXTRA_EXTENSIONS)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "at most %d extra device extensions",
                       TB_MAX_EXTRA_EXTENSIONS);
    tb_result r = create_instance(gpu, options);
    if (!r) r = choose_device(gpu, choice);
    if (!r) r = create_device(gpu, options);
    if (r) tb_gpu_destroy(gpu);
    return r;
}

void tb_gpu_destroy(tb_gpu* gpu)
{
    if (gpu->device) {
        vkDeviceWaitIdle(gpu->device);
        vkDestroyFence(gpu->device, gpu->fence, NULL);
        vkDestroyCommandPool(gpu->device, gpu->command_pool, NULL);
        vkDestroyDevice(gpu->device, NULL);
    }
    if (gpu->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)
            vkGetInstanceProcAddr(gpu->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(gpu->instance, gpu->messenger, NULL);
    }
    if (gpu->instance) vkDestroyInstance(gpu->instance, NULL);
    tb_diag* diag = gpu->diag;
    memset(gpu, 0, sizeof *gpu);
    gpu->diag = diag;
}

tb_result tb_gpu_submit_wait(tb_gpu* gpu, const VkCommandBuffer* cbs, uint32_t count)
{
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = count, .pCommandBuffers = cbs,
    };
    tb_result r = tb_vk_check(gpu->diag, vkQueueSubmit(gpu->queue, 1, &submit, gpu->fence),
                              "vkQueueSubmit");
    if (r) return r;
    r = tb_vk_check(gpu->diag, vkWaitForFences(gpu->device, 1, &gpu->fence, VK_TRUE, UINT64_MAX),
                    "vkWaitForFences");
    vkResetFences(gpu->device, 1, &gpu->fence);
    return r;
}

tb_result tb_gpu_command_buffer(tb_gpu* gpu, VkCommandBuffer* out)
{
    VkCommandBufferAllocateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = gpu->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1,
    };
    return tb_vk_check(gpu->diag, vkAllocateCommandBuffers(gpu->device, &info, out),
                       "vkAllocateCommandBuffers");
}
