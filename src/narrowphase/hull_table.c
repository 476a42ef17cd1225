/* The GPU hull table (narrowphase.h): every live hull and box shape's geometry, packed. */
#include <stdlib.h>
#include <string.h>

#include "narrowphase/narrowphase.h"

#define INITIAL_VECTORS 256u
#define INITIAL_TOPOLOGY 1024u

static uint32_t hull_vector_count(const tb_hull* h)
{
    return h->vertex_count + h->face_count;
}

/* Edges (two words each), each vertex's ring (a head per vertex, an entry per edge end),
 * face entries, face vertex indices. */
static uint32_t hull_topology_count(const tb_hull* h)
{
    return 2 * h->edge_count + h->vertex_count + 2 * h->edge_count + h->face_count +
           h->index_count;
}

/* Each vertex's ring at `abase`: a head per vertex (first | count << 16, the first counted
 * from the entries, which follow the heads), then per edge end an entry (neighbour | edge
 * << 16), so the narrowphase can walk from vertex to vertex (support points, Gauss maps). */
static void pack_rings(uint32_t* topology, const tb_hull* h, uint32_t abase)
{
    uint32_t* heads = topology + abase;
    uint32_t* entries = heads + h->vertex_count;
    for (uint32_t v = 0; v < h->vertex_count; v++) heads[v] = 0;
    for (uint32_t e = 0; e < h->edge_count; e++) {
        heads[h->edges[e].v0] += 1u << 16;
        heads[h->edges[e].v1] += 1u << 16;
    }
    uint32_t first = 0;
    for (uint32_t v = 0; v < h->vertex_count; v++) {
        uint32_t count = heads[v] >> 16;
        heads[v] = first;   /* filled from here; the count is set back below */
        first += count;
    }
    for (uint32_t e = 0; e < h->edge_count; e++) {
        const tb_hull_edge* edge = &h->edges[e];
        entries[heads[edge->v0]++] = edge->v1 | e << 16;
        entries[heads[edge->v1]++] = edge->v0 | e << 16;
    }
    /* heads[v] now ends where v's ring ends: its start is the previous vertex's end. */
    uint32_t start = 0;
    for (uint32_t v = 0; v < h->vertex_count; v++) {
        uint32_t end = heads[v];
        heads[v] = start | (end - start) << 16;
        start = end;
    }
}

static tb_result create_buffer(tb_narrowphase* np, uint32_t binding, VkDeviceSize bytes,
                               tb_buffer* buf, int* replaced)
{
    tb_buffer_destroy(np->kit.memory, buf);
    tb_result r = tb_buffer_create(np->kit.memory, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, buf);
    if (r) return r;
    tb_pipelines_bind(np->kit.pipelines, binding, buf->buffer);
    tb_graph_invalidate(np->kit.graph);
    *replaced = 1;
    return TB_OK;
}

/* One host image and its GPU buffer, doubled until they hold `needed` elements of `size`
 * bytes. The host image is as large as the buffer, so packing never reallocates twice. */
