/* Batching and the batched contact solve on the GPU (glsl/solver), driven alone.
 *
 * Colouring: random, lattice, star and chain constraint graphs are written straight into the
 * pair and manifold buffers, the colouring passes run, and the result is checked against the
 * batching property (no dynamic body twice in a colour, every constraint once, offsets and
 * dispatch arguments consistent) and against a plain C run of the same rounds, which must give
 * the very same colours.
 *
 * Solve: hand-made manifolds between a few bodies, one step of colouring, apply_forces,
 * prepare, the substeps and integrate, compared with what one step of the contact model
 * gives in closed form (resting impulse m g dt, bounce e v, speculative arrival, a push-out
 * that adds no velocity, kinetic friction mu g dt, a stack's 3:2:1 impulses), bit-identical
 * when repeated. */
#include "harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "world/world.h"
#include "solver/solver.h"

#define DT (1.0f / 60.0f)

/* ---- a world with the solver's buffers bound -------------------------------------------- */

typedef struct fixture {
    tb_world* w;
    tb_solver solver;
    uint32_t bodies;          ///< body slots, [0, statics) static, the rest dynamic
    uint32_t statics;
    uint32_t capacity;        ///< pair capacity of one half
    tb_body_id* ids;          ///< ids of the bodies, in slot order
    tb_buffer counters, pairs, manifolds, constraints, colour_list, colour_work, claim, solver_bodies;
    uint32_t parity;              /* the half reset_counters chose: this step's manifolds */
    tb_buffer tail_scratch;       /* device-local compaction scratch of the tail's list */
} fixture;

static tb_buffer host_buffer(tb_world* w, VkDeviceSize bytes, VkBufferUsageFlags extra)
{
    tb_buffer b;
    th_assert_ok(tb_buffer_create(&w->memory, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | extra, 1, &b));
    memset(b.mapped, 0, (size_t)bytes);
    return b;
}

/* Bodies from `defs`, the first `statics` of them static; pair capacity `capacity` per half. */
static void fixture_init_defs(fixture* f, tb_world* w, const tb_body_def* defs, uint32_t bodies,
                              uint32_t statics, uint32_t capacity)
{
    memset(f, 0, sizeof *f);
    f->w = w;
    f->bodies = bodies;
    f->statics = statics;
    f->capacity = capacity ? capacity : 1;
    f->ids = malloc(bodies * sizeof *f->ids);
    assert_non_null(f->ids);
    th_assert_ok(tb_body_create_many(w, defs, bodies, f->ids));
    th_assert_ok(tb_world_flush(w));
    assert_int_equal(w->store.slots, bodies);

    VkDeviceSize cap = f->capacity;
    f->counters = host_buffer(w, sizeof(tb_gpu_counters), VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    f->pairs = host_buffer(w, 2 * cap * sizeof(tb_gpu_uvec4), 0);
    f->manifolds = host_buffer(w, 2 * cap * sizeof(tb_gpu_manifold), 0);
    f->constraints = host_buffer(w, cap * sizeof(tb_gpu_constraint), 0);
    f->colour_list = host_buffer(w, cap * sizeof(uint32_t), 0);
    f->colour_work = host_buffer(w, 2 * cap * sizeof(uint32_t), 0);
    f->claim = host_buffer(w, bodies * sizeof(uint32_t), 0);
    f->solver_bodies = host_buffer(w, bodies * sizeof(tb_gpu_solver_body), 0);
    th_assert_ok(tb_buffer_create(&w->memory, tb_prims_compact_scratch(&w->prims, f->capacity),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                  0, &f->tail_scratch));
    memset(f->claim.mapped, 0xff, bodies * sizeof(uint32_t));
    tb_pipelines* p = &w->pipelines;
    tb_pipelines_bind(p, TB_BIND_COUNTERS, f->counters.buffer);
    tb_pipelines_bind(p, TB_BIND_PAIRS, f->pairs.buffer);
    tb_pipelines_bind(p, TB_BIND_COLOUR_LIST, f->colour_list.buffer);
    tb_pipelines_bind(p, TB_BIND_COLOUR_WORK, f->colour_work.buffer);
    tb_pipelines_bind(p, TB_BIND_BODY_CLAIM, f->claim.buffer);
    tb_pipelines_bind(p, TB_BIND_SOLVER_BODIES, f->solver_bodies.buffer);
    tb_graph_invalidate(&w->graph);
    th_assert_ok(tb_solver_init(&f->solver, p));
    th_assert_ok(tb_solver_prepare_soft_step(&f->solver));
}

/* `bodies` unit spheres, the first `statics` static. */
static void fixture_init(fixture* f, uint32_t bodies, uint32_t statics, uint32_t capacity)
{
    tb_world* w = th_world_create(NULL);
    tb_shape_id sphere = th_sphere(w, 0.5f);
    tb_body_def* defs = malloc(bodies * sizeof *defs);
    assert_non_null(defs);
    for (uint32_t i = 0; i < bodies; i++)
        defs[i] = i < statics ? th_static_def(sphere, th_v3((float)i, 0, 0))
                              : th_dynamic_def(sphere, th_v3((float)i, 2, 0));
    fixture_init_defs(f, w, defs, bodies, statics, capacity);
    free(defs);
}

static void fixture_destroy(fixture* f)
{
    tb_world* w = f->w;
    tb_solver_destroy(&f->solver);
    tb_buffer* all[] = { &f->counters, &f->pairs, &f->manifolds, &f->constraints,
                         &f->colour_list, &f->colour_work, &f->claim, &f->solver_bodies,
                         &f->tail_scratch };
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) tb_buffer_destroy(&w->memory, all[i]);
    free(f->ids);
    th_world_destroy(w);
}

static tb_gpu_counters* counters_of(fixture* f) { return f->counters.mapped; }
static tb_gpu_uvec4* pairs_of(fixture* f) { return f->pairs.mapped; }
static tb_gpu_manifold* manifolds_of(fixture* f) { return f->manifolds.mapped; }

/* The list of the constraints left to the tail, as the step records it after 64 rounds. */
static void record_tail_list(fixture* f, tb_pass_list* list)
{
    tb_solver_tail tail = {
        .prims = &f->w->prims, .work = tb_gpu_ptr_of(&f->colour_work, 0),
        .pair_count = tb_gpu_ptr_of(&f->counters, offsetof(tb_gpu_counters, state) + 8),
        .list_count = tb_gpu_ptr_of(&f->counters, offsetof(tb_gpu_counters, colouring) + 8),
        .scratch = tb_gpu_ptr_of(&f->tail_scratch, 0), .pair_capacity = f->capacity,
    };
    th_assert_ok(tb_solver_record_tail_list(&f->solver, list, f->counters.buffer, &tail));
}
static uint32_t* colour_list_of(fixture* f) { return f->colour_list.mapped; }

