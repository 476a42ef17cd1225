/* The incremental 3-axis sort and sweep (glsl/broadphase/isap*), after the parallel
 * incremental SAP of Coumans' GDC 2013 GPU rigid-body talk: instead of swapping endpoints
 * into place one at a time (sequential SAP), sort all of them on the three axes every step
 * and compare with last step's orders, read-only; an endpoint that moved looks at the ones
 * it passed, and those are where overlaps start. Pairs whose overlap ended are dropped from
 * last step's runs. The linear BVH's search takes over (the seed's fallback to another
 * broadphase) when there is no usable last step or the moves would cost more than it.
 *
 * Passes: keys (per body) -> 3 sorts (tb_prims_sort, 32-bit keys) -> ranks (orders and
 * places into this step's half) -> measure (moves) -> decide -> the LBVH's build (skipped
 * in incremental steps); then the step's pair output runs both searches' count and write
 * passes (the incremental one or the LBVH's does the work).
 *
 * What a step keeps for the next (orders, places, boxes, a header) lives in the half of its
 * parity, and last step's pairs are last step's half of the pair array: a step that is
 * abandoned and run again reads exactly what it read the first time. Growing the pair
 * buffer keeps both halves (src/world/sim.c); growing the body capacity zeroes this state, which
 * makes the next step search from scratch. */
#include "broadphase/isap.h"

#include <stdlib.h>

#define CONTROL_BYTES 256   /* the control, rounded up */
/* C99's static assertion: the array size is negative unless the control fits its room. */
typedef char isap_control_fits[sizeof(tb_gpu_isap_control) <= CONTROL_BYTES ? 1 : -1];

/* Bytes of one per-axis array: 3 axes of 2 endpoints per body slot. */
static VkDeviceSize axis_bytes(uint32_t capacity)
{
    return (VkDeviceSize)capacity * 6 * sizeof(uint32_t);
}

static VkDeviceSize keys_offset(void) { return CONTROL_BYTES; }
static VkDeviceSize order_offset(uint32_t c, int half) { return CONTROL_BYTES + (2 + half) * axis_bytes(c); }
static VkDeviceSize place_offset(uint32_t c, int half) { return CONTROL_BYTES + (4 + half) * axis_bytes(c); }
static VkDeviceSize box_offset(uint32_t c, int half)
{
    return CONTROL_BYTES + 6 * axis_bytes(c) + (VkDeviceSize)half * c * 2 * sizeof(tb_gpu_vec4);
}
static VkDeviceSize state_bytes(uint32_t c) { return box_offset(c, 2); }

static void isap_destroy(tb_broadphase_ctx* bp)
{
    tb_isap_state* s = bp->state;
    if (!s) return;
    VkPipeline all[] = { s->keys, s->ranks, s->measure, s->decide, s->pairs };
    tb_broadphase_destroy_pipelines(bp, all, sizeof all / sizeof all[0]);
    tb_buffer_destroy(bp->kit.memory, &s->state);
    tb_buffer_destroy(bp->kit.memory, &s->scratch);
    tb_lbvh_search_destroy(bp, s->scratch_search);
    free(s);
    bp->state = NULL;
}

