/* Shapes: their records, the GPU shape table and its host copy, and the hulls the
 * narrowphase's hull table packs. */
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

tb_shape_record* tb_shape_lookup(tb_world* w, tb_shape_id id, uint32_t* slot, tb_result* r)
{
    if (!w) {
        *r = TB_ERROR_INVALID_ARGUMENT;
        return NULL;
    }
    if (id.index1 == 0 || id.world != w->serial || id.index1 > w->shape_slots.used) {
        *r = tb_fail(&w->diag, TB_ERROR_INVALID_ID, "shape id {%u, %u, %u} does not name a shape "
                     "of this world", id.index1, id.world, id.generation);
        return NULL;
    }
    tb_shape_record* s = &w->shapes[id.index1 - 1];
    if (!s->alive || s->generation != id.generation) {
        *r = tb_fail(&w->diag, TB_ERROR_STALE_ID, "shape id {%u, %u, %u} is stale: the shape was "
                     "destroyed", id.index1, id.world, id.generation);
        return NULL;
    }
    *slot = id.index1 - 1;
    *r = TB_OK;
    return s;
}

static tb_result grow_shape_table(tb_world* w, uint32_t needed)
{
    if (needed <= w->shape_table_capacity) return TB_OK;
    uint32_t cap = w->shape_table_capacity ? w->shape_table_capacity * 2 : 16;
    while (cap < needed) cap *= 2;
    tb_shape_record* records = realloc(w->shapes, cap * sizeof *records);
    if (records) w->shapes = records;
    tb_gpu_shape* gpu = realloc(w->gpu_shapes, cap * sizeof *gpu);
    if (gpu) w->gpu_shapes = gpu;
    if (!records || !gpu) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    uint32_t old = w->shape_table_capacity;
    memset(w->shapes + old, 0, (cap - old) * sizeof *records);
    memset(w->gpu_shapes + old, 0, (cap - old) * sizeof *gpu);
    w->shape_table_capacity = cap;
    return TB_OK;
}

/* Take a slot and fill both the host record and the GPU entry. */
static tb_result add_shape(tb_world* w, const tb_shape_record* record, const tb_gpu_shape* gpu,
                           tb_shape_id* out)
{
    if (w->shape_slots.live >= w->max_shapes)
        return tb_fail(&w->diag, TB_ERROR_CAPACITY, "the world holds at most %u shapes "
                       "(tb_world_def.max_shapes)", w->max_shapes);
    if (!w->shape_slots.free_count && grow_shape_table(w, w->shape_slots.used + 1))
        return TB_ERROR_OUT_OF_MEMORY;
    uint32_t slot;
    tb_slots_take(&w->shape_slots, &slot);
    uint16_t generation = tb_next_generation(w->shapes[slot].generation);
    w->shapes[slot] = *record;
    w->shapes[slot].generation = generation;
    w->shapes[slot].alive = 1;
    w->gpu_shapes[slot] = *gpu;
    w->gpu_shapes[slot].material = (tb_gpu_vec4){ record->material.friction,
                                                  record->material.restitution, 0.0f, 0.0f };
    w->shapes_dirty = 1;
    if (record->material.restitution > 0.0f && w->bouncy_shapes++ == 0) w->step_built = 0;
    *out = (tb_shape_id){ slot + 1, w->serial, w->shapes[slot].generation };
    return TB_OK;
}

/* The step records some stages only while shapes of a kind exist (step.c): the
 * narrowphase's hull pass while hull shapes do, the mesh passes while mesh shapes do, the
 * midphase split while mesh or compound shapes do. The first of a kind to come or the last
 * to go rebuilds the step. */
int tb_shape_type_is_round(tb_shape_type type)
{
    return type == TB_SHAPE_CAPSULE || type == TB_SHAPE_CYLINDER || type == TB_SHAPE_CONE;
}