/* What step_begin and the broadphase leave: counters zero but the parity, the pair count and
 * its dispatch arguments (workgroups of 64, rows beyond the device's x limit). */
static void reset_counters(fixture* f, uint32_t pairs, uint32_t parity)
{
    tb_gpu_counters* c = counters_of(f);
    memset(c, 0, sizeof *c);
    uint32_t groups = (pairs + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE;
    uint32_t max_x = f->w->gpu.props.limits.maxComputeWorkGroupCount[0];
    uint32_t x = groups < max_x ? groups : max_x;
    c->pair_dispatch = (tb_gpu_uvec4){ x, x ? (groups + x - 1) / x : 1, 1, 0 };
    c->state = (tb_gpu_uvec4){ 0, parity, pairs, 0 };
    f->parity = parity;
}

/* A pass of a world shader dispatched per body; the caller destroys its pipeline. */
static tb_pass per_body_pass(fixture* f, const char* shader)
{
    tb_pass pass = { .rule = TB_DISPATCH_PER_BODY };
    th_assert_ok(tb_pipeline_create(&f->w->pipelines, shader, TB_WORKGROUP_SIZE, &pass.pipeline));
    return pass;
}

/* Write the params, record `list` and run it. */
static void run_passes(fixture* f, const tb_gpu_params* params, const tb_pass_list* list)
{
    tb_world* w = f->w;
    /* The kernels reach the contact arrays by address: this half's manifolds as this
     * step's, the other half's as last step's. */
    tb_gpu_params with = *params;
    VkDeviceSize half = (VkDeviceSize)f->capacity * sizeof(tb_gpu_manifold);
    VkDeviceAddress m = f->manifolds.address;
    with.contact_arrays[0] = tb_gpu_addresses(m + f->parity * half, m + (f->parity ^ 1u) * half);
    with.contact_arrays[1] = tb_gpu_addresses(f->constraints.address, 0);
    VkCommandBuffer cb;
    th_assert_ok(tb_gpu_command_buffer(&w->gpu, &cb));
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT };
    vkBeginCommandBuffer(cb, &begin);
    vkCmdUpdateBuffer(cb, w->params_buffer.buffer, 0, sizeof with, &with);
    VkMemoryBarrier upload = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                               .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                               .dstAccessMask = VK_ACCESS_UNIFORM_READ_BIT |
                                                VK_ACCESS_INDIRECT_COMMAND_READ_BIT };
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                         0, 1, &upload, 0, NULL, 0, NULL);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, w->pipelines.layout, 0, 1,
                            &w->pipelines.set, 0, NULL);
    tb_passes_record(cb, w->pipelines.layout, list->passes, list->count, w->params_buffer.buffer);
    VkMemoryBarrier readback = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                 .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                 .dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT };
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                         &readback, 0, NULL, 0, NULL);
    vkEndCommandBuffer(cb);
    th_assert_ok(tb_gpu_submit_wait(&w->gpu, &cb, 1));
    vkFreeCommandBuffers(w->gpu.device, w->gpu.command_pool, 1, &cb);
    /* The passes moved bodies behind the world's back: its mirror must be read again. */
    tb_body_store_stepped(&w->store);
}

static tb_gpu_params colouring_params(fixture* f, uint32_t rounds)
{
    tb_gpu_params p = f->w->params;
    p.gravity.w = DT;
    p.counts.x = f->bodies;
    p.capacity = (tb_gpu_uvec4){ f->capacity, 0, rounds, 1 };
    return p;
}

static void run_colouring(fixture* f, uint32_t pairs, uint32_t parity, uint32_t rounds,
                          uint32_t sub_rounds)
{
    reset_counters(f, pairs, parity);
    tb_pass_list list = { 0 };
    th_assert_ok(tb_solver_record_colouring(&f->solver, &list, f->counters.buffer, rounds,
                                            sub_rounds));
    uint32_t last = rounds == TB_MAX_COLOURS;
    assert_int_equal(list.count, 2 * ((rounds - last) * sub_rounds + last) + 1);
    tb_gpu_params params = colouring_params(f, rounds);
    /* apply_forces first: it resets the claims. */
    tb_pass forces = per_body_pass(f, "integrate/apply_forces");
    tb_pass_list all = { 0 };
    th_assert_ok(tb_pass_list_add(&all, &f->w->diag, &forces));
    for (uint32_t i = 0; i < list.count; i++)
        th_assert_ok(tb_pass_list_add(&all, &f->w->diag, &list.passes[i]));
    run_passes(f, &params, &all);
    tb_pipeline_destroy(&f->w->pipelines, forces.pipeline);
    tb_pass_list_free(&all);
    tb_pass_list_free(&list);
}

/* ---- constraint graphs ------------------------------------------------------------------ */

/* A graph: pair p joins bodies a[p], b[p] and its manifold has points[p] points. */
typedef struct graph {
    uint32_t n;
    uint32_t *a, *b, *points;
} graph;

static graph graph_alloc(uint32_t n)
{
    graph g = { n, calloc(n + 1, 4), calloc(n + 1, 4), calloc(n + 1, 4) };
    assert_true(g.a && g.b && g.points);
    return g;
}

static void graph_free(graph* g)
{
    free(g->a);
    free(g->b);
    free(g->points);
}

static int is_dynamic(const fixture* f, uint32_t body)
{
    return body >= f->statics;
}

/* n random pairs of distinct bodies, never two static ones; about one in six has no points. */
static graph random_graph(const fixture* f, uint32_t n, uint64_t seed)
{
    graph g = graph_alloc(n);
    th_rng rng = th_rng_seed(seed);
    for (uint32_t p = 0; p < n; p++) {
        uint32_t a, b;
        do {
            a = th_rng_u32(&rng) % f->bodies;
            b = th_rng_u32(&rng) % f->bodies;
        } while (a == b || (!is_dynamic(f, a) && !is_dynamic(f, b)));
        g.a[p] = a;
        g.b[p] = b;
        g.points[p] = th_rng_u32(&rng) % 6 == 0 ? 0 : 1 + th_rng_u32(&rng) % TB_MAX_MANIFOLD_POINTS;
    }
    return g;
}

