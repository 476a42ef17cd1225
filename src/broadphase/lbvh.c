/* The linear BVH broadphase (glsl/broadphase/lbvh_*.comp): every step builds a tree over
 * the bodies' boxes and each body walks it for its pairs.
 *
 *   lbvh_bounds      bounds of the live bodies' centres (planes left out)
 *   lbvh_keys        a Morton code per body in those bounds; large static bodies (wider
 *                    than the scene of centres) and dead slots get keys after every code
 *   sort             (key, slot) by 31 bits: leaves, then large bodies, then dead slots
 *   build            Karras' hierarchy, then the bottom-up refit (lbvh_build.h)
 *   lbvh_pairs       the search (the step's pair output runs it to count, then write): each
 *                    leaf walks the leaves after it, each dynamic body the large ones
 *
 * Large statics stay out of the tree so a plane cannot make every node above it infinite;
 * the bounds leave planes out so the codes keep their resolution where the bodies are.
 * Its arrays grow with the body capacity; the bounds live in a small buffer of their own
 * that the count pass clears for the next step.
 */
#include "broadphase/lbvh.h"

#include <stdlib.h>

#include "broadphase/lbvh_build.h"

struct tb_lbvh_search {
    VkPipeline bounds, keys, pairs;
    tb_lbvh_kernels build;
    tb_buffer scene;                  /* tb_gpu_lbvh_bounds */
    tb_buffer keys_buf, values, nodes, links;
    tb_buffer cache;                  /* partners the counting walk keeps (lbvh_pairs) */
    uint32_t capacity;
};
typedef tb_lbvh_search lbvh_state;

static void free_arrays(tb_broadphase_ctx* bp, lbvh_state* s)
{
    tb_buffer_destroy(bp->kit.memory, &s->keys_buf);
    tb_buffer_destroy(bp->kit.memory, &s->values);
    tb_buffer_destroy(bp->kit.memory, &s->nodes);
    tb_buffer_destroy(bp->kit.memory, &s->links);
    tb_buffer_destroy(bp->kit.memory, &s->cache);
    s->capacity = 0;
}

void tb_lbvh_search_destroy(tb_broadphase_ctx* bp, tb_lbvh_search* s)
{
    if (!s) return;
    VkPipeline all[] = { s->bounds, s->keys, s->pairs };
    tb_broadphase_destroy_pipelines(bp, all, sizeof all / sizeof all[0]);
    tb_lbvh_kernels_destroy(&s->build, bp->kit.pipelines);
    free_arrays(bp, s);
    tb_buffer_destroy(bp->kit.memory, &s->scene);
    free(s);
}

