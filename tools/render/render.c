/* tools/render: the public tr_ calls. A frame is one command buffer on the world's queue:
 * a barrier after the world's compute writes, a compute pass that lists the bodies of each
 * triangle-mesh shape (render_meshes.c), one render pass (planes, then instanced spheres,
 * boxes, capsules, cylinders, cones, hulls and meshes, then AABB lines, then contact lines,
 * depth-tested, then joint lines over everything, then the static bodies see-through), a
 * copy of the colour image into a host-visible buffer, and a wait on our own fence. Bodies
 * and contacts are never looped over on the host, except to read AABBs for the automatic
 * camera and to know whether a plane exists; joints are (render_joints.c), and shapes are,
 * to keep a mesh per hull and mesh shape and to know which shape types live
 * (render_hulls.c). */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "layout.h"
#include "render_internal.h"

/* Why the last tr_create failed (there is no renderer to hold it): tr_last_error(NULL). */
static char create_error[256];

tb_result tr_fail(tr_renderer* r, tb_result code, const char* fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vsnprintf(r->error, sizeof r->error, fmt, args);
    va_end(args);
    return code;
}

tb_result tr_vk(tr_renderer* r, VkResult vr, const char* what)
{
    if (vr == VK_SUCCESS) return TB_OK;
    if (vr == VK_ERROR_OUT_OF_HOST_MEMORY || vr == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "%s: out of memory (VkResult %d)", what, vr);
    return tr_fail(r, TB_ERROR_DEVICE, "%s failed (VkResult %d)", what, vr);
}

tr_options tr_default_options(void)
{
    tr_options o = {
        .width = 960, .height = 540,
        .camera = { .eye = { 10, 8, 14 }, .target = { 0, 0, 0 }, .up = { 0, 1, 0 },
                    .fov_y_degrees = 45.0f, .automatic = 1 },
        .color = TR_COLOR_BY_ID, .speed_scale = 10.0f, .show_aabbs = 0, .show_grid = 1,
        .show_contacts = 0, .show_joints = 1, .static_opacity = 0.3f,
    };
    return o;
}

static tb_result check_options(tr_renderer* r, const tr_options* o)
{
    if (o->width == 0 || o->height == 0 || o->width > r->max_image_size ||
        o->height > r->max_image_size)
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "image size %ux%u is outside 1..%u",
                       o->width, o->height, r->max_image_size);
    if ((unsigned)o->color > TR_COLOR_BY_SHAPE)
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "unknown colour mode %d", (int)o->color);
    if (!(o->speed_scale > 0.0f) || !isfinite(o->speed_scale))
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "speed_scale must be finite and > 0");
    if (!(o->static_opacity >= 0.0f && o->static_opacity <= 1.0f))
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "static_opacity must be in [0, 1]");
    if (!tr_camera_valid(&o->camera))
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "bad camera: fov must be in (1, 179) "
                       "degrees and, unless automatic, eye apart from target with up not "
                       "along the view direction");
    return TB_OK;
}

static tb_result create_objects(tr_renderer* r, const tr_options* options)
{
    tb_result res = tb_world_vulkan_device(r->world, &r->dev);
    if (res) return tr_fail(r, res, "tb_world_vulkan_device failed");
    if (!r->dev.has_graphics)
        return tr_fail(r, TB_ERROR_NO_DEVICE, "the world's queue cannot draw (a compute-only "
                       "queue family); the renderer needs a graphics-capable one");
    res = tr_gpu_init(r);
    if (!res) res = check_options(r, options);
    if (res) return res;
    r->options = *options;
    res = tr_targets_create(r);
    if (!res) res = tr_meshes_create(r);
    if (!res) res = tr_pipelines_create(r);
    return res;
}