/* Write the graph into half `parity`, and recognisable junk into the other half. */
static void write_graph(fixture* f, const graph* g, uint32_t parity)
{
    tb_gpu_uvec4* pairs = pairs_of(f);
    tb_gpu_manifold* m = manifolds_of(f);
    uint32_t cur = parity * f->capacity, other = (parity ^ 1) * f->capacity;
    for (uint32_t p = 0; p < f->capacity; p++) {
        pairs[other + p] = (tb_gpu_uvec4){ 0, 1, 7, 0xdead };
        memset(&m[other + p], 0, sizeof m[0]);
        m[other + p].info = (tb_gpu_uvec4){ 4, 0, 1, 0 };
    }
    for (uint32_t p = 0; p < g->n; p++) {
        pairs[cur + p] = (tb_gpu_uvec4){ g->a[p], g->b[p], TB_NO_COLOUR, 0 };
        memset(&m[cur + p], 0, sizeof m[0]);
        m[cur + p].info = (tb_gpu_uvec4){ g->points[p], g->a[p], g->b[p], 0 };
    }
}

/* ---- the plain C reference: the same rounds, one after the other ------------------------ */

#define CLAIM_FREE 0xffffffffu

static uint32_t scramble(uint32_t p, uint32_t round)
{
    const uint32_t mask = (1u << TB_COLOUR_INDEX_BITS) - 1u;
    uint32_t x = (p ^ (round * 0x2F0B3D5u)) & mask;
    x = (x * 0x9E3779B1u) & mask;
    x ^= x >> 13;
    x = (x * 0x85EBCA77u) & mask;
    x ^= x >> 11;
    return x;
}

/* One claim pass then one decide pass, as documented in glsl/solver/colouring.glsl. The
 * decide pass reads the claims as the claim pass left them (held[]) before changing any. */
static void reference_sub_round(const fixture* f, const graph* g, uint32_t r, uint32_t sub,
                                int another, uint32_t* claim, uint32_t* colour, uint8_t* held)
{
    uint32_t high = (uint32_t)(TB_MAX_COLOURS - 1 - r) << TB_COLOUR_INDEX_BITS;
    uint32_t mark = high - 1;
    for (uint32_t p = 0; p < g->n; p++) {
        uint32_t v = high | scramble(p, r), ends[2] = { g->a[p], g->b[p] };
        if (!g->points[p] || colour[p] != TB_NO_COLOUR || v == CLAIM_FREE) continue;
        int blocked = 0;
        for (int e = 0; e < 2; e++) blocked |= sub > 0 && is_dynamic(f, ends[e]) && claim[ends[e]] == mark;
        for (int e = 0; e < 2 && !blocked; e++)
            if (is_dynamic(f, ends[e]) && v < claim[ends[e]]) claim[ends[e]] = v;
    }
    for (uint32_t p = 0; p < g->n; p++) {
        uint32_t v = high | scramble(p, r), ends[2] = { g->a[p], g->b[p] };
        held[p] = 0;
        if (!g->points[p] || colour[p] != TB_NO_COLOUR || v == CLAIM_FREE) continue;
        for (int e = 0; e < 2; e++)
            if (!is_dynamic(f, ends[e]) || claim[ends[e]] == v) held[p] |= (uint8_t)(1 << e);
    }
    for (uint32_t p = 0; p < g->n; p++) {
        uint32_t ends[2] = { g->a[p], g->b[p] };
        if (!g->points[p] || colour[p] != TB_NO_COLOUR) continue;
        int won = held[p] == 3;
        if (won) colour[p] = r;
        for (int e = 0; e < 2 && another; e++)
            if ((held[p] >> e & 1) && is_dynamic(f, ends[e])) claim[ends[e]] = won ? mark : CLAIM_FREE;
    }
}

static void reference_colours(const fixture* f, const graph* g, uint32_t rounds,
                              uint32_t sub_rounds, uint32_t* colour)
{
    uint32_t* claim = malloc(f->bodies * sizeof *claim);
    uint8_t* held = malloc(g->n + 1);
    assert_true(claim && held);
    for (uint32_t i = 0; i < f->bodies; i++) claim[i] = CLAIM_FREE;
    for (uint32_t p = 0; p < g->n; p++) colour[p] = TB_NO_COLOUR;
    for (uint32_t r = 0; r < rounds; r++) {
        uint32_t subs = r + 1 < TB_MAX_COLOURS ? sub_rounds : 1;
        for (uint32_t s = 0; s < subs; s++)
            reference_sub_round(f, g, r, s, s + 1 < subs, claim, colour, held);
    }
    free(claim);
    free(held);
}

/* ---- checks ----------------------------------------------------------------------------- */

typedef struct colouring_summary {
    uint32_t colours_used, left, max_degree;
} colouring_summary;

static uint32_t max_dynamic_degree(const fixture* f, const graph* g)
{
    uint32_t* degree = calloc(f->bodies, sizeof *degree);
    uint32_t best = 0;
    for (uint32_t p = 0; p < g->n; p++) {
        if (!g->points[p]) continue;
        if (is_dynamic(f, g->a[p]) && ++degree[g->a[p]] > best) best = degree[g->a[p]];
        if (is_dynamic(f, g->b[p]) && ++degree[g->b[p]] > best) best = degree[g->b[p]];
    }
    free(degree);
    return best;
}

/* Within one colour no dynamic body appears twice. */
static void check_disjoint(const fixture* f, const graph* g, const uint32_t* colour)
{
    uint32_t* seen = malloc(f->bodies * sizeof *seen);
    for (uint32_t i = 0; i < f->bodies; i++) seen[i] = TB_NO_COLOUR;
    for (uint32_t c = 0; c < TB_MAX_COLOURS; c++) {
        for (uint32_t p = 0; p < g->n; p++) {
            if (colour[p] != c) continue;
            uint32_t ends[2] = { g->a[p], g->b[p] };
            for (int e = 0; e < 2; e++) {
                if (!is_dynamic(f, ends[e])) continue;
                if (seen[ends[e]] == c) fail_msg("body %u twice in colour %u", ends[e], c);
                seen[ends[e]] = c;
            }
        }
    }
    free(seen);
}

