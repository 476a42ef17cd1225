/* The Vulkan interop calls of include/tumble_vulkan.h. */
#include <string.h>

#include "api/api.h"
#include "world/world.h"
#include "tumble_vulkan.h"

tb_result tb_world_create_vulkan(const tb_world_def* def, const tb_vulkan_extensions* ext,
                                 tb_world** out)
{
    tb_gpu_options extra = { 0 };
    if (ext) {
        extra.instance_extensions = ext->instance_extensions;
        extra.instance_extension_count = ext->instance_extension_count;
        extra.device_extensions = ext->device_extensions;
        extra.device_extension_count = ext->device_extension_count;
    }
    return tb_api_world_create(def, &extra, out);
}

tb_result tb_world_vulkan_device(const tb_world* w, tb_vulkan_device* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out)
        return tb_fail(&((tb_world*)w)->diag, TB_ERROR_INVALID_ARGUMENT,
                       "tb_world_vulkan_device: out is NULL");
    *out = (tb_vulkan_device){
        .instance = w->gpu.instance, .physical_device = w->gpu.physical,
        .device = w->gpu.device, .queue = w->gpu.queue, .queue_family = w->gpu.queue_family,
        .has_graphics = (w->gpu.queue_flags & VK_QUEUE_GRAPHICS_BIT) != 0,
    };
    return TB_OK;
}

tb_result tb_world_vulkan_bodies(tb_world* w, tb_vulkan_bodies* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_vulkan_bodies: out is NULL");
    tb_result r = tb_world_flush(w);
    if (r) return r;
    const tb_body_store* s = &w->store;
    *out = (tb_vulkan_bodies){
        .position = s->gpu[TB_ARRAY_POS].buffer, .rotation = s->gpu[TB_ARRAY_ROT].buffer,
        .linear_velocity = s->gpu[TB_ARRAY_LINVEL].buffer, .info = s->gpu[TB_ARRAY_INFO].buffer,
        .aabb_min = s->gpu[TB_ARRAY_AABB_MIN].buffer, .aabb_max = s->gpu[TB_ARRAY_AABB_MAX].buffer,
        .shapes = w->shape_buffer.buffer, .slots = s->slots, .shape_slots = w->shape_slots.used,
        .generation = w->buffer_generation,
    };
    return TB_OK;
}

tb_result tb_world_vulkan_contacts(tb_world* w, tb_vulkan_contacts* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT,
                       "tb_world_vulkan_contacts: out is NULL");
    memset(out, 0, sizeof *out);
    tb_world_contact_buffer(w, &out->manifolds, &out->count, &out->size);
    out->offset = 0;
    out->stride = sizeof(tb_gpu_manifold);
    out->generation = w->buffer_generation;
    return TB_OK;
}
