/* The world: creation, the step, stats. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define DEFAULT_MAX_BODIES (1u << 24)
#define DEFAULT_MAX_SHAPES (1u << 20)
#define INITIAL_SHAPE_CAPACITY 16u
#define INITIAL_COLOUR_ROUNDS 16u
#define MIN_COLOUR_ROUNDS 4u
#define ROUNDS_SPARE 2u      /* rounds recorded beyond the colours a step used */
#define SHRINK_SLACK 3u      /* re-record only when more rounds than this go unused */
#define MAX_REDO 16

static uint16_t next_world_serial(void)
{
    static uint16_t serial;
    uint16_t s = __atomic_add_fetch(&serial, 1, __ATOMIC_RELAXED);
    return s ? s : __atomic_add_fetch(&serial, 1, __ATOMIC_RELAXED);
}

static tb_result check_world_def(tb_diag* diag, const tb_world_def* def)
{
    if (!def || def->internal_cookie != TB_DEF_COOKIE)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT,
                       "world def was not initialised with tb_default_world_def()");
    if (!tb_finite3(def->gravity))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "gravity must be finite");
    if (!isfinite(def->max_rotation_per_step) || def->max_rotation_per_step <= 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "max_rotation_per_step must be finite "
                       "and > 0, not %g", (double)def->max_rotation_per_step);
    if (def->substeps < 1 || def->substeps > 64)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "substeps must be in [1, 64], not %u",
                       def->substeps);
    if (!isfinite(def->contact_hertz) || def->contact_hertz < 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "contact_hertz must be finite and >= 0, "
                       "not %g", (double)def->contact_hertz);
    if (def->solver_iterations < 1 || def->solver_iterations > 1000)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "solver_iterations must be in [1, 1000], "
                       "not %u", def->solver_iterations);
    const struct { float v; const char* name; float hi; } ranges[] = {
        { def->contact_margin, "contact_margin", 1e30f },
        { def->restitution_threshold, "restitution_threshold", 1e30f },
        { def->contact_damping_ratio, "contact_damping_ratio", 1e30f },
        { def->contact_push_speed, "contact_push_speed", 1e30f },
    };
    for (size_t i = 0; i < sizeof ranges / sizeof ranges[0]; i++)
        if (!isfinite(ranges[i].v) || ranges[i].v < 0 || ranges[i].v > ranges[i].hi)
            return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s must be finite, >= 0%s, not %g",
                           ranges[i].name, ranges[i].hi == 1.0f ? " and <= 1" : "",
                           (double)ranges[i].v);
    return TB_OK;
}