/* The colour list holds each coloured constraint once, inside its colour's range. */
static void check_colour_list(fixture* f, const graph* g, const uint32_t* colour)
{
    const tb_gpu_counters* c = counters_of(f);
    const uint32_t* list = colour_list_of(f);
    uint8_t* listed = calloc(g->n + 1, 1);
    for (uint32_t k = 0; k < TB_MAX_COLOURS; k++) {
        for (uint32_t i = 0; i < c->colour[k].x; i++) {
            uint32_t p = list[c->colour[k].y + i];
            assert_true(p < g->n);
            if (listed[p]) fail_msg("pair %u listed twice", p);
            listed[p] = 1;
            assert_int_equal(colour[p], k);
        }
    }
    for (uint32_t p = 0; p < g->n; p++)
        assert_int_equal(listed[p], colour[p] != TB_NO_COLOUR);
    free(listed);
}

/* Counts, offsets, batches, dispatch arguments and totals agree with the colours. */
static colouring_summary check_counters(fixture* f, const graph* g, const uint32_t* colour,
                                        uint32_t rounds)
{
    const tb_gpu_counters* c = counters_of(f);
    uint32_t count[TB_MAX_COLOURS] = { 0 }, constraints = 0, points = 0, left = 0;
    for (uint32_t p = 0; p < g->n; p++) {
        if (!g->points[p]) continue;
        constraints++;
        points += g->points[p];
        if (colour[p] == TB_NO_COLOUR) left++;
        else count[colour[p]]++;
    }
    uint32_t sg = f->w->gpu.subgroup_size, first = 0, batches = 0, used = 0;
    for (uint32_t k = 0; k < TB_MAX_COLOURS; k++) {
        assert_int_equal(c->colour[k].x, count[k]);
        assert_int_equal(c->colour[k].y, first);
        assert_int_equal(c->colour[k].z, batches);
        uint32_t groups = (count[k] + TB_SOLVER_WORKGROUP_SIZE - 1) / TB_SOLVER_WORKGROUP_SIZE;
        const tb_gpu_uvec4* d = &c->colour_dispatch[k];
        assert_true(d->x <= TB_DISPATCH_MAX_X && d->z == 1);
        assert_true((uint64_t)d->x * d->y >= groups);
        assert_true(groups == 0 ? d->x == 0 : (uint64_t)d->x * (d->y - 1) < groups);
        if (k >= rounds) assert_int_equal(count[k], 0);
        first += count[k];
        batches += (count[k] + sg - 1) / sg;
        used += count[k] > 0;
    }
    assert_int_equal(c->solver.x, used);
    assert_int_equal(c->solver.y, left);
    assert_int_equal(c->solver.z, batches);
    (void)points;   /* the narrowphase counts points (solver.w); colouring leaves them */
    assert_int_equal(first + left, constraints);
    uint32_t abort = left > 0 && rounds < TB_MAX_COLOURS ? TB_ABORT_COLOURS : 0;
    assert_int_equal(c->state.x, abort);
    colouring_summary s = { used, left, max_dynamic_degree(f, g) };
    return s;
}

/* Run the colouring of g and check everything; returns what it found. */
static colouring_summary colour_and_check(fixture* f, const graph* g, uint32_t parity,
                                          uint32_t rounds, uint32_t sub_rounds)
{
    assert_true(g->n <= f->capacity);
    write_graph(f, g, parity);
    run_colouring(f, g->n, parity, rounds, sub_rounds);
    uint32_t* colour = malloc((g->n + 1) * sizeof *colour);
    uint32_t* expected = malloc((g->n + 1) * sizeof *expected);
    const tb_gpu_uvec4* pairs = pairs_of(f);
    uint32_t cur = parity * f->capacity, other = (parity ^ 1) * f->capacity;
    for (uint32_t p = 0; p < g->n; p++) {
        colour[p] = pairs[cur + p].z;
        assert_int_equal(pairs[cur + p].x, g->a[p]);
        assert_int_equal(pairs[cur + p].y, g->b[p]);
        if (!g->points[p]) assert_int_equal(colour[p], TB_NO_COLOUR);
    }
    for (uint32_t p = 0; p < f->capacity; p++) assert_int_equal(pairs[other + p].z, 7);
    reference_colours(f, g, rounds, sub_rounds, expected);
    for (uint32_t p = 0; p < g->n; p++)
        if (colour[p] != expected[p])
            fail_msg("pair %u: colour %u, the C reference says %u", p, colour[p], expected[p]);
    check_disjoint(f, g, colour);
    check_colour_list(f, g, colour);
    colouring_summary s = check_counters(f, g, colour, rounds);
    free(colour);
    free(expected);
    return s;
}

/* ---- tests ------------------------------------------------------------------------------ */

/* Random graphs from empty to thousands of constraints, in both halves, with one to three
 * sub-rounds per round. Two sub-rounds come within a few colours of the largest number of
 * constraints at one dynamic body, which no colouring can beat. */
static void test_random_graphs(void** state)
{
    (void)state;
    fixture f;
    fixture_init(&f, 600, 60, 6000);
    const uint32_t sizes[] = { 0, 1, 2, 5, 63, 64, 65, 500, 3000, 6000 };
    for (uint32_t sub_rounds = 1; sub_rounds <= 3; sub_rounds++) {
        for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
            graph g = random_graph(&f, sizes[i], 100 + i);
            colouring_summary s = colour_and_check(&f, &g, (uint32_t)i & 1, TB_MAX_COLOURS, sub_rounds);
            if (sizes[i] >= 500)
                printf("  %u sub-round(s), %5u pairs: %2u colours, max dynamic degree %2u\n",
                       sub_rounds, sizes[i], s.colours_used, s.max_degree);
            assert_int_equal(s.left, 0);
            assert_true(s.colours_used >= s.max_degree);
            if (sub_rounds == 1) assert_true(s.colours_used <= 2 * s.max_degree + 2);
            else assert_true(s.colours_used <= s.max_degree + s.max_degree / 8 + 2);
            graph_free(&g);
        }
    }
    fixture_destroy(&f);
}

/* A pile-like graph: bodies on a jittered 3D lattice touching their face, edge and corner
 * neighbours, the bottom layer on a static ground. */