int tb_shape_type_is_convex(tb_shape_type type)
{
    return type == TB_SHAPE_SPHERE || type == TB_SHAPE_BOX || type == TB_SHAPE_HULL ||
           tb_shape_type_is_round(type);
}

static void count_shapes(tb_world* w, uint32_t* count, int change)
{
    uint32_t before = *count;
    *count = (uint32_t)((int64_t)before + change);
    if ((before == 0) != (*count == 0)) w->step_built = 0;
}

/* The GPU image of a mesh, heightfield or compound: its bytes, and the image written at dst. */
static VkDeviceSize image_bytes(const tb_shape_record* rec)
{
    size_t n = rec->mesh ? tb_mesh_image_size(rec->mesh)
             : rec->compound ? tb_compound_image_size(rec->compound)
             : tb_heightfield_image_size(rec->heightfield);
    return n * sizeof(tb_gpu_uvec4);
}

static void pack_image(const tb_shape_record* rec, void* dst)
{
    if (rec->mesh) tb_mesh_pack(rec->mesh, dst);
    else if (rec->compound) tb_compound_pack(rec->compound, dst);
    else tb_heightfield_pack(rec->heightfield, dst);
}

/* A mesh's, heightfield's or compound's GPU image has a buffer of its own, which the shape
 * finds by its device address (tb_gpu_shape.hull.xy); the next submission uploads it. */
static tb_result create_mesh_buffer(tb_world* w, tb_shape_record* rec, tb_gpu_shape* gpu)
{
    VkDeviceSize bytes = image_bytes(rec);
    tb_result r = tb_buffer_create(&w->memory, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, &rec->mesh_buffer);
    if (r) return r;
    gpu->hull = tb_gpu_addresses(rec->mesh_buffer.address, 0);
    rec->mesh_pending = 1;
    return TB_OK;
}

/* A compound's children stay in use while it lives. */
static void use_children(tb_world* w, const tb_compound* c, int change)
{
    for (uint32_t i = 0; c && i < c->count; i++) {
        tb_shape_record* child = &w->shapes[c->parts[i].shape];
        child->users = (uint32_t)((int64_t)child->users + change);
    }
}

/* Hulls (boxes too), meshes and compounds own their geometry; the hull table packs hulls
 * for the GPU, a mesh or compound has its own buffer. */
tb_result tb_shapes_add(tb_world* w, tb_shape_record* rec, const tb_gpu_shape* gpu,
                        tb_shape_id* out)
{
    tb_gpu_shape entry = *gpu;
    int triangles = rec->mesh || rec->heightfield;
    int imaged = triangles || rec->compound;
    tb_result r = imaged ? create_mesh_buffer(w, rec, &entry) : TB_OK;
    if (!r) r = add_shape(w, rec, &entry, out);
    if (r) {
        tb_buffer_destroy(&w->memory, &rec->mesh_buffer);
        tb_shape_release_hull(rec);
        return r;
    }
    if (triangles) count_shapes(w, &w->mesh_shapes, +1);
    if (tb_shape_type_is_round(rec->type)) count_shapes(w, &w->round_shapes, +1);
    if (rec->compound) count_shapes(w, &w->compound_shapes, +1);
    if (imaged) w->mesh_uploads++;
    use_children(w, rec->compound, +1);
    if (!rec->hull) return TB_OK;
    w->narrowphase.hulls.dirty = 1;
    if (rec->type == TB_SHAPE_HULL) count_shapes(w, &w->hull_shapes, +1);
    return TB_OK;
}

void tb_shape_release_hull(tb_shape_record* s)
{
    if (s->mesh) {
        tb_mesh_free(s->mesh);
        free(s->mesh);
        s->mesh = NULL;
    }
    if (s->heightfield) {
        tb_heightfield_free(s->heightfield);
        free(s->heightfield);
        s->heightfield = NULL;
    }
    free(s->compound);
    s->compound = NULL;
    if (!s->hull) return;
    tb_hull_free(s->hull);
    free(s->hull);
    s->hull = NULL;
}