tb_result tr_create(tb_world* world, const tr_options* options, tr_renderer** out)
{
    if (out) *out = NULL;
    if (!world || !out) {
        snprintf(create_error, sizeof create_error, "tr_create needs a world and an output");
        return TB_ERROR_INVALID_ARGUMENT;
    }
    tr_renderer* r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(create_error, sizeof create_error, "no host memory for a renderer");
        return TB_ERROR_OUT_OF_MEMORY;
    }
    r->world = world;
    tr_options defaults = tr_default_options();
    tb_result res = create_objects(r, options ? options : &defaults);
    if (res) {
        snprintf(create_error, sizeof create_error, "%s", r->error);
        tr_destroy(r);
        return res;
    }
    create_error[0] = '\0';
    *out = r;
    return TB_OK;
}

void tr_destroy(tr_renderer* r)
{
    if (!r) return;
    /* Every frame waits for its fence before returning, so nothing is in flight here. */
    if (r->dev.device) {
        tr_pipelines_destroy(r);
        tr_mesh_lists_destroy(r);
        tr_joints_destroy(r);
        tr_hulls_destroy(r);
        tr_gpu_destroy(r);
    }
    free(r);
}

tb_result tr_set_options(tr_renderer* r, const tr_options* options)
{
    if (!r || !options) return TB_ERROR_INVALID_ARGUMENT;
    tb_result res = check_options(r, options);
    if (res) return res;
    int resize = options->width != r->options.width || options->height != r->options.height;
    tr_options old = r->options;
    r->options = *options;
    if (!resize) return TB_OK;
    tr_targets_destroy(r);
    res = tr_targets_create(r);
    if (!res) return TB_OK;
    /* Keep the renderer usable at its old size; report the failure. */
    char why[sizeof r->error];
    memcpy(why, r->error, sizeof why);
    tr_targets_destroy(r);
    r->options = old;
    if (tr_targets_create(r)) tr_targets_destroy(r);
    memcpy(r->error, why, sizeof why);
    return res;
}

static void memory_barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkAccessFlags src_access,
                           VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = src_access, .dstAccessMask = dst_access,
    };
    vkCmdPipelineBarrier(cb, src, dst, 0, 1, &barrier, 0, NULL, 0, NULL);
}

static void fill_push(const tr_renderer* r, const tr_view* v, tr_push* p)
{
    memset(p, 0, sizeof *p);
    memcpy(p->view_proj, v->view_proj, sizeof p->view_proj);
    const tr_camera* c = &v->camera;
    p->eye[0] = c->eye.x; p->eye[1] = c->eye.y; p->eye[2] = c->eye.z;
    p->eye[3] = (float)v->far_plane;
    p->target[0] = c->target.x; p->target[1] = c->target.y; p->target[2] = c->target.z;
    p->target[3] = r->options.speed_scale;
    /* Towards the light: above, a little to +x and +z. */
    const double light[3] = { 0.45, 1.0, 0.3 };
    double len = sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    for (int i = 0; i < 3; i++) p->light[i] = (float)(light[i] / len);
    p->light[3] = (float)v->floor_y;
    p->mode[1] = (uint32_t)r->options.color;
    p->mode[2] = r->options.show_grid ? TR_FLAG_GRID : 0;
    if (r->options.static_opacity < 1.0f) p->mode[2] |= TR_FLAG_SEE_THROUGH;
}

/* The push constants of the see-through pass of static bodies. */
static tr_push static_pass_push(const tr_renderer* r, const tr_push* p)
{
    tr_push s = *p;
    uint32_t opacity = (uint32_t)lroundf(r->options.static_opacity * 255.0f);
    s.mode[2] = (p->mode[2] & ~TR_FLAG_SEE_THROUGH) | TR_FLAG_STATIC_PASS |
                (opacity << TR_OPACITY_SHIFT);
    return s;
}

/* What one frame draws besides the camera. */
typedef struct tr_frame {
    uint32_t slots;             /* body slots: instances of the body draws */
    int default_plane;          /* the grid under the scene, for a world without planes */
    uint32_t first_manifold;    /* the last step's manifolds in the manifold buffer */
    uint32_t manifolds;         /* 0: no contact overlay */
    uint32_t joint_vertices;    /* 0: no joint overlay */
} tr_frame;