static void test_lattice_graph(void** state)
{
    (void)state;
    enum { SIDE = 12 };
    fixture f;
    fixture_init(&f, SIDE * SIDE * SIDE + 1, 1, 40000);
    graph g = graph_alloc(40000);
    th_rng rng = th_rng_seed(9);
    uint32_t n = 0;
    for (int x = 0; x < SIDE; x++)
        for (int y = 0; y < SIDE; y++)
            for (int z = 0; z < SIDE; z++) {
                uint32_t body = 1 + (uint32_t)((x * SIDE + y) * SIDE + z);
                if (y == 0) { g.a[n] = 0; g.b[n] = body; g.points[n++] = 4; }
                for (int d = 14; d < 27; d++) {  /* the 13 neighbours after it, of 26 */
                    int dx = d / 9 - 1, dy = d / 3 % 3 - 1, dz = d % 3 - 1;
                    if (x + dx >= SIDE || y + dy < 0 || y + dy >= SIDE || z + dz < 0 ||
                        z + dz >= SIDE)
                        continue;
                    if (th_rng_u32(&rng) % 4 == 0) continue;
                    g.a[n] = body;
                    g.b[n] = 1 + (uint32_t)(((x + dx) * SIDE + y + dy) * SIDE + z + dz);
                    g.points[n++] = 1 + th_rng_u32(&rng) % 4;
                }
            }
    g.n = n;
    colouring_summary s = colour_and_check(&f, &g, 0, TB_MAX_COLOURS, TB_SOLVER_SUB_ROUNDS);
    printf("  lattice, %u pairs: %u colours, max dynamic degree %u\n", n, s.colours_used,
           s.max_degree);
    assert_int_equal(s.left, 0);
    assert_true(s.colours_used <= s.max_degree + s.max_degree / 2 + 2);
    graph_free(&g);
    fixture_destroy(&f);
}

/* ~200k constraints among 100k bodies. */
static void test_large_graph(void** state)
{
    (void)state;
    fixture f;
    const uint32_t n = 200000;
    fixture_init(&f, 100000, 5000, n);
    graph g = random_graph(&f, n, 4242);
    colouring_summary s = colour_and_check(&f, &g, 1, 24, TB_SOLVER_SUB_ROUNDS);
    printf("  %u pairs: %u colours, max dynamic degree %u\n", n, s.colours_used, s.max_degree);
    assert_int_equal(s.left, 0);
    assert_true(s.colours_used <= s.max_degree + s.max_degree / 8 + 2);
    graph_free(&g);
    fixture_destroy(&f);
}

/* Too few rounds: the leftovers abandon the step; what was coloured is still consistent. */
static void test_too_few_rounds_aborts(void** state)
{
    (void)state;
    fixture f;
    fixture_init(&f, 300, 10, 3000);
    graph g = random_graph(&f, 3000, 77);
    for (uint32_t sub_rounds = 1; sub_rounds <= 2; sub_rounds++) {
        colouring_summary s = colour_and_check(&f, &g, sub_rounds & 1, 3, sub_rounds);
        assert_true(s.left > 0);
        assert_int_equal(counters_of(&f)->state.x, TB_ABORT_COLOURS);
    }
    graph_free(&g);
    fixture_destroy(&f);
}

/* A star: one dynamic body in more constraints than rounds. Each round can colour only one
 * of them; with R < 64 the step is abandoned, with R = 64 the rest is left to the tail. */
static void test_star(void** state)
{
    (void)state;
    fixture f;
    fixture_init(&f, 200, 0, 200);
    const uint32_t rounds[] = { 8, 40, TB_MAX_COLOURS };
    for (size_t i = 0; i < sizeof rounds / sizeof rounds[0]; i++) {
        graph g = graph_alloc(150);
        for (uint32_t p = 0; p < g.n; p++) {
            g.a[p] = p & 1 ? 0 : p + 1;   /* both orders */
            g.b[p] = p & 1 ? p + 1 : 0;
            g.points[p] = 1 + p % 4;
        }
        colouring_summary s = colour_and_check(&f, &g, 0, rounds[i], TB_SOLVER_SUB_ROUNDS);
        assert_int_equal(s.colours_used, rounds[i]);
        assert_int_equal(s.left, g.n - rounds[i]);
        graph_free(&g);
    }
    fixture_destroy(&f);
}

/* Many dynamic bodies resting on one static body (and a few on a second): a static body is
 * never claimed, so they all share colour 0. */
static void test_static_bodies_do_not_block(void** state)
{
    (void)state;
    fixture f;
    fixture_init(&f, 2002, 2, 2000);
    graph g = graph_alloc(2000);
    for (uint32_t p = 0; p < g.n; p++) {
        uint32_t ground = p % 97 == 0 ? 1 : 0;
        g.a[p] = p % 3 ? ground : p + 2;
        g.b[p] = p % 3 ? p + 2 : ground;
        g.points[p] = 4;
    }
    colouring_summary s = colour_and_check(&f, &g, 1, 4, TB_SOLVER_SUB_ROUNDS);
    assert_int_equal(s.colours_used, 1);
    assert_int_equal(s.left, 0);
    assert_int_equal(counters_of(&f)->colour[0].x, g.n);
    graph_free(&g);
    fixture_destroy(&f);
}

/* A chain 0-1-2-...: index-ordered claims would colour one link per round; scrambled ones
 * need only a few colours. */
static void test_chain(void** state)
{
    (void)state;
    fixture f;
    fixture_init(&f, 4001, 0, 4000);
    graph g = graph_alloc(4000);
    for (uint32_t p = 0; p < g.n; p++) {
        g.a[p] = p;
        g.b[p] = p + 1;
        g.points[p] = 2;
    }
    colouring_summary s = colour_and_check(&f, &g, 0, 16, TB_SOLVER_SUB_ROUNDS);
    printf("  chain of %u: %u colours\n", g.n, s.colours_used);
    assert_int_equal(s.left, 0);
    assert_true(s.colours_used <= 4);
    graph_free(&g);
    fixture_destroy(&f);
}

/* ---- the batched solve ------------------------------------------------------------------ */

#define THRESHOLD 1.0f
#define PUSH_SPEED 3.0f
#define SUBSTEPS 6u

/* The ground: a static box whose top face is the plane y = 0.5. */
static tb_body_def ground_def(tb_world* w)
{
    return th_static_def(th_box(w, th_v3(5, 0.5f, 5)), th_v3(0, 0, 0));
}

/* Pair p of half `parity` joins a and b; normal from a to b; points (xyz, separation). */
static void set_contact(fixture* f, uint32_t parity, uint32_t p, uint32_t a, uint32_t b,
                        tb_vec3 n, float friction, float restitution, uint32_t count,
                        const tb_gpu_vec4* points)
{
    uint32_t at = parity * f->capacity + p, e;
    memcpy(&e, &restitution, sizeof e);
    pairs_of(f)[at] = (tb_gpu_uvec4){ a, b, TB_NO_COLOUR, 0 };
    tb_gpu_manifold* m = &manifolds_of(f)[at];
    memset(m, 0, sizeof *m);
    m->normal = (tb_gpu_vec4){ n.x, n.y, n.z, friction };
    m->info = (tb_gpu_uvec4){ count, a, b, e };
    for (uint32_t k = 0; k < count; k++) m->point[k] = points[k];
}