static int env_flag(const char* name)
{
    const char* v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

static tb_result create_shape_buffer(tb_world* w, uint32_t capacity)
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

static tb_result create_gpu_objects(tb_world* w, const tb_world_def* def,
                                    const tb_gpu_options* extra)
{
    tb_gpu_options options = *extra;
    options.device = def->device;
    options.validation = def->validation || env_flag("TUMBLE_VALIDATION");
    tb_result r = tb_gpu_create(&w->gpu, &options, &w->diag);
    if (!r) r = tb_memory_init(&w->memory, &w->gpu);
    if (!r) r = tb_pipelines_init(&w->pipelines, &w->gpu, def->pipeline_cache_path);
    if (!r) r = tb_world_shader_dir_from_env(w);
    if (!r) r = tb_transfer_init(&w->transfer, &w->memory);
    if (!r) r = tb_graph_init(&w->graph, &w->gpu, &w->pipelines);
    if (!r) r = tb_buffer_create(&w->memory, sizeof(tb_gpu_params),
                                 VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, &w->params_buffer);
    if (r) return r;
    tb_pipelines_bind(&w->pipelines, TB_BIND_PARAMS, w->params_buffer.buffer);
    r = create_shape_buffer(w, INITIAL_SHAPE_CAPACITY);
    if (!r) r = tb_hull_table_init(w);
    if (!r) r = tb_body_store_init(&w->store, &w->memory, &w->pipelines, &w->transfer,
                                   def->initial_body_capacity);
    uint64_t pairs = def->initial_pair_capacity ? def->initial_pair_capacity
                                                : 4 * (uint64_t)(w->store.capacity ? w->store.capacity : 1);
    if (!r) r = tb_prims_init(&w->prims, &w->pipelines);
    if (!r) r = tb_sim_init(&w->sim, &w->memory, &w->pipelines, &w->prims, &w->transfer,
                            w->store.capacity, pairs);   /* clamped to the device's limit */
    if (!r) r = tb_solver_init(&w->solver, &w->pipelines);
    if (!r) r = tb_step_kernels_create(w);
    if (!r) r = tb_plugins_init(w);
    if (!r) r = tb_broadphase_shared_create(w);
    if (!r) r = w->broadphase->create(w);
    if (!r) r = w->broadphase->reserve(w, w->store.capacity);
    if (!r) r = tb_step_build(w);
    return r;
}

tb_result tb_world_create_with(const tb_world_def* def, const tb_gpu_options* extra,
                               tb_world** out)
{
    tb_diag early = { .log = def ? def->log : NULL, .log_user = def ? def->log_user : NULL };
    if (!out) return tb_fail(&early, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = NULL;
    tb_result r = check_world_def(&early, def);
    tb_broadphase broadphase = TB_BROADPHASE_GRID;
    if (!r) r = tb_broadphase_resolve(&early, def->broadphase, &broadphase);
    tb_world* w = r ? NULL : calloc(1, sizeof *w);
    if (!r && !w) r = tb_fail(&early, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    if (r) { tb_diag_set_create_error(early.message); return r; }
    w->diag = early;
    w->serial = next_world_serial();
    w->gravity = def->gravity;
    w->max_rotation_per_step = def->max_rotation_per_step;
    w->substeps = def->substeps;
    w->solver_iterations = def->solver_iterations;
    w->contact_margin = def->contact_margin;
    w->restitution_threshold = def->restitution_threshold;
    w->contact_hertz = def->contact_hertz;
    w->contact_damping_ratio = def->contact_damping_ratio;
    w->contact_push_speed = def->contact_push_speed;
    w->broadphase_kind = broadphase;
    w->broadphase = tb_broadphase_ops_of(broadphase);
    w->colour_rounds = INITIAL_COLOUR_ROUNDS;
    w->max_bodies = def->max_bodies ? def->max_bodies : DEFAULT_MAX_BODIES;
    w->max_shapes = def->max_shapes ? def->max_shapes : DEFAULT_MAX_SHAPES;
    r = create_gpu_objects(w, def, extra);
    if (r) {
        tb_diag_set_create_error(w->diag.message);
        tb_world_destroy(w);
        return r;
    }
    tb_diag_set_create_error("");
    *out = w;
    return TB_OK;
}

tb_result tb_world_create(const tb_world_def* def, tb_world** out)
{
    tb_gpu_options none = { 0 };
    return tb_world_create_with(def, &none, out);
}

void tb_world_destroy(tb_world* w)
{
    if (!w) return;
    if (w->gpu.device) vkDeviceWaitIdle(w->gpu.device);
    if (w->gpu.device) {
        tb_graph_destroy(&w->graph);
        tb_plugins_destroy(w);
        tb_step_kernels_destroy(w);
        if (w->broadphase) w->broadphase->destroy(w);
        tb_broadphase_shared_destroy(w);
        tb_solver_destroy(&w->solver);
        tb_sim_destroy(&w->sim);
        tb_prims_destroy(&w->prims);
        tb_body_store_destroy(&w->store);
        tb_buffer_destroy(&w->memory, &w->shape_buffer);
        tb_hull_table_destroy(w);
        tb_buffer_destroy(&w->memory, &w->params_buffer);
        tb_transfer_destroy(&w->transfer);
        tb_pipelines_destroy(&w->pipelines);
        tb_memory_destroy(&w->memory);
    }
    tb_gpu_destroy(&w->gpu);
    tb_slots_free(&w->body_slots);
    tb_slots_free(&w->shape_slots);
    free(w->bodies);
    for (uint32_t i = 0; i < w->shape_slots.used; i++) tb_shape_release_hull(&w->shapes[i]);
    free(w->shapes);
    free(w->gpu_shapes);
    free(w);
}

const char* tb_world_last_error(const tb_world* w)
{
    return w ? w->diag.message : tb_diag_create_error();
}

tb_result tb_world_set_gravity(tb_world* w, tb_vec3 gravity)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!tb_finite3(gravity)) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "gravity must be finite");
    w->gravity = gravity;
    return TB_OK;
}

tb_vec3 tb_world_get_gravity(const tb_world* w)
{
    return w ? w->gravity : (tb_vec3){ 0, 0, 0 };
}