static void push(const tr_renderer* r, const tr_push* p)
{
    vkCmdPushConstants(r->cb, r->pipeline_layout, TR_PUSH_STAGES, 0, sizeof *p, p);
}

static void draw_mesh(const tr_renderer* r, tr_push* p, uint32_t type, const tr_mesh* m,
                      uint32_t slots)
{
    p->mode[0] = type;
    push(r, p);
    vkCmdDrawIndexed(r->cb, m->index_count, slots, m->first_index, m->vertex_offset, 0);
}

/* Each mesh shape's mesh once per body of that shape: the instances its indirect draw
 * got from the list pass, pc.mode.w where its list starts. */
static void draw_mesh_shapes(const tr_renderer* r, tr_push* p)
{
    const VkDeviceSize stride = sizeof(VkDrawIndexedIndirectCommand);
    p->mode[0] = TB_GPU_SHAPE_MESH;
    for (uint32_t i = 0; i < r->mesh_draw_count; i++) {
        p->mode[3] = i * r->mesh_capacity;
        push(r, p);
        vkCmdDrawIndexedIndirect(r->cb, r->mesh_commands.buffer, i * stride, 1, (uint32_t)stride);
    }
}

/* The unit mesh of each shape type that has one (spheres, boxes, capsules, cylinders,
 * cones) and each hull and compound shape's mesh, every body slot an instance of each (the
 * shaders hide the slots that are not theirs), then the mesh shapes, with the bound mesh
 * pipeline. A unit mesh is drawn only while a shape of its type lives. */
static void draw_bodies(const tr_renderer* r, tr_push* p, uint32_t slots)
{
    VkCommandBuffer cb = r->cb;
    VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &r->vertices.buffer, &zero);
    vkCmdBindIndexBuffer(cb, r->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (uint32_t type = 0; type < TR_SHAPE_TYPES; type++)
        if (r->units[type].index_count && (r->shape_types & (1u << type)))
            draw_mesh(r, p, type, &r->units[type], slots);
    for (uint32_t i = 0; i < r->hull_draw_count; i++) {
        const tr_shape_draw* h = &r->hull_draws[i];
        p->mode[0] = h->shape_type;
        p->mode[3] = h->shape_slot;
        push(r, p);
        vkCmdDrawIndexed(cb, h->index_count, slots, h->first_index, h->vertex_offset, 0);
    }
    draw_mesh_shapes(r, p);
}

/* The contact overlay after the opaque scene, depth-tested: one instance per manifold. */
static void draw_contacts(const tr_renderer* r, tr_push* p, const tr_frame* f)
{
    vkCmdBindPipeline(r->cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->contact_pipeline);
    p->mode[3] = f->first_manifold;
    push(r, p);
    vkCmdDraw(r->cb, TB_MAX_MANIFOLD_POINTS * TR_CONTACT_VERTICES_PER_POINT, f->manifolds, 0, 0);
}

/* The joint overlay after the contacts, over everything: the segments the host wrote. */
static void draw_joints(const tr_renderer* r, const tr_push* p, const tr_frame* f)
{
    vkCmdBindPipeline(r->cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->joint_pipeline);
    push(r, p);
    vkCmdDraw(r->cb, f->joint_vertices, 1, 0, 0);
}

/* Everything inside the render pass. Planes go first: they fade out by blending over the
 * clear colour. Each body draw covers every body slot; the shaders hide what is not theirs.
 * See-through static bodies go last, blended over everything they hide. */
