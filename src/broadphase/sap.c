/* The parallel 1-axis sort and sweep broadphase (glsl/broadphase/sap*.comp), after the
 * GDC 2013 Bullet 3 talk: choose the axis along which the AABB centres spread most, sort
 * the boxes by their minimum on it, and let each body sweep forward through the sorted
 * boxes that can still reach it. Large static bodies (planes, ground boxes) stay out of the
 * sweep (sorted after it) and every dynamic body tests them.
 *
 * Passes: sap_keys writes the sort entries along the axis the previous step chose; the
 * radix sort orders them (32 key bits), large bodies and dead slots last; sap_gather copies
 * the boxes into sorted order, finds where the large ones are and measures the spread of
 * the centres; sap_sweep counts and then writes the pairs around the shared scan and
 * capacity check, and its writing run chooses the next step's axis. */
#include "broadphase/broadphase.h"

#include <stdlib.h>
#include <string.h>

/* One buffer per TB_SAP_* address, in that order. */
enum { SAP_BUFFERS = TB_SAP_ADDRESSES };

typedef struct sap_state {
    VkPipeline keys, gather, sweep;
    tb_buffer buffers[SAP_BUFFERS];
} sap_state;

static void release_buffers(tb_broadphase_ctx* bp, sap_state* s)
{
    for (int b = 0; b < SAP_BUFFERS; b++) tb_buffer_destroy(bp->kit.memory, &s->buffers[b]);
}

static void sap_destroy(tb_broadphase_ctx* bp)
{
    sap_state* s = bp->state;
    if (!s) return;
    VkPipeline all[] = { s->keys, s->gather, s->sweep };
    tb_broadphase_destroy_pipelines(bp, all, sizeof all / sizeof all[0]);
    release_buffers(bp, s);
    free(s);
    bp->state = NULL;
}

static tb_result sap_create(tb_broadphase_ctx* bp)
{
    sap_state* s = calloc(1, sizeof *s);
    if (!s) return tb_fail(bp->kit.diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    bp->state = s;
    tb_pipelines* p = bp->kit.pipelines;
    tb_result r = tb_pipeline_create(p, "broadphase/sap_keys", TB_WORKGROUP_SIZE, &s->keys);
    if (!r) r = tb_pipeline_create(p, "broadphase/sap_gather", TB_WORKGROUP_SIZE, &s->gather);
    if (!r) r = tb_pipeline_create(p, "broadphase/sap_sweep", TB_WORKGROUP_SIZE, &s->sweep);
    return r;
}

/* Bytes of the buffer behind address `index` for `capacity` body slots. */
static VkDeviceSize buffer_bytes(int index, uint32_t capacity)
{
    VkDeviceSize n = capacity ? capacity : 1;
    switch (index) {
    case TB_SAP_BOX_MIN:
    case TB_SAP_BOX_MAX: return n * 16;
    case TB_SAP_PARTIALS:
        return (n + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE * sizeof(tb_gpu_sap_partial);
    case TB_SAP_HEADER: return sizeof(tb_gpu_sap_header);
    default: return n * 4;
    }
}

/* Only the header's axis outlives a step, so growing the buffers is replacing them. The
 * world grows the sim's buffers first, which waits for the device, so no step still uses
 * ours. */
static tb_result sap_reserve(tb_broadphase_ctx* bp, uint32_t capacity)
{
    sap_state* s = bp->state;
    release_buffers(bp, s);
    tb_result r = TB_OK;
    for (int b = 0; b < SAP_BUFFERS && !r; b++)
        r = tb_broadphase_buffer(bp, buffer_bytes(b, capacity), &s->buffers[b]);
    /* A zero header: the first step sweeps along x (then each step chooses the next's). */
    return r ? r : tb_gpu_kit_clear(&bp->kit, &s->buffers[TB_SAP_HEADER]);
}

static tb_gpu_ptr buffer_ptr(const sap_state* s, int index, VkDeviceSize offset)
{
    return tb_gpu_ptr_of(&s->buffers[index], offset);
}

/* The push constants of every sap kernel: mode, and the addresses of all its buffers. */
static tb_gpu_broadphase_push push_of(const sap_state* s, uint32_t mode)
{
    tb_gpu_broadphase_push push;
    memset(&push, 0, sizeof push);
    push.args.x = mode;
    for (int b = 0; b < SAP_BUFFERS; b += 2)
        push.address[b / 2] = tb_gpu_addresses(s->buffers[b].address, s->buffers[b + 1].address);
    return push;
}

static tb_result sap_record(tb_broadphase_ctx* bp, tb_pass_list* list, tb_broadphase_search* search)
{
    sap_state* s = bp->state;
    tb_gpu_ptr slots = bp->io.slots;
    tb_gpu_ptr scratch = bp->io.scratch;
    tb_gpu_ptr none = { 0 };
    tb_gpu_broadphase_push count = push_of(s, TB_BROADPHASE_COUNT);
    tb_gpu_broadphase_push write = push_of(s, TB_BROADPHASE_WRITE);
    uint32_t cap = bp->io.body_capacity;
    tb_result r = tb_broadphase_add(bp, list, s->keys, TB_DISPATCH_PER_BODY, 0, none, &count);
    if (!r) r = tb_prims_sort(bp->kit.prims, list, buffer_ptr(s, TB_SAP_KEYS, 0),
                              buffer_ptr(s, TB_SAP_ORDER, 0), slots, cap, 32, scratch);
    if (!r) r = tb_broadphase_add(bp, list, s->gather, TB_DISPATCH_PER_BODY, 0, none, &count);
    search->counts[0] = tb_broadphase_pass(s->sweep, TB_DISPATCH_PER_BODY, 0, none, &count);
    search->writes[0] = tb_broadphase_pass(s->sweep, TB_DISPATCH_PER_BODY, 0, none, &write);
    search->n = 1;
    return r;
}

/* The header: the axis the last step chose for the next. */
static void sap_kept(const tb_broadphase_ctx* bp, VkBuffer* buffer, VkDeviceSize* bytes)
{
    const sap_state* s = bp->state;
    *buffer = s->buffers[TB_SAP_HEADER].buffer;
    *bytes = sizeof(tb_gpu_sap_header);
}

const tb_broadphase_ops tb_broadphase_sap = {
    "sap", "broadphase/sap", sap_create, sap_reserve, sap_record, sap_destroy, 0, sap_kept,
};