tb_result tb_world_reserve_bodies(tb_world* w, uint32_t slots)
{
    int grew = 0;
    tb_result r = tb_body_store_reserve(&w->store, &w->transfer, slots, &grew);
    if (!r && grew) r = tb_sim_reserve_bodies(&w->sim, &w->transfer, w->store.capacity);
    if (!r && grew) r = w->broadphase->reserve(w, w->store.capacity);
    if (grew) {
        w->step_built = 0;
        w->buffer_generation++;
    }
    return r;
}

/* The soft contact of a substep h (Box2D v3's soft step): a damped spring of contact_hertz,
 * capped at a quarter of the substep rate so it stays stable (at half the rate a 10-box
 * column already rocks itself over); 0 takes the cap (twice as stiff against static
 * bodies, which cannot give way), written as the bias rate, mass
 * scale and impulse scale the solve uses (see glsl/solver/contact.glsl). */
tb_gpu_vec4 tb_contact_softness(const tb_world* w, float h, double scale)
{
    if (!(h > 0)) return (tb_gpu_vec4){ 0, 1, 0, 0 };
    double cap = 0.25 / h;
    double hertz = scale * (w->contact_hertz > 0 && w->contact_hertz < cap ? w->contact_hertz : cap);
    double omega = 2.0 * 3.14159265358979323846 * hertz, zeta = w->contact_damping_ratio;
    double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
    return (tb_gpu_vec4){ (float)(omega / a1), (float)(a2 * a3), (float)a3, h };
}

/* Per-body dispatches cover the slots in use; rows of groups keep x within the device limit. */
static void write_params(tb_world* w, float dt)
{
    uint32_t slots = w->store.slots;
    uint32_t groups = (slots + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE;
    uint32_t max_x = w->gpu.props.limits.maxComputeWorkGroupCount[0];
    uint32_t x = groups < max_x ? groups : max_x;
    tb_gpu_params* p = &w->params;
    p->gravity = (tb_gpu_vec4){ w->gravity.x, w->gravity.y, w->gravity.z, dt };
    p->counts = (tb_gpu_uvec4){ slots, w->shape_slots.used, w->substeps, w->body_set_version };
    p->limits = (tb_gpu_vec4){ w->max_rotation_per_step, 0, 0, 0 };
    p->body_dispatch = (tb_gpu_uvec4){ x, x ? (groups + x - 1) / x : 1, 1, 0 };
    p->capacity = (tb_gpu_uvec4){ w->sim.pair_capacity, w->sim.table_size - 1, w->colour_rounds,
                                  w->solver_iterations };
    p->contact = (tb_gpu_vec4){ w->contact_margin, w->restitution_threshold,
                                w->contact_push_speed, 0 };
    p->soft = tb_contact_softness(w, dt / (float)w->substeps, 1.0);
    p->soft_static = tb_contact_softness(w, dt / (float)w->substeps, 2.0);
    const tb_buffer* pair = w->sim.pair;
    p->contact_arrays[0] = tb_gpu_addresses(pair[TB_SIM_MANIFOLDS].address,
                                            pair[TB_SIM_PREV_MANIFOLDS].address);
    p->contact_arrays[1] = tb_gpu_addresses(pair[TB_SIM_CONSTRAINTS].address, 0);
}

tb_result tb_world_prepare_shapes(tb_world* w)
{
    tb_result r = tb_hull_table_prepare(w);
    if (r || w->shape_slots.used <= w->shape_buffer_capacity) return r;
    uint32_t cap = w->shape_buffer_capacity * 2;
    while (cap < w->shape_slots.used) cap *= 2;
    return create_shape_buffer(w, cap);
}

/* Record this submission's uploads (params, shapes, dirty bodies) and, with a mask, the
 * downloads of those body arrays that are stale. */
static tb_result record_transfer(tb_world* w, float dt, uint32_t mask, const void** landing)
{
    VkDeviceSize shape_bytes = w->shapes_dirty ? w->shape_slots.used * sizeof(tb_gpu_shape) : 0;
    VkDeviceSize bytes = shape_bytes + tb_hull_table_upload_bytes(w) +
                         tb_body_store_upload_bytes(&w->store) +
                         tb_body_store_download_bytes(&w->store, mask) + 64;
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, bytes);
    if (r) return r;
    write_params(w, dt);
    vkCmdUpdateBuffer(t->cb, w->params_buffer.buffer, 0, sizeof w->params, &w->params);
    tb_plugins_record_upload(w, t->cb);
    uint32_t no_abort = 0;   /* a step abandoned before is run again from here */
    vkCmdUpdateBuffer(t->cb, w->sim.counters.buffer, offsetof(tb_gpu_counters, state), 4, &no_abort);
    uint32_t no_events[2] = { 0, 0 };   /* the last submission's were delivered */
    vkCmdUpdateBuffer(t->cb, w->sim.counters.buffer, offsetof(tb_gpu_counters, events),
                      sizeof no_events, no_events);
    if (shape_bytes) {
        void* dst = tb_transfer_upload(t, w->shape_buffer.buffer, 0, shape_bytes);
        if (dst) memcpy(dst, w->gpu_shapes, shape_bytes);
        w->shapes_dirty = 0;
    }
    tb_hull_table_record_upload(w, t);
    tb_body_store_record_uploads(&w->store, t);
    if (mask) {
        tb_transfer_barrier(t);
        tb_body_store_record_downloads(&w->store, t, mask, landing);
    }
    return tb_transfer_end(t);
}