static void record_draws(const tr_renderer* r, const tr_view* v, const tr_frame* f)
{
    uint32_t slots = f->slots;
    VkCommandBuffer cb = r->cb;
    VkViewport viewport = { 0, 0, (float)r->options.width, (float)r->options.height, 0, 1 };
    VkRect2D scissor = { { 0, 0 }, { r->options.width, r->options.height } };
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->pipeline_layout, 0, 1,
                            &r->set, 0, NULL);
    tr_push p;
    fill_push(r, v, &p);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->plane_pipeline);
    if (slots) {
        push(r, &p);
        vkCmdDraw(cb, 6, slots, 0, 0);
    }
    if (f->default_plane) {
        tr_push d = p;
        d.mode[2] |= TR_FLAG_DEFAULT_PLANE;
        push(r, &d);
        vkCmdDraw(cb, 6, 1, 0, 0);
    }
    if (!slots) return;
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->mesh_pipeline);
    tr_push bodies = p;
    draw_bodies(r, &bodies, slots);
    if (r->options.show_aabbs) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->line_pipeline);
        push(r, &p);
        vkCmdDraw(cb, 24, slots, 0, 0);
    }
    if (f->manifolds) draw_contacts(r, &p, f);
    if (f->joint_vertices) draw_joints(r, &p, f);
    /* Opacity 0 leaves static bodies out altogether. */
    if ((p.mode[2] & TR_FLAG_SEE_THROUGH) && r->options.static_opacity > 0.0f) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r->static_pipeline);
        tr_push s = static_pass_push(r, &p);
        draw_bodies(r, &s, slots);
    }
}