/* The solver's part of a step on the pairs written: colouring, prepare, apply_forces, the
 * substeps, integrate. apply_forces runs after the colouring so that a step abandoned for
 * colours leaves the bodies untouched. The contacts are as soft as the world's defaults. */
static void solver_step(fixture* f, uint32_t pairs, uint32_t parity, uint32_t rounds,
                        uint32_t substeps, uint32_t iterations)
{
    for (uint32_t p = 0; p < pairs; p++) pairs_of(f)[parity * f->capacity + p].z = TB_NO_COLOUR;
    reset_counters(f, pairs, parity);
    tb_pass forces = per_body_pass(f, "integrate/apply_forces");
    tb_pass integrate = per_body_pass(f, "integrate/integrate");
    tb_pass_list list = { 0 };
    VkBuffer counters = f->counters.buffer;
    th_assert_ok(tb_solver_record_colouring(&f->solver, &list, counters, rounds, TB_SOLVER_SUB_ROUNDS));
    if (rounds == TB_MAX_COLOURS) record_tail_list(f, &list);
    th_assert_ok(tb_solver_record_prepare(&f->solver, &list, counters));
    th_assert_ok(tb_pass_list_add(&list, &f->w->diag, &forces));
    th_assert_ok(tb_solver_record_solve(&f->solver, &list, counters, rounds, substeps, iterations));
    th_assert_ok(tb_pass_list_add(&list, &f->w->diag, &integrate));
    tb_gpu_params params = colouring_params(f, rounds);
    params.counts.z = substeps;
    params.capacity.w = iterations;
    params.contact = (tb_gpu_vec4){ 0.02f, THRESHOLD, PUSH_SPEED, 0 };
    tb_solver_contact contact = { f->w->contact_hertz, f->w->contact_damping_ratio };
    params.soft = tb_solver_softness(&contact, DT / (float)substeps, 1.0);
    params.soft_static = tb_solver_softness(&contact, DT / (float)substeps, 2.0);
    run_passes(f, &params, &list);
    tb_pipeline_destroy(&f->w->pipelines, forces.pipeline);
    tb_pipeline_destroy(&f->w->pipelines, integrate.pipeline);
    tb_pass_list_free(&list);
}

static float mass_of(const fixture* f, uint32_t slot)
{
    return f->w->bodies[slot].mass;
}

static tb_vec3 velocity_of(fixture* f, uint32_t slot)
{
    tb_vec3 v, w;
    th_assert_ok(tb_body_get_velocity(f->w, f->ids[slot], &v, &w));
    return v;
}

static tb_vec3 spin_of(fixture* f, uint32_t slot)
{
    tb_vec3 v, w;
    th_assert_ok(tb_body_get_velocity(f->w, f->ids[slot], &v, &w));
    return w;
}

static tb_vec3 position_of(fixture* f, uint32_t slot)
{
    tb_vec3 x;
    th_read_pose(f->w, f->ids[slot], &x, NULL);
    return x;
}

static tb_gpu_vec4 impulse_of(fixture* f, uint32_t parity, uint32_t p, uint32_t k)
{
    return manifolds_of(f)[parity * f->capacity + p].impulse[k];
}

/* A unit sphere resting on the ground, the pair in either order: each substep's normal
 * impulse is m g h, the step's m g dt, and the sphere keeps still; warm started, the next
 * step does the same. */
static void test_solve_resting_sphere(void** state)
{
    (void)state;
    for (uint32_t flip = 0; flip < 2; flip++) {
        fixture f;
        tb_world* w = th_world_create(NULL);
        tb_body_def defs[2] = { ground_def(w), th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 1, 0)) };
        fixture_init_defs(&f, w, defs, 2, 1, 4);
        double g = -tb_world_get_gravity(w).y, m = mass_of(&f, 1);
        tb_gpu_vec4 point = { 0, 0.5f, 0, 0 };
        set_contact(&f, flip, 0, flip, 1 - flip, th_v3(0, flip ? -1.0f : 1.0f, 0), 0.5f, 0, 1, &point);
        for (int step = 0; step < 2; step++) {
            solver_step(&f, 1, flip, 4, SUBSTEPS, 1);
            th_assert_near(velocity_of(&f, 1).y, 0, 1e-6, 0);
            th_assert_near(impulse_of(&f, flip, 0, 0).x, m * g * DT / SUBSTEPS, 0, 1e-3);
            th_assert_near(impulse_of(&f, flip, 0, 0).w, m * g * DT, 0, 1e-3);
            th_assert_near(position_of(&f, 1).y, 1.0, 2e-5, 0);
        }
        fixture_destroy(&f);
    }
}

/* One sphere over the ground with velocity v (y only) and one contact point of separation s. */
static void sphere_contact(fixture* f, float height, float vy, float separation, float restitution)
{
    tb_world* w = th_world_create(NULL);
    tb_body_def defs[2] = { ground_def(w), th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, height, 0)) };
    defs[1].linear_velocity = th_v3(0, vy, 0);
    fixture_init_defs(f, w, defs, 2, 1, 4);
    tb_gpu_vec4 point = { 0, 0.5f + 0.5f * separation, 0, separation };
    set_contact(f, 0, 0, 0, 1, th_v3(0, 1, 0), 0.5f, restitution, 1, &point);
}

/* Restitution: above the threshold the sphere leaves at e times the approach speed it hit
 * with (the fastest the solve saw); below it, it stops.
 * Either way it stays at the surface within the step (the bounce follows the substeps). */
static void test_solve_restitution(void** state)
{
    (void)state;
    const float speeds[] = { 5.0f, 0.5f };
    for (int i = 0; i < 2; i++) {
        fixture f;
        sphere_contact(&f, 1.0f, -speeds[i], 0, 0.5f);
        /* It hits with the speed of the first substep: the step's start plus g h. */
        double g = -tb_world_get_gravity(f.w).y, approach = speeds[i] + g * DT / SUBSTEPS;
        solver_step(&f, 1, 0, 2, SUBSTEPS, 1);
        double expected = approach > THRESHOLD ? 0.5 * approach : 0;
        th_assert_near(velocity_of(&f, 1).y, expected, 1e-5, 1e-5);
        th_assert_near(position_of(&f, 1).y, 1.0, 1e-3, 0);
        fixture_destroy(&f);
    }
}