void tb_shapes_remove(tb_world* w, uint32_t slot)
{
    tb_shape_record* s = &w->shapes[slot];
    s->alive = 0;
    if (s->hull) w->narrowphase.hulls.dirty = 1;
    if (s->type == TB_SHAPE_HULL) count_shapes(w, &w->hull_shapes, -1);
    if (tb_shape_type_is_round(s->type)) count_shapes(w, &w->round_shapes, -1);
    use_children(w, s->compound, -1);
    if (s->compound) count_shapes(w, &w->compound_shapes, -1);
    if (s->mesh || s->heightfield) count_shapes(w, &w->mesh_shapes, -1);
    if (s->mesh || s->heightfield || s->compound) {
        if (s->mesh_pending) w->mesh_uploads--;
        s->mesh_pending = 0;
        tb_buffer_destroy(&w->memory, &s->mesh_buffer);
    }
    tb_shape_release_hull(s);
    tb_slots_give(&w->shape_slots, slot);
}

VkDeviceSize tb_shapes_mesh_upload_bytes(const tb_world* w)
{
    VkDeviceSize bytes = 0;
    for (uint32_t s = 0; w->mesh_uploads && s < w->shape_slots.used; s++)
        if (w->shapes[s].alive && w->shapes[s].mesh_pending)
            bytes += image_bytes(&w->shapes[s]);
    return bytes;
}

void tb_shapes_record_mesh_uploads(tb_world* w, tb_transfer* t)
{
    for (uint32_t s = 0; w->mesh_uploads && s < w->shape_slots.used; s++) {
        tb_shape_record* rec = &w->shapes[s];
        if (!rec->alive || !rec->mesh_pending) continue;
        void* dst = tb_transfer_upload(t, rec->mesh_buffer.buffer, 0, image_bytes(rec));
        if (!dst) continue;   /* the transfer's error stands; the upload waits */
        pack_image(rec, dst);
        rec->mesh_pending = 0;
        w->mesh_uploads--;
    }
}

tb_result tb_shapes_create_buffer(tb_world* w, uint32_t capacity)
{
    tb_buffer_destroy(&w->memory, &w->shape_buffer);
    tb_result r = tb_buffer_create(&w->memory, capacity * sizeof(tb_gpu_shape),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, &w->shape_buffer);
    if (r) return r;
    w->shape_buffer_capacity = capacity;
    tb_pipelines_bind(&w->pipelines, TB_BIND_SHAPES, w->shape_buffer.buffer);
    tb_graph_invalidate(&w->graph);
    w->buffer_generation++;
    w->shapes_dirty = 1;
    return TB_OK;
}

static const tb_hull* hull_at(const void* owner, uint32_t slot)
{
    const tb_shape_record* rec = &((const tb_world*)owner)->shapes[slot];
    return rec->alive ? rec->hull : NULL;
}

/* Packing rewrites the hull shapes' locators, so the shape table goes up again too. */
static tb_result prepare_hulls(tb_world* w)
{
    if (!w->narrowphase.hulls.dirty) return TB_OK;
    tb_hull_shapes shapes = { w->shape_slots.used, hull_at, w, w->gpu_shapes };
    int replaced = 0;
    tb_result r = tb_hull_table_prepare(&w->narrowphase, &shapes, &replaced);
    if (replaced) w->buffer_generation++;
    if (!r) w->shapes_dirty = 1;
    return r;
}

tb_result tb_world_prepare_shapes(tb_world* w)
{
    tb_result r = prepare_hulls(w);
    if (r || w->shape_slots.used <= w->shape_buffer_capacity) return r;
    uint32_t cap = w->shape_buffer_capacity * 2;
    while (cap < w->shape_slots.used) cap *= 2;
    return tb_shapes_create_buffer(w, cap);
}