tb_result tb_lbvh_search_create(tb_broadphase_ctx* bp, tb_lbvh_search** out)
{
    lbvh_state* s = calloc(1, sizeof *s);
    *out = s;
    if (!s) return tb_fail(bp->kit.diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_pipelines* p = bp->kit.pipelines;
    tb_result r = tb_pipeline_create(p, "broadphase/lbvh_bounds", TB_WORKGROUP_SIZE, &s->bounds);
    if (!r) r = tb_pipeline_create(p, "broadphase/lbvh_keys", TB_WORKGROUP_SIZE, &s->keys);
    if (!r) r = tb_pipeline_create(p, "broadphase/lbvh_pairs", TB_WORKGROUP_SIZE, &s->pairs);
    if (!r) r = tb_lbvh_kernels_create(&s->build, p);
    /* The bounds start empty (all zero); after that every step leaves them so. */
    if (!r) r = tb_broadphase_buffer(bp, sizeof(tb_gpu_lbvh_bounds), &s->scene);
    if (!r) r = tb_gpu_kit_clear(&bp->kit, &s->scene);
    return r;
}

/* Nothing in the arrays outlives a step, so growth replaces them. */
tb_result tb_lbvh_search_reserve(tb_broadphase_ctx* bp, tb_lbvh_search* s, uint32_t capacity)
{
    if (capacity <= s->capacity) return TB_OK;
    free_arrays(bp, s);
    VkDeviceSize per_body = (VkDeviceSize)(capacity ? capacity : 1) * sizeof(uint32_t);
    tb_result r = tb_broadphase_buffer(bp, per_body, &s->keys_buf);
    if (!r) r = tb_broadphase_buffer(bp, per_body, &s->values);
    if (!r) r = tb_broadphase_buffer(bp, tb_lbvh_node_bytes(capacity), &s->nodes);
    if (!r) r = tb_broadphase_buffer(bp, tb_lbvh_link_bytes(capacity), &s->links);
    if (!r) r = tb_broadphase_buffer(bp, per_body * TB_LBVH_CACHED_PAIRS, &s->cache);
    if (r) free_arrays(bp, s);
    else s->capacity = capacity;
    return r;
}

static tb_gpu_ptr ptr_of(const tb_buffer* b)
{
    return tb_gpu_ptr_of(b, 0);
}

/* The push constants every lbvh kernel of the broadphase takes (lbvh_bodies.glsl). */
static tb_gpu_broadphase_push body_push(const lbvh_state* s, uint32_t mode, tb_gpu_ptr skip)
{
    tb_gpu_broadphase_push push = { { mode, s->capacity, 0, 0 }, { { 0 } } };
    push.address[0] = tb_gpu_addresses(s->keys_buf.address, s->values.address);
    push.address[1] = tb_gpu_addresses(s->scene.address, s->nodes.address);
    push.address[2] = tb_gpu_addresses(s->links.address, skip.address);
    push.address[3] = tb_gpu_addresses(s->cache.address, 0);
    return push;
}

static tb_lbvh_build build_of(tb_broadphase_ctx* bp, const lbvh_state* s, tb_gpu_ptr slots, tb_gpu_ptr skip)
{
    tb_lbvh_build b = {
        .capacity = s->capacity,
        .keys = ptr_of(&s->keys_buf), .items = ptr_of(&s->values), .count = slots,
        .skip = skip.address ? skip
                             : bp->io.abandoned,
        .nodes = ptr_of(&s->nodes), .links = ptr_of(&s->links),
        .box_min = bp->io.aabb_min,
        .box_max = bp->io.aabb_max,
        .rule = TB_DISPATCH_PER_BODY,
    };
    return b;
}

static uint32_t bounds_groups(uint32_t capacity)
{
    uint32_t groups = (capacity + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE;
    return groups < 1 ? 1 : groups > TB_LBVH_BOUNDS_GROUPS ? TB_LBVH_BOUNDS_GROUPS : groups;
}

tb_result tb_lbvh_search_record(tb_broadphase_ctx* bp, tb_lbvh_search* s, tb_pass_list* list,
                                tb_gpu_ptr count, tb_gpu_ptr skip, tb_pass* count_pass,
                                tb_pass* write_pass)
{
    tb_gpu_ptr scratch = bp->io.scratch;
    tb_gpu_ptr none = { 0 };
    tb_gpu_broadphase_push counting = body_push(s, TB_BROADPHASE_COUNT, skip);
    tb_gpu_broadphase_push writing = body_push(s, TB_BROADPHASE_WRITE, skip);
    tb_lbvh_build build = build_of(bp, s, count, skip);
    tb_result r = tb_broadphase_add(bp, list, s->bounds, TB_DISPATCH_FIXED,
                                    bounds_groups(s->capacity), none, &counting);
    if (!r) r = tb_broadphase_add(bp, list, s->keys, TB_DISPATCH_PER_BODY, 0, none, &counting);
    if (!r) r = tb_prims_sort(bp->kit.prims, list, ptr_of(&s->keys_buf), ptr_of(&s->values), count,
                              bp->io.body_capacity, TB_LBVH_SORT_BITS, scratch);
    if (!r) r = tb_lbvh_record_build(&s->build, list, bp->kit.diag, &build);
    *count_pass = tb_broadphase_pass(s->pairs, TB_DISPATCH_PER_BODY, 0, none, &counting);
    *write_pass = tb_broadphase_pass(s->pairs, TB_DISPATCH_PER_BODY, 0, none, &writing);
    return r;
}

/* ---- the lbvh broadphase: the search every step, never skipped ---------------------------- */

static tb_result lbvh_create(tb_broadphase_ctx* bp)
{
    tb_lbvh_search* s = NULL;
    tb_result r = tb_lbvh_search_create(bp, &s);
    bp->state = s;
    return r;
}

static tb_result lbvh_reserve(tb_broadphase_ctx* bp, uint32_t capacity)
{
    return tb_lbvh_search_reserve(bp, bp->state, capacity);
}

static tb_result lbvh_record(tb_broadphase_ctx* bp, tb_pass_list* list, tb_broadphase_search* search)
{
    tb_gpu_ptr slots = bp->io.slots;
    tb_gpu_ptr none = { 0 };
    search->n = 1;
    return tb_lbvh_search_record(bp, bp->state, list, slots, none, &search->counts[0],
                                 &search->writes[0]);
}

static void lbvh_destroy(tb_broadphase_ctx* bp)
{
    tb_lbvh_search_destroy(bp, bp->state);
    bp->state = NULL;
}

const tb_broadphase_ops tb_broadphase_lbvh = {
    "lbvh", "broadphase/lbvh", lbvh_create, lbvh_reserve, lbvh_record, lbvh_destroy, 0, NULL,
};