tb_result tb_world_fetch(tb_world* w, uint32_t mask)
{
    if (!(mask & ~w->store.fresh)) return TB_OK;
    const void* landing[TB_ARRAY_COUNT] = { 0 };
    tb_result r = tb_world_prepare_shapes(w);
    if (!r) r = record_transfer(w, 0.0f, mask, landing);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &w->transfer.cb, 1);
    if (!r) tb_body_store_take_downloads(&w->store, mask, landing);
    return r;
}

tb_result tb_world_flush(tb_world* w)
{
    if (!w->store.dirty_count && !w->shapes_dirty && !w->hulls.dirty &&
        w->shape_slots.used <= w->shape_buffer_capacity)
        return TB_OK;
    tb_result r = tb_world_prepare_shapes(w);
    if (!r) r = record_transfer(w, 0.0f, 0, NULL);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &w->transfer.cb, 1);
    return r;
}

static tb_result submit_steps(tb_world* w, uint32_t n)
{
    VkCommandBuffer* cbs = malloc(((size_t)n + 1) * sizeof *cbs);
    if (!cbs) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    cbs[0] = w->transfer.cb;
    for (uint32_t i = 1; i <= n; i++) cbs[i] = w->graph.cb;
    tb_result r = tb_gpu_submit_wait(&w->gpu, cbs, n + 1);
    free(cbs);
    return r;
}

/* A step the GPU abandoned: grow what overflowed so the step fits when run again. Pairs get
 * a quarter more than needed (at least a quarter more than before), within the device. */
static tb_result grow_for(tb_world* w, const tb_gpu_counters* c)
{
    tb_result r = TB_OK;
    if (c->state.x & TB_ABORT_PAIRS) {
        uint64_t limit = tb_sim_pair_limit(&w->sim), need = c->state.w;
        if (need > limit)
            return tb_fail(&w->diag, TB_ERROR_CAPACITY, "a step found %llu contact pairs, more "
                           "than the %llu this device's buffers can hold",
                           (unsigned long long)need, (unsigned long long)limit);
        uint64_t want = need + need / 4 + 64;
        uint64_t grown = (uint64_t)w->sim.pair_capacity + w->sim.pair_capacity / 4;
        if (want < grown) want = grown;
        if (want > limit) want = limit;
        r = tb_sim_reserve_pairs(&w->sim, &w->transfer, (uint32_t)want);
    }
    if (!r && (c->state.x & TB_ABORT_EVENTS)) r = tb_plugins_grow_events(w, c->events.x);
    if (!r && (c->state.x & TB_ABORT_COLOURS)) {
        uint32_t rounds = w->colour_rounds + w->colour_rounds / 2;
        w->colour_rounds = rounds < TB_MAX_COLOURS ? rounds : TB_MAX_COLOURS;
    }
    if (!r && !(c->state.x & (TB_ABORT_PAIRS | TB_ABORT_COLOURS | TB_ABORT_EVENTS)))
        r = tb_fail(&w->diag, TB_ERROR_DEVICE, "the GPU abandoned a step for an unknown reason "
                    "(flags %#x)", c->state.x);
    w->step_built = 0;
    w->buffer_generation++;
    return r;
}

/* Every recorded colouring round costs dispatches in the colouring and in each solver
 * iteration, used or not: when a step used far fewer colours, record fewer rounds (with a
 * little room; a step that needs more is run again with more). */