static tb_result grow_array(tb_narrowphase* np, uint32_t binding, uint32_t needed, size_t size,
                            void** host, uint32_t* capacity, tb_buffer* buffer, int* replaced)
{
    if (needed <= *capacity) return TB_OK;
    uint32_t cap = *capacity;
    while (cap < needed) cap *= 2;
    void* grown = realloc(*host, (size_t)cap * size);
    if (!grown) return tb_fail(np->kit.diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    *host = grown;
    tb_result r = create_buffer(np, binding, (VkDeviceSize)cap * size, buffer, replaced);
    if (!r) *capacity = cap;
    return r;
}

static tb_result grow(tb_narrowphase* np, uint32_t vectors, uint32_t topology, int* replaced)
{
    tb_hull_table* t = &np->hulls;
    void* v = t->vectors;
    void* o = t->topology;
    tb_result r = grow_array(np, TB_BIND_HULL_VECTORS, vectors, sizeof *t->vectors, &v,
                             &t->vector_capacity, &t->vector_buffer, replaced);
    t->vectors = v;
    if (!r) r = grow_array(np, TB_BIND_HULL_TOPOLOGY, topology, sizeof *t->topology, &o,
                           &t->topology_capacity, &t->topology_buffer, replaced);
    t->topology = o;
    return r;
}

static tb_result hull_table_init(tb_narrowphase* np, int* replaced)
{
    tb_hull_table* t = &np->hulls;
    t->vector_capacity = INITIAL_VECTORS / 2;
    t->topology_capacity = INITIAL_TOPOLOGY / 2;
    t->dirty = 1;
    return grow(np, INITIAL_VECTORS, INITIAL_TOPOLOGY, replaced);
}

static void hull_table_destroy(tb_narrowphase* np)
{
    tb_hull_table* t = &np->hulls;
    tb_buffer_destroy(np->kit.memory, &t->vector_buffer);
    tb_buffer_destroy(np->kit.memory, &t->topology_buffer);
    free(t->vectors);
    free(t->topology);
    memset(t, 0, sizeof *t);
}

/* Write one hull at the given bases and point its shape at it. */
static void pack_hull(tb_hull_table* t, const tb_hull* h, uint32_t vbase, uint32_t tbase,
                      tb_gpu_shape* shape)
{
    for (uint32_t i = 0; i < h->vertex_count; i++)
        t->vectors[vbase + i] = (tb_gpu_vec4){ h->vertices[i][0], h->vertices[i][1],
                                               h->vertices[i][2], 0.0f };
    uint32_t pbase = vbase + h->vertex_count;
    for (uint32_t f = 0; f < h->face_count; f++)
        t->vectors[pbase + f] = (tb_gpu_vec4){ h->planes[f][0], h->planes[f][1],
                                               h->planes[f][2], h->planes[f][3] };
    for (uint32_t e = 0; e < h->edge_count; e++) {
        const tb_hull_edge* edge = &h->edges[e];
        t->topology[tbase + 2 * e] = edge->v0 | (uint32_t)edge->v1 << 16;
        t->topology[tbase + 2 * e + 1] = edge->left | (uint32_t)edge->right << 16;
    }
    pack_rings(t->topology, h, tbase + 2 * h->edge_count);
    /* Face entries, then the indices; a face's first index counts from the face base. */
    uint32_t fbase = tbase + 2 * h->edge_count + h->vertex_count + 2 * h->edge_count;
    for (uint32_t f = 0; f < h->face_count; f++)
        t->topology[fbase + f] = (h->face_count + h->faces[f].first) | h->faces[f].count << 16;
    for (uint32_t i = 0; i < h->index_count; i++)
        t->topology[fbase + h->face_count + i] = h->indices[i];
    shape->info.y = h->vertex_count;
    shape->info.z = h->face_count;
    shape->info.w = h->edge_count;
    shape->hull = (tb_gpu_uvec4){ vbase, pbase, tbase, fbase };
}

tb_result tb_hull_table_prepare(tb_narrowphase* np, const tb_hull_shapes* shapes, int* replaced)
{
    tb_hull_table* t = &np->hulls;
    if (!t->dirty) return TB_OK;
    uint32_t vectors = 0, topology = 0;
    for (uint32_t s = 0; s < shapes->count; s++) {
        const tb_hull* h = shapes->hull_at(shapes->owner, s);
        if (!h) continue;
        vectors += hull_vector_count(h);
        topology += hull_topology_count(h);
    }
    tb_result r = grow(np, vectors, topology, replaced);
    if (r) return r;
    uint32_t vbase = 0, tbase = 0;
    for (uint32_t s = 0; s < shapes->count; s++) {
        const tb_hull* h = shapes->hull_at(shapes->owner, s);
        if (!h) continue;
        pack_hull(t, h, vbase, tbase, &shapes->gpu_shapes[s]);
        vbase += hull_vector_count(h);
        tbase += hull_topology_count(h);
    }
    t->vectors_used = vectors;
    t->topology_used = topology;
    t->dirty = 0;
    t->upload = 1;
    return TB_OK;
}

VkDeviceSize tb_hull_table_upload_bytes(const tb_narrowphase* np)
{
    const tb_hull_table* t = &np->hulls;
    if (!t->upload) return 0;
    return t->vectors_used * sizeof(tb_gpu_vec4) + t->topology_used * sizeof(uint32_t);
}

void tb_hull_table_record_upload(tb_narrowphase* np, tb_transfer* transfer)
{
    tb_hull_table* t = &np->hulls;
    if (!t->upload) return;
    VkDeviceSize vbytes = t->vectors_used * sizeof(tb_gpu_vec4);
    VkDeviceSize tbytes = t->topology_used * sizeof(uint32_t);
    void* dst = vbytes ? tb_transfer_upload(transfer, t->vector_buffer.buffer, 0, vbytes) : NULL;
    if (dst) memcpy(dst, t->vectors, vbytes);
    dst = tbytes ? tb_transfer_upload(transfer, t->topology_buffer.buffer, 0, tbytes) : NULL;
    if (dst) memcpy(dst, t->topology, tbytes);
    t->upload = 0;
}

/* ---- the narrowphase's passes ------------------------------------------------------------ */

tb_result tb_narrowphase_init(tb_narrowphase* np, const tb_gpu_kit* kit, int* replaced)
{
    np->kit = *kit;
    /* The kernels are made when a step is first recorded (the hull pairs' when it is with
     * hulls): narrowphase/contacts is the longest of all to compile (on lavapipe a third
     * of a world's creation), and a world that never steps never needs it. */
    return hull_table_init(np, replaced);
}

void tb_narrowphase_destroy(tb_narrowphase* np)
{
    if (!np->kit.pipelines) return;
    tb_pipeline_destroy(np->kit.pipelines, np->contacts);
    tb_pipeline_destroy(np->kit.pipelines, np->hull_sat);
    tb_pipeline_destroy(np->kit.pipelines, np->hull_points);
    tb_pipeline_destroy(np->kit.pipelines, np->mesh_points);
    tb_pipeline_destroy(np->kit.pipelines, np->mesh_reduce);
    tb_pipeline_destroy(np->kit.pipelines, np->round_order);
    tb_pipeline_destroy(np->kit.pipelines, np->round_cull);
    tb_pipeline_destroy(np->kit.pipelines, np->round_points);
    hull_table_destroy(np);
    memset(np, 0, sizeof *np);
}

/* A pass dispatched over counters at dispatch_offset, with push constant args.x `arg`. */
static tb_result per_pair_with(const tb_narrowphase* np, tb_pass_list* list,
                               VkPipeline pipeline, VkBuffer counters,
                               VkDeviceSize dispatch_offset, uint32_t arg)
{
    tb_pass pass = tb_pass_with_args(pipeline, TB_DISPATCH_INDIRECT, counters, dispatch_offset,
                                     arg, 0, 0);
    return tb_pass_list_add(list, np->kit.diag, &pass);
}

static tb_result per_pair_at(const tb_narrowphase* np, tb_pass_list* list, VkPipeline pipeline,
                             VkBuffer counters, VkDeviceSize dispatch_offset)
{
    return per_pair_with(np, list, pipeline, counters, dispatch_offset, 0);
}

static tb_result per_pair(const tb_narrowphase* np, tb_pass_list* list, VkPipeline pipeline,
                          VkBuffer counters)
{
    return per_pair_at(np, list, pipeline, counters, TB_COUNTERS_PAIR_DISPATCH_OFFSET);
}

tb_result tb_narrowphase_record_contacts(tb_narrowphase* np, tb_pass_list* list,
                                         VkBuffer counters, int listed)
{
    tb_result r = tb_pipeline_create_once(np->kit.pipelines, "narrowphase/contacts",
                                          TB_WORKGROUP_SIZE, &np->contacts);
    /* args.x 1: over the pairs of its kinds that round_order listed. */
    return r ? r : per_pair_with(np, list, np->contacts, counters,
                                 TB_COUNTERS_PAIR_DISPATCH_OFFSET, listed ? 1u : 0u);
}

tb_result tb_narrowphase_record_hull_sat(tb_narrowphase* np, tb_pass_list* list,
                                         VkBuffer counters)
{
    tb_result r = tb_pipeline_create_once(np->kit.pipelines, "narrowphase/hull_sat",
                                          TB_WIDE_WORKGROUP_SIZE, &np->hull_sat);
    return r ? r : per_pair_at(np, list, np->hull_sat, counters,
                               TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET);
}

tb_result tb_narrowphase_record_hull_points(tb_narrowphase* np, tb_pass_list* list,
                                            VkBuffer counters, int listed)
{
    tb_result r = tb_pipeline_create_once(np->kit.pipelines, "narrowphase/hull_points",
                                          TB_WORKGROUP_SIZE, &np->hull_points);
    return r ? r : per_pair_with(np, list, np->hull_points, counters,
                                 TB_COUNTERS_PAIR_DISPATCH_OFFSET, listed ? 1u : 0u);
}

tb_result tb_narrowphase_record_mesh_points(tb_narrowphase* np, tb_pass_list* list,
                                            VkBuffer counters)
{
    tb_pipelines* p = np->kit.pipelines;
    tb_result r = tb_pipeline_create_once(p, "narrowphase/mesh_points", TB_WORKGROUP_SIZE,
                                          &np->mesh_points);
    if (!r) r = tb_pipeline_create_once(p, "narrowphase/mesh_reduce", TB_WORKGROUP_SIZE,
                                        &np->mesh_reduce);
    if (!r) r = per_pair(np, list, np->mesh_points, counters);
    if (!r) r = per_pair(np, list, np->mesh_reduce, counters);
    return r;
}

tb_result tb_narrowphase_record_round_cull(tb_narrowphase* np, tb_pass_list* list,
                                           VkBuffer counters)
{
    tb_pipelines* p = np->kit.pipelines;
    tb_result r = tb_pipeline_create_once(p, "narrowphase/round_order", TB_WIDE_WORKGROUP_SIZE,
                                          &np->round_order);
    if (!r) r = tb_pipeline_create_once(p, "narrowphase/round_cull", TB_WIDE_WORKGROUP_SIZE,
                                        &np->round_cull);
    if (!r) r = per_pair_at(np, list, np->round_cull, counters,
                            TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET);
    return r ? r : per_pair_at(np, list, np->round_order, counters,
                               TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET);
}

tb_result tb_narrowphase_record_round_points(tb_narrowphase* np, tb_pass_list* list,
                                             VkBuffer counters)
{
    tb_result r = tb_pipeline_create_once(np->kit.pipelines, "narrowphase/round_points",
                                          TB_WIDE_WORKGROUP_SIZE, &np->round_points);
    return r ? r : per_pair_at(np, list, np->round_points, counters,
                               TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET);
}