/* Where a free fall from rest at speed v0 (y) ends after one step of substeps. */
static double fall(double y0, double v0, double g, uint32_t substeps, double* v_end)
{
    double y = y0, v = v0, h = DT / substeps;
    for (uint32_t k = 0; k < substeps; k++) {
        v -= g * h;
        y += v * h;
    }
    *v_end = v;
    return y;
}

/* Speculative contact 0.1 m apart: a slow fall does not reach the ground within the step and
 * is left alone; a fast one lands exactly on the surface within the step and stops there
 * (no bounce from a distance, e = 0). */
static void test_solve_speculative(void** state)
{
    (void)state;
    const float speeds[] = { 3.0f, 12.0f };
    for (int i = 0; i < 2; i++) {
        fixture f;
        sphere_contact(&f, 1.1f, -speeds[i], 0.1f, 0);
        double g = -tb_world_get_gravity(f.w).y, v;
        double y = fall(1.1, -speeds[i], g, SUBSTEPS, &v);
        solver_step(&f, 1, 0, 2, SUBSTEPS, 1);
        if (i == 0) {
            th_assert_near(velocity_of(&f, 1).y, v, 1e-4, 1e-5);
            th_assert_near(position_of(&f, 1).y, y, 1e-5, 0);
        } else {
            th_assert_near(position_of(&f, 1).y, 1.0, 1e-3, 0);
            assert_true(fabs(velocity_of(&f, 1).y) < 0.1);
        }
        fixture_destroy(&f);
    }
}

/* 10 cm of penetration: the soft contact pushes the sphere out, no faster than the push
 * speed, and the relax leaves its velocity at zero (no energy from the push-out), even with
 * restitution (it was not approaching). */
static void test_solve_push_out(void** state)
{
    (void)state;
    fixture f;
    sphere_contact(&f, 0.9f, 0, -0.1f, 0.8f);
    solver_step(&f, 1, 0, 2, SUBSTEPS, 1);
    th_assert_near(velocity_of(&f, 1).y, 0, 1e-5, 0);
    double rise = position_of(&f, 1).y - 0.9;
    print_message("  pushed out %.4f m of 0.1 in a step\n", rise);
    assert_true(rise > 0.01 && rise <= PUSH_SPEED * DT + 1e-6);
    fixture_destroy(&f);
}

/* A unit box sliding on the ground on its four bottom corners: kinetic friction takes
 * mu g dt off its speed in a step; a slower box sticks. */
static void test_solve_friction(void** state)
{
    (void)state;
    const float speeds[] = { 2.0f, 0.05f };
    for (int i = 0; i < 2; i++) {
        fixture f;
        tb_world* w = th_world_create(NULL);
        tb_body_def defs[2] = { ground_def(w), th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), th_v3(0, 1, 0)) };
        defs[1].linear_velocity = th_v3(speeds[i], 0, 0);
        fixture_init_defs(&f, w, defs, 2, 1, 4);
        tb_gpu_vec4 corners[4];
        for (int k = 0; k < 4; k++)
            corners[k] = (tb_gpu_vec4){ k & 1 ? 0.5f : -0.5f, 0.5f, k & 2 ? 0.5f : -0.5f, 0 };
        const float mu = 0.5f;
        set_contact(&f, 0, 0, 0, 1, th_v3(0, 1, 0), mu, 0, 4, corners);
        double g = -tb_world_get_gravity(w).y;
        solver_step(&f, 1, 0, 2, SUBSTEPS, 8);
        tb_vec3 v = velocity_of(&f, 1), spin = spin_of(&f, 1);
        double expected = speeds[i] > mu * g * DT ? speeds[i] - mu * g * DT : 0;
        th_assert_near(v.x, expected, 1e-3, 1e-3);
        th_assert_near(v.y, 0, 1e-3, 0);
        th_assert_near(v.z, 0, 1e-5, 0);
        th_assert_near(spin.x, 0, 1e-3, 0);
        th_assert_near(spin.z, 0, 2e-3, 0);
        double normal = 0;
        for (int k = 0; k < 4; k++) normal += impulse_of(&f, 0, 0, (uint32_t)k).w;
        th_assert_near(normal, mass_of(&f, 1) * g * DT, 0, 2e-3);
        fixture_destroy(&f);
    }
}

/* Three spheres stacked on the ground: two colours alternate over the chain; the contacts
 * carry 3, 2 and 1 times m g dt over the step. The same step run twice gives bit-identical results. */
static void stack_step(fixture* f, uint32_t iterations)
{
    for (uint32_t i = 1; i <= 3; i++) {
        th_assert_ok(tb_body_set_pose(f->w, f->ids[i], th_v3(0, (float)i, 0), th_q(0, 0, 0, 1)));
        th_assert_ok(tb_body_set_velocity(f->w, f->ids[i], th_v3(0, 0, 0), th_v3(0, 0, 0)));
    }
    th_assert_ok(tb_world_flush(f->w));
    for (uint32_t p = 0; p < 3; p++) {
        tb_gpu_vec4 point = { 0, 0.5f + (float)p, 0, 0 };
        set_contact(f, 1, p, p, p + 1, th_v3(0, 1, 0), 0.5f, 0, 1, &point);
    }
    solver_step(f, 3, 1, 4, SUBSTEPS, iterations);
}

static void test_solve_stack_deterministic(void** state)
{
    (void)state;
    fixture f;
    tb_world* w = th_world_create(NULL);
    tb_shape_id ball = th_sphere(w, 0.5f);
    tb_body_def defs[4] = { ground_def(w) };
    for (int i = 1; i <= 3; i++) defs[i] = th_dynamic_def(ball, th_v3(0, (float)i, 0));
    fixture_init_defs(&f, w, defs, 4, 1, 4);
    double g = -tb_world_get_gravity(w).y, mgdt = mass_of(&f, 1) * g * DT;
    stack_step(&f, 8);
    assert_int_equal(counters_of(&f)->solver.x, 2);
    /* Started cold, the soft contacts give a little in the first substeps while they take the
     * load (the spheres sink into them), so they carry the weight within a few per cent. */
    for (uint32_t p = 0; p < 3; p++) th_assert_near(impulse_of(&f, 1, p, 0).w, (3 - p) * mgdt, 0, 0.05);
    tb_vec3 first[4];
    tb_gpu_manifold manifolds[3];
    for (uint32_t i = 1; i <= 3; i++) {
        th_assert_near(velocity_of(&f, i).y, 0, 1e-2, 0);   /* still settling into the springs */
        first[i] = position_of(&f, i);
    }
    memcpy(manifolds, &manifolds_of(&f)[f.capacity], sizeof manifolds);
    stack_step(&f, 8);
    for (uint32_t i = 1; i <= 3; i++) {
        tb_vec3 x = position_of(&f, i);
        assert_memory_equal(&x, &first[i], sizeof x);
    }
    assert_memory_equal(manifolds, &manifolds_of(&f)[f.capacity], sizeof manifolds);
    fixture_destroy(&f);
}

