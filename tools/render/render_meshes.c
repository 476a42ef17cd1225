/* Triangle-mesh shapes: their meshes, built on the host from the public API, and the bodies
 * that use each, listed on the GPU every frame.
 *
 * tb_shape_get_mesh_geometry gives a mesh's vertices (body frame) and triangles as they were
 * made; each triangle becomes three vertices with the normal of its front, the side from
 * which it runs counter-clockwise (flat shaded, as hulls are). render_hulls.c places these
 * meshes in the shared buffers with the hulls' and builds them again only when the shapes
 * change.
 *
 * A mesh may have millions of triangles, so it is not drawn over every body slot with the
 * slots of other shapes hidden, as a hull is: that would cost its vertices times the body
 * slots. Each frame mesh_lists.comp lists the body slots of every mesh shape instead and
 * counts them into that shape's indexed indirect draw: one draw per mesh shape, its
 * instances its bodies, and the bodies never read on the host. Each list has room for every
 * body slot, so its buffer holds mesh shapes x body slots slot numbers: meshes are few.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "layout.h"
#include "render_internal.h"

/* mesh_lists.comp counts instances in indirect draws of TR_MESH_COMMAND_UINTS uints. */
typedef char command_size_check[sizeof(VkDrawIndexedIndirectCommand) ==
                                TR_MESH_COMMAND_UINTS * sizeof(uint32_t) ? 1 : -1];

void tr_flat_triangle(const tb_vec3* a, const tb_vec3* b, const tb_vec3* c, tr_vertex out[3])
{
    const tb_vec3* p[3] = { a, b, c };
    double e1[3] = { b->x - a->x, b->y - a->y, b->z - a->z };
    double e2[3] = { c->x - a->x, c->y - a->y, c->z - a->z };
    double n[3];
    tr_cross3(e1, e2, n);
    double len = sqrt(tr_dot3(n, n));
    for (int k = 0; k < 3; k++) {
        out[k].position[0] = p[k]->x;
        out[k].position[1] = p[k]->y;
        out[k].position[2] = p[k]->z;
        for (int i = 0; i < 3; i++) out[k].normal[i] = len > 0 ? (float)(n[i] / len) : 0.0f;
    }
}

static tb_result geometry_failed(tr_renderer* r, tb_result res)
{
    return tr_fail(r, res, "tb_shape_get_mesh_geometry: %s", tb_world_last_error(r->world));
}

tb_result tr_mesh_shape_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** out,
                                 uint32_t* vertex_count)
{
    *out = NULL;
    *vertex_count = 0;
    uint32_t nv = 0, nt = 0, got_v, got_t;
    tb_result res = tb_shape_get_mesh_geometry(r->world, id, NULL, 0, NULL, 0, &nv, &nt);
    if (res) return geometry_failed(r, res);
    tb_vec3* points = malloc((nv ? nv : 1) * sizeof *points);
    uint32_t* tris = malloc(3 * (size_t)(nt ? nt : 1) * sizeof *tris);
    tr_vertex* v = malloc(3 * (size_t)(nt ? nt : 1) * sizeof *v);
    if (!points || !tris || !v)
        res = tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for a mesh of %u triangles", nt);
    else if ((res = tb_shape_get_mesh_geometry(r->world, id, points, nv, tris, nt, &got_v,
                                               &got_t)))
        res = geometry_failed(r, res);
    /* tb_shape_create_mesh refused indices out of range. */
    for (uint32_t t = 0; !res && t < nt; t++)
        tr_flat_triangle(&points[tris[3 * t]], &points[tris[3 * t + 1]], &points[tris[3 * t + 2]],
                         &v[3 * t]);
    free(points);
    free(tris);
    if (res) {
        free(v);
        return res;
    }
    *out = v;
    *vertex_count = 3 * nt;
    return TB_OK;
}

/* ---- the bodies of each mesh shape, listed on the GPU ------------------------------- */

/* A host-visible storage buffer of `bytes` in place of *b (its old one kept on failure). */
static tb_result replace_buffer(tr_renderer* r, VkDeviceSize bytes, VkBufferUsageFlags usage,
                                tr_buffer* b)
{
    tr_buffer fresh = { 0 };
    tb_result res = tr_host_buffer(r, bytes, usage | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &fresh);
    if (res) {
        tr_buffer_destroy(r, &fresh);
        return res;
    }
    tr_buffer_destroy(r, b);
    *b = fresh;
    return TB_OK;
}

/* Point the set's mesh-list bindings at the current buffers (the set is not in use: every
 * frame waits for its fence). */