static void fit_colour_rounds(tb_world* w, const tb_gpu_counters* c)
{
    uint32_t used = c->solver.x;
    if (w->colour_rounds == TB_MAX_COLOURS && c->solver.y) return;   /* the tail is in use */
    uint32_t rounds = used + ROUNDS_SPARE > MIN_COLOUR_ROUNDS ? used + ROUNDS_SPARE
                                                              : MIN_COLOUR_ROUNDS;
    if (used + SHRINK_SLACK < w->colour_rounds && rounds < w->colour_rounds) {
        w->colour_rounds = rounds;
        w->step_built = 0;
    }
}

/* Submit up to n steps; returns how many the GPU completed (fewer when one overflowed). */
static tb_result run_steps(tb_world* w, float dt, uint32_t n, uint32_t* done)
{
    tb_world_reload_shaders(w);
    tb_result r = tb_world_prepare_shapes(w);
    if (!r && !w->step_built) r = tb_step_build(w);
    if (!r) r = tb_graph_prepare(&w->graph, w->params_buffer.buffer);
    if (!r) r = record_transfer(w, dt, 0, NULL);
    if (!r) r = submit_steps(w, n);
    if (r) return r;
    tb_body_store_stepped(&w->store);
    w->submits++;
    const tb_gpu_counters* c = tb_sim_counters(&w->sim);
    *done = (uint32_t)(c->state.y - (uint32_t)w->gpu_steps);
    w->gpu_steps += *done;
    r = tb_plugins_deliver_events(w, c);
    if (!r && c->state.x) r = grow_for(w, c);
    else if (!r) fit_colour_rounds(w, c);
    return r;
}

tb_result tb_world_step_n(tb_world* w, float dt, uint32_t n)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!isfinite(dt) || dt <= 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "dt must be finite and > 0, not %g",
                       (double)dt);
    uint32_t left = n, redo = 0;
    while (left > 0) {
        uint32_t done = 0;
        tb_result r = run_steps(w, dt, left, &done);
        w->steps += done;
        left -= done;
        if (r) return r;
        if (left == 0) break;
        w->steps_redone++;
        if (++redo > MAX_REDO)
            return tb_fail(&w->diag, TB_ERROR_CAPACITY, "a step still overflowed after %d "
                           "buffer growths", MAX_REDO);
    }
    if (n) tb_graph_read_times(&w->graph, w->stage_ms, &w->gpu_ms);
    return TB_OK;
}

tb_result tb_world_step(tb_world* w, float dt)
{
    return tb_world_step_n(w, dt, 1);
}

tb_result tb_world_device_info(const tb_world* w, tb_device_info* out)
{
    if (!w || !out) return TB_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", w->gpu.props.deviceName);
    snprintf(out->driver, sizeof out->driver, "%.*s", (int)sizeof out->driver - 1, w->gpu.driver);
    out->vendor_id = w->gpu.props.vendorID;
    out->device_id = w->gpu.props.deviceID;
    out->api_version = w->gpu.props.apiVersion;
    out->subgroup_size = w->gpu.subgroup_size;
    out->is_cpu = w->gpu.is_cpu;
    return TB_OK;
}

tb_result tb_world_get_stats(const tb_world* w, tb_world_stats* out)
{
    if (!w || !out) return TB_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    out->body_count = w->body_slots.live;
    out->body_capacity = w->store.capacity;
    out->shape_count = w->shape_slots.live;
    out->steps = w->steps;
    out->submits = w->submits;
    out->records = w->graph.records;
    out->buffer_growths = w->store.growths;
    out->validation_messages = w->diag.validation_messages;
    out->gpu_ms = w->gpu_ms;
    const tb_gpu_counters* c = tb_sim_counters(&w->sim);
    out->pair_count = c->state.z;
    out->pair_capacity = w->sim.pair_capacity;
    out->contact_count = c->solver.w;
    out->colour_count = c->solver.x;
    out->batch_count = c->solver.z;
    out->colour_rounds = w->colour_rounds;
    out->steps_redone = w->steps_redone;
    out->broadphase = w->broadphase->name;
    out->buffer_growths += w->sim.growths;
    out->stage_count = w->graph.count;
    for (uint32_t i = 0; i < w->graph.count; i++) {
        out->stages[i].name = w->graph.stages[i].name;
        out->stages[i].ms = w->stage_ms[i];
    }
    return TB_OK;
}