/* A box held up by more static posts than there are colours: with every round recorded the
 * leftovers are solved by the tail, in order, and the box is held still. With fewer rounds
 * the step is abandoned and the box is left exactly as it was. */
static void test_solve_tail_and_abort(void** state)
{
    (void)state;
    enum { POSTS = 70 };
    const uint32_t rounds[] = { TB_MAX_COLOURS, 8 };
    for (int i = 0; i < 2; i++) {
        fixture f;
        tb_world* w = th_world_create(NULL);
        tb_shape_id post = th_sphere(w, 0.05f);
        tb_body_def defs[POSTS + 1];
        for (int k = 0; k < POSTS; k++)
            defs[k] = th_static_def(post, th_v3(-0.45f + 0.9f * (k % 10) / 9, 0.45f, -0.45f + 0.9f * (k / 10) / 6));
        defs[POSTS] = th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), th_v3(0, 1, 0));
        fixture_init_defs(&f, w, defs, POSTS + 1, POSTS, POSTS);
        for (uint32_t k = 0; k < POSTS; k++) {
            tb_gpu_vec4 point = { defs[k].position.x, 0.5f, defs[k].position.z, 0 };
            set_contact(&f, 0, k, k, POSTS, th_v3(0, 1, 0), 0.5f, 0, 1, &point);
        }
        double g = -tb_world_get_gravity(w).y;
        solver_step(&f, POSTS, 0, rounds[i], SUBSTEPS, 5);
        const tb_gpu_counters* c = counters_of(&f);
        tb_vec3 v = velocity_of(&f, POSTS);
        if (rounds[i] == TB_MAX_COLOURS) {
            assert_int_equal(c->state.x, 0);
            assert_int_equal(c->solver.y, POSTS - TB_MAX_COLOURS);
            double normal = 0;
            for (uint32_t k = 0; k < POSTS; k++) normal += impulse_of(&f, 0, k, 0).w;
            th_assert_near(normal, mass_of(&f, POSTS) * g * DT, 0, 1e-3);
            th_assert_near(v.y, 0, 1e-4, 0);
        } else {
            assert_int_equal(c->state.x, TB_ABORT_COLOURS);
            assert_true(v.x == 0 && v.y == 0 && v.z == 0);
            tb_vec3 x = position_of(&f, POSTS);
            assert_true(x.x == 0 && x.y == 1 && x.z == 0);
        }
        fixture_destroy(&f);
    }
}

/* A hub: 70 balls resting on one dynamic plate that rests on the ground. The plate is in 71
 * constraints, so 64 colours leave 7 to the tail; each ball is held by its one constraint
 * only, so every ball keeps still only if the tail solved its constraint. */
static void test_tail_holds_every_ball(void** state)
{
    (void)state;
    enum { BALLS = 70 };
    fixture f;
    tb_world* w = th_world_create(NULL);
    tb_shape_id ball = th_sphere(w, 0.05f);
    tb_body_def defs[BALLS + 2];
    defs[0] = th_static_def(th_box(w, th_v3(5, 0.5f, 5)), th_v3(0, -0.5f, 0));
    defs[1] = th_dynamic_def(th_box(w, th_v3(1, 0.05f, 1)), th_v3(0, 0.05f, 0));
    for (int k = 0; k < BALLS; k++)
        defs[k + 2] = th_dynamic_def(ball, th_v3(-0.9f + 1.8f * (k % 10) / 9, 0.15f,
                                                 -0.9f + 1.8f * (k / 10) / 6));
    fixture_init_defs(&f, w, defs, BALLS + 2, 1, BALLS + 1);
    tb_gpu_vec4 corners[4] = { { -1, 0, -1, 0 }, { 1, 0, -1, 0 }, { 1, 0, 1, 0 }, { -1, 0, 1, 0 } };
    set_contact(&f, 0, 0, 0, 1, th_v3(0, 1, 0), 0.5f, 0, 4, corners);
    for (uint32_t k = 0; k < BALLS; k++) {
        tb_gpu_vec4 point = { defs[k + 2].position.x, 0.1f, defs[k + 2].position.z, 0 };
        set_contact(&f, 0, k + 1, 1, k + 2, th_v3(0, 1, 0), 0.5f, 0, 1, &point);
    }
    solver_step(&f, BALLS + 1, 0, TB_MAX_COLOURS, SUBSTEPS, 1);
    const tb_gpu_counters* c = counters_of(&f);
    assert_int_equal(c->state.x, 0);
    assert_int_equal(c->solver.y, BALLS + 1 - TB_MAX_COLOURS);
    assert_int_equal(c->colouring.z, BALLS + 1 - TB_MAX_COLOURS);
    double g = -tb_world_get_gravity(w).y;
    for (uint32_t k = 0; k < BALLS; k++) {
        tb_vec3 v = velocity_of(&f, k + 2);
        if (fabs(v.y) > 0.05 * g * DT) fail_msg("ball %u falls at %g m/s", k, v.y);
    }
    fixture_destroy(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_graphs),
        cmocka_unit_test(test_lattice_graph),
        cmocka_unit_test(test_large_graph),
        cmocka_unit_test(test_too_few_rounds_aborts),
        cmocka_unit_test(test_star),
        cmocka_unit_test(test_static_bodies_do_not_block),
        cmocka_unit_test(test_chain),
        cmocka_unit_test(test_solve_resting_sphere),
        cmocka_unit_test(test_solve_restitution),
        cmocka_unit_test(test_solve_speculative),
        cmocka_unit_test(test_solve_push_out),
        cmocka_unit_test(test_solve_friction),
        cmocka_unit_test(test_solve_stack_deterministic),
        cmocka_unit_test(test_solve_tail_and_abort),
        cmocka_unit_test(test_tail_holds_every_ball),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