static void bind_lists(tr_renderer* r)
{
    const uint32_t bindings[3] = { TR_BIND_MESH_OF_SHAPE, TR_BIND_MESH_COMMANDS,
                                   TR_BIND_MESH_INSTANCES };
    const tr_buffer* buffers[3] = { &r->mesh_of_shape, &r->mesh_commands, &r->mesh_instances };
    VkDescriptorBufferInfo infos[3];
    VkWriteDescriptorSet writes[3];
    for (int i = 0; i < 3; i++) {
        infos[i] = (VkDescriptorBufferInfo){ buffers[i]->buffer, 0, VK_WHOLE_SIZE };
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->set,
            .dstBinding = bindings[i], .descriptorCount = 1,
            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &infos[i],
        };
    }
    vkUpdateDescriptorSets(r->dev.device, 3, writes, 0, NULL);
}

/* New buffers for the current mesh draws and `slots` body slots: the shape table written,
 * a list per draw with room for every slot. Even without mesh shapes they exist (one
 * entry each), since mesh.vert names the list binding in every body draw. */
static tb_result rebuild(tr_renderer* r, uint32_t slots)
{
    uint32_t draws = r->mesh_draw_count ? r->mesh_draw_count : 1;
    uint32_t capacity = slots ? slots : 1, shapes = r->scan_slots ? r->scan_slots : 1;
    VkDeviceSize list_bytes = (VkDeviceSize)draws * capacity * sizeof(uint32_t);
    if (list_bytes > r->max_storage_range)
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "%u mesh shapes over %u body slots need "
                       "%llu bytes of body lists; one binding holds %llu", draws, capacity,
                       (unsigned long long)list_bytes, (unsigned long long)r->max_storage_range);
    tb_result res = replace_buffer(r, shapes * sizeof(uint32_t), 0, &r->mesh_of_shape);
    if (!res) res = replace_buffer(r, draws * sizeof(VkDrawIndexedIndirectCommand),
                                   VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, &r->mesh_commands);
    if (!res) res = replace_buffer(r, list_bytes, 0, &r->mesh_instances);
    if (res) return res;
    uint32_t* table = r->mesh_of_shape.mapped;
    for (uint32_t s = 0; s < shapes; s++) table[s] = TR_NO_MESH;
    for (uint32_t d = 0; d < r->mesh_draw_count; d++) table[r->mesh_draws[d].shape_slot] = d;
    bind_lists(r);
    r->mesh_capacity = capacity;
    r->mesh_lists_stale = 0;
    return TB_OK;
}

tb_result tr_mesh_lists_prepare(tr_renderer* r, uint32_t slots)
{
    if (r->mesh_lists_stale || slots > r->mesh_capacity || !r->mesh_instances.buffer) {
        tb_result res = rebuild(r, slots);
        if (res) return res;
    }
    /* No instances until the pass counts them; the host's writes are visible to the
     * submission that follows. */
    VkDrawIndexedIndirectCommand* commands = r->mesh_commands.mapped;
    for (uint32_t d = 0; d < r->mesh_draw_count; d++) {
        const tr_shape_draw* m = &r->mesh_draws[d];
        commands[d] = (VkDrawIndexedIndirectCommand){ m->index_count, 0, m->first_index,
                                                      m->vertex_offset, 0 };
    }
    return TB_OK;
}

void tr_mesh_lists_record(tr_renderer* r, uint32_t slots)
{
    if (!r->mesh_draw_count || !slots) return;
    VkCommandBuffer cb = r->cb;
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, r->mesh_list_pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, r->pipeline_layout, 0, 1,
                            &r->set, 0, NULL);
    tr_push p;
    memset(&p, 0, sizeof p);
    p.mode[0] = slots;
    p.mode[1] = r->mesh_capacity;
    p.mode[2] = r->scan_slots;
    vkCmdPushConstants(cb, r->pipeline_layout, TR_PUSH_STAGES, 0, sizeof p, &p);
    /* Rows of at most 65,535 groups, the least maxComputeWorkGroupCount every device has. */
    uint32_t groups = (slots + TR_MESH_LIST_GROUP - 1) / TR_MESH_LIST_GROUP;
    uint32_t row = groups < 65535 ? groups : 65535;
    vkCmdDispatch(cb, row, (groups + row - 1) / row, 1);
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT,
    };
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT,
                         0, 1, &barrier, 0, NULL, 0, NULL);
}

void tr_mesh_lists_destroy(tr_renderer* r)
{
    tr_buffer_destroy(r, &r->mesh_of_shape);
    tr_buffer_destroy(r, &r->mesh_commands);
    tr_buffer_destroy(r, &r->mesh_instances);
    r->mesh_capacity = 0;
    r->mesh_lists_stale = 0;
}