static tb_result record(tr_renderer* r, const tr_view* v, const tr_frame* f)
{
    VkCommandBuffer cb = r->cb;
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    tb_result res = tr_vk(r, vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
    if (res) return res;
    /* The world's compute and transfer writes before our reads (the mesh list pass's
     * included); and the last frame's copy into the read-back buffer before this frame's. */
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_VERTEX_INPUT_BIT |
                   VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT |
                   VK_ACCESS_INDEX_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                   VK_ACCESS_TRANSFER_WRITE_BIT);
    tr_mesh_lists_record(r, f->slots);
    VkClearValue clears[2] = {
        { .color = { { TR_SKY_R / 255.0f, TR_SKY_G / 255.0f, TR_SKY_B / 255.0f, 1.0f } } },
        { .depthStencil = { 1.0f, 0 } },
    };
    VkRenderPassBeginInfo pass = {
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
        .renderPass = r->render_pass, .framebuffer = r->framebuffer,
        .renderArea = { { 0, 0 }, { r->options.width, r->options.height } },
        .clearValueCount = 2, .pClearValues = clears,
    };
    vkCmdBeginRenderPass(cb, &pass, VK_SUBPASS_CONTENTS_INLINE);
    record_draws(r, v, f);
    vkCmdEndRenderPass(cb);
    /* The render pass left the image in TRANSFER_SRC_OPTIMAL, its dependency ordering the
     * colour writes before this copy; rows come out top first, tightly packed. */
    VkBufferImageCopy region = {
        .imageSubresource = { VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1 },
        .imageExtent = { r->options.width, r->options.height, 1 },
    };
    vkCmdCopyImageToBuffer(cb, r->color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           r->readback.buffer, 1, &region);
    memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    /* The world's next step overwrites what the vertex shaders and the list pass read: make
     * it wait. */
    memory_barrier(cb, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
    return tr_vk(r, vkEndCommandBuffer(cb), "vkEndCommandBuffer");
}

static tb_result submit_and_wait(tr_renderer* r)
{
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &r->cb,
    };
    VkDevice d = r->dev.device;
    tb_result res = tr_vk(r, vkQueueSubmit(r->dev.queue, 1, &submit, r->fence), "vkQueueSubmit");
    if (res) return res;
    res = tr_vk(r, vkWaitForFences(d, 1, &r->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    if (res) return res;
    return tr_vk(r, vkResetFences(d, 1, &r->fence), "vkResetFences");
}

/* The last step's manifolds, bound for the overlay; f->manifolds stays 0 without any. */
static tb_result prepare_contacts(tr_renderer* r, tr_frame* f)
{
    tb_vulkan_contacts c;
    tb_result res = tb_world_vulkan_contacts(r->world, &c);
    if (res) return tr_fail(r, res, "tb_world_vulkan_contacts: %s",
                            tb_world_last_error(r->world));
    if (c.count == 0) return TB_OK;
    if (c.stride != sizeof(tb_gpu_manifold) || c.offset % c.stride != 0)
        return tr_fail(r, TB_ERROR_DEVICE, "manifolds of %u bytes at offset %llu do not match "
                       "the renderer's layout (%u bytes)", c.stride,
                       (unsigned long long)c.offset, (unsigned)sizeof(tb_gpu_manifold));
    res = tr_bind_contacts(r, &c);
    if (res) return res;
    f->first_manifold = (uint32_t)(c.offset / c.stride);
    /* A world past one binding's range shows the contacts the binding holds. */
    VkDeviceSize range = c.size < r->max_storage_range ? c.size : r->max_storage_range;
    uint64_t bound = range / c.stride;
    uint64_t shown = bound > f->first_manifold ? bound - f->first_manifold : 0;
    f->manifolds = c.count < shown ? c.count : (uint32_t)shown;
    return TB_OK;
}

tb_result tr_render(tr_renderer* r)
{
    if (!r) return TB_ERROR_INVALID_ARGUMENT;
    if (!r->framebuffer)
        return tr_fail(r, TB_ERROR_DEVICE, "the renderer has no images (a resize failed)");
    tb_vulkan_bodies bodies;
    tb_result res = tb_world_vulkan_bodies(r->world, &bodies);
    if (res) return tr_fail(r, res, "tb_world_vulkan_bodies: %s", tb_world_last_error(r->world));
    res = tr_bind_bodies(r, &bodies);
    if (!res) res = tr_hulls_update(r, &bodies);
    if (!res) res = tr_mesh_lists_prepare(r, bodies.slots);
    if (res) return res;
    tr_frame frame = { .slots = bodies.slots };
    if (r->options.show_contacts) res = prepare_contacts(r, &frame);
    if (!res && r->options.show_joints) res = tr_joints_prepare(r, &frame.joint_vertices);
    if (res) return res;
    tr_scene scene = { 0 };
    if (r->options.camera.automatic || r->options.show_grid) res = tr_scene_scan(r, &scene);
    if (res) return res;
    tr_view view;
    tr_view_resolve(&r->options, &scene, &view);
    frame.default_plane = r->options.show_grid && !scene.has_plane;
    res = record(r, &view, &frame);
    if (!res) res = submit_and_wait(r);
    if (res) return res;
    r->last_camera = view.camera;
    r->has_frame = 1;
    return TB_OK;
}

tb_result tr_read_pixels(tr_renderer* r, uint8_t* rgba)
{
    if (!r || !rgba) return TB_ERROR_INVALID_ARGUMENT;
    if (!r->has_frame)
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "no frame yet: call tr_render first");
    memcpy(rgba, r->readback.mapped, (size_t)r->options.width * r->options.height * 4);
    return TB_OK;
}

tb_result tr_write_png(tr_renderer* r, const char* path)
{
    if (!r || !path) return TB_ERROR_INVALID_ARGUMENT;
    if (!r->has_frame)
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "no frame yet: call tr_render first");
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = r->options.width;
    image.height = r->options.height;
    image.format = PNG_FORMAT_RGBA;
    if (!png_image_write_to_file(&image, path, 0, r->readback.mapped,
                                 (png_int_32)(r->options.width * 4), NULL))
        return tr_fail(r, TB_ERROR_INVALID_ARGUMENT, "writing %s failed: %s", path,
                       image.message);
    return TB_OK;
}

tr_camera tr_last_camera(const tr_renderer* r)
{
    return r ? r->last_camera : tr_default_options().camera;
}

const char* tr_last_error(const tr_renderer* r)
{
    return r ? r->error : create_error;
}