static tb_result isap_create(tb_broadphase_ctx* bp)
{
    tb_isap_state* s = calloc(1, sizeof *s);
    if (!s) return tb_fail(bp->kit.diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    bp->state = s;
    tb_pipelines* p = bp->kit.pipelines;
    tb_result r = tb_pipeline_create(p, "broadphase/isap_keys", TB_WORKGROUP_SIZE, &s->keys);
    if (!r) r = tb_pipeline_create(p, "broadphase/isap_ranks", TB_WORKGROUP_SIZE, &s->ranks);
    if (!r) r = tb_pipeline_create(p, "broadphase/isap_measure", TB_WORKGROUP_SIZE, &s->measure);
    if (!r) r = tb_pipeline_create(p, "broadphase/isap_decide", 1, &s->decide);
    if (!r) r = tb_pipeline_create(p, "broadphase/isap_pairs", TB_WORKGROUP_SIZE, &s->pairs);
    if (!r) r = tb_lbvh_search_create(bp, &s->scratch_search);
    return r;
}

/* New, zeroed buffers for `capacity` slots: a zero header means "no last step". */
static tb_result isap_reserve(tb_broadphase_ctx* bp, uint32_t capacity)
{
    tb_isap_state* s = bp->state;
    tb_buffer_destroy(bp->kit.memory, &s->state);
    tb_buffer_destroy(bp->kit.memory, &s->scratch);
    s->capacity = 0;
    uint32_t endpoints = capacity * 2;
    tb_result r = tb_broadphase_buffer(bp, state_bytes(capacity), &s->state);
    if (!r) r = tb_broadphase_buffer(bp, tb_prims_sort_scratch(bp->kit.prims, endpoints), &s->scratch);
    if (!r) r = tb_lbvh_search_reserve(bp, s->scratch_search, capacity);
    if (!r) r = tb_gpu_kit_clear(&bp->kit, &s->state);
    if (!r) s->capacity = capacity;
    return r;
}

static tb_gpu_broadphase_push isap_push(const tb_isap_state* s, uint32_t mode)
{
    tb_gpu_broadphase_push push = { { mode, s->capacity, 0, 0 }, { { 0 } } };
    VkDeviceAddress base = s->state.address;
    uint32_t c = s->capacity;
    push.address[0] = tb_gpu_addresses(base + order_offset(c, 0), base + order_offset(c, 1));
    push.address[1] = tb_gpu_addresses(base + place_offset(c, 0), base + place_offset(c, 1));
    push.address[2] = tb_gpu_addresses(base + box_offset(c, 0), base + box_offset(c, 1));
    push.address[3] = tb_gpu_addresses(base + keys_offset(), base + TB_ISAP_CONTROL_OFFSET);
    return push;
}

/* Sort each axis's 2n endpoint keys, carrying the endpoint ids along. */
static tb_result record_sorts(tb_broadphase_ctx* bp, const tb_isap_state* s, tb_pass_list* list)
{
    tb_gpu_ptr count = tb_gpu_ptr_of(&s->state, TB_ISAP_CONTROL_OFFSET +
                                                    offsetof(tb_gpu_isap_control, sort));
    tb_gpu_ptr scratch = tb_gpu_ptr_of(&s->scratch, 0);
    VkDeviceSize axis = axis_bytes(s->capacity) / 3;
    tb_result r = TB_OK;
    for (uint32_t k = 0; k < 3 && !r; k++) {
        tb_gpu_ptr keys = tb_gpu_ptr_of(&s->state, keys_offset() + k * axis);
        tb_gpu_ptr ids = tb_gpu_ptr_of(&s->state, keys_offset() + axis_bytes(s->capacity) + k * axis);
        r = tb_prims_sort(bp->kit.prims, list, keys, ids, count, s->capacity * 2, 32, scratch);
    }
    return r;
}

static tb_result isap_record(tb_broadphase_ctx* bp, tb_pass_list* list, tb_broadphase_search* search)
{
    tb_isap_state* s = bp->state;
    tb_gpu_ptr none = { 0 };
    VkDeviceSize choice = TB_ISAP_CONTROL_OFFSET + offsetof(tb_gpu_isap_control, search);
    tb_gpu_ptr incremental = tb_gpu_ptr_of(&s->state, choice);
    tb_gpu_ptr scratch_slots = tb_gpu_ptr_of(&s->state, choice + 4);
    tb_gpu_broadphase_push count = isap_push(s, TB_BROADPHASE_COUNT);
    tb_gpu_broadphase_push write = isap_push(s, TB_BROADPHASE_WRITE);
    tb_result r = tb_broadphase_add(bp, list, s->keys, TB_DISPATCH_PER_BODY, 0, none, &count);
    if (!r) r = record_sorts(bp, s, list);
    if (!r) r = tb_broadphase_add(bp, list, s->ranks, TB_DISPATCH_PER_BODY, 0, none, &count);
    if (!r) r = tb_broadphase_add(bp, list, s->measure, TB_DISPATCH_PER_BODY, 0, none, &count);
    if (!r) r = tb_broadphase_add(bp, list, s->decide, TB_DISPATCH_FIXED, 1, none, &count);
    if (!r) r = tb_lbvh_search_record(bp, s->scratch_search, list, scratch_slots, incremental,
                                      &search->counts[1], &search->writes[1]);
    search->counts[0] = tb_broadphase_pass(s->pairs, TB_DISPATCH_PER_BODY, 0, none, &count);
    search->writes[0] = tb_broadphase_pass(s->pairs, TB_DISPATCH_PER_BODY, 0, none, &write);
    search->n = 2;
    return r;
}

/* The whole state buffer: its size follows the body capacity. */
static void isap_kept(const tb_broadphase_ctx* bp, VkBuffer* buffer, VkDeviceSize* bytes)
{
    const tb_isap_state* s = bp->state;
    *buffer = s->state.buffer;
    *bytes = state_bytes(s->capacity);
}

const tb_broadphase_ops tb_broadphase_isap = {
    "isap", "broadphase/isap", isap_create, isap_reserve, isap_record, isap_destroy, 1, isap_kept,
};
