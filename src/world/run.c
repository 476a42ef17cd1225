/* Running steps: this submission's uploads, the submission, and after it the growth of
 * whatever overflowed, after which the step is run again from its unchanged inputs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define MIN_COLOUR_ROUNDS 4u
#define ROUNDS_SPARE 2u      /* rounds recorded beyond the colours a step used */
#define SHRINK_SLACK 3u      /* re-record only when more rounds than this go unused */
#define BLOCK_SHRINK_AFTER 60u /* the block solver's colours: a few unused are given up only
                                  after this many runs of steps in a row used fewer */
/* The block solver's colouring rounds recorded beyond the `used` of the last step (a
 * step's rounds go up and down by a few); re-recorded fewer once twice this go unused. */
#define BLOCK_ROUNDS_ROOM(used) (4u + (used) / 4u)
#define MAX_REDO 16
/* Steps in one submission at the most: tb_world_step_n's n steps go in batches of this
 * many (a submission lists each step's command buffer). TUMBLE_STEPS_PER_SUBMIT=N (1 to
 * this) makes a world's batches smaller, so a test can see them in a few steps. */
#define MAX_STEPS_PER_SUBMIT 4096u

/* Per-body dispatches cover the slots in use; rows of groups keep x within the device limit. */
static void write_params(tb_world* w, float dt)
{
    uint32_t slots = w->store.slots;
    uint32_t groups = (slots + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE;
    uint32_t max_x = w->gpu.props.limits.maxComputeWorkGroupCount[0];
    uint32_t x = groups < max_x ? groups : max_x;
    tb_gpu_params* p = &w->params;
    p->gravity = (tb_gpu_vec4){ w->gravity.x, w->gravity.y, w->gravity.z, dt };
    uint32_t substeps = tb_world_substeps(w);
    p->counts = (tb_gpu_uvec4){ slots, w->shape_slots.used, substeps, w->body_set_version };
    /* Reuse is off when either bound is 0 (a distance below 0 never passes). */
    int reuse = w->reuse_distance > 0 && w->reuse_angle > 0;
    p->limits = (tb_gpu_vec4){ w->max_rotation_per_step, cosf(0.5f * w->reuse_angle), 0, 0 };
    p->body_dispatch = (tb_gpu_uvec4){ x, x ? (groups + x - 1) / x : 1, 1, 0 };
    p->capacity = (tb_gpu_uvec4){ w->sim.pair_capacity, w->sim.table_size - 1, w->colour_rounds,
                                  w->solver_iterations };
    p->contact = (tb_gpu_vec4){ w->contact_margin, w->restitution_threshold,
                                w->contact_push_speed, reuse ? w->reuse_distance : -1.0f };
    tb_solver_contact contact = { w->contact_hertz, w->contact_damping_ratio };
    p->soft = tb_solver_softness(&contact, dt / (float)substeps, 1.0);
    p->soft_static = tb_solver_softness(&contact, dt / (float)substeps, 2.0);
    const tb_block_settings* b = &w->block_settings;
    p->block = (tb_gpu_vec4){ b->stiffness, b->growth, b->max_stiffness, b->warm_share };
    p->block_more = (tb_gpu_vec4){ b->stabilisation, b->anchored_friction, (float)w->substeps,
                                   b->stiffness_carry };
    p->block_joints = (tb_gpu_vec4){ b->joint_max_stiffness, b->joint_warm_share,
                                     b->joint_stiffness_carry, 0 };
    const tb_buffer* pair = w->sim.pair;
    /* The manifold array of the next step's parity, then the other (last step's); after
     * each step of the submission the GPU swaps the two (tb_tail_swap). */
    const tb_buffer* next = tb_sim_manifolds_of_step(&w->sim, w->gpu_steps);
    const tb_buffer* last = tb_sim_manifolds_of_step(&w->sim, w->gpu_steps + 1);
    p->contact_arrays[0] = tb_gpu_addresses(next->address, last->address);
    p->contact_arrays[1] = tb_gpu_addresses(pair[TB_SIM_CONSTRAINTS].address,
                                            pair[TB_SIM_BLOCK_ENTRIES].address);
    p->joint_arrays = tb_gpu_addresses(w->joints.joints.address, w->joints.state.address);
    p->joint_info = tb_joints_params(&w->joints);
}

/* Record this submission's uploads (params, shapes, dirty bodies) and, with a mask, the
 * downloads of those body arrays that are stale. */
static tb_result record_transfer(tb_world* w, float dt, uint32_t mask, const void** landing)
{
    tb_result prepared = tb_joints_prepare(&w->joints);
    if (!prepared) prepared = tb_world_rank_joint_bodies(w);
    if (prepared) return prepared;
    VkDeviceSize shape_bytes = w->shapes_dirty ? w->shape_slots.used * sizeof(tb_gpu_shape) : 0;
    VkDeviceSize bytes = shape_bytes + tb_hull_table_upload_bytes(&w->narrowphase) +
                         tb_shapes_mesh_upload_bytes(w) +
                         tb_body_store_upload_bytes(&w->store) +
                         tb_joints_upload_bytes(&w->joints) +
                         tb_body_store_download_bytes(&w->store, mask) + 64;
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, bytes);
    if (r) return r;
    write_params(w, dt);
    vkCmdUpdateBuffer(t->cb, w->params_buffer.buffer, 0, sizeof w->params, &w->params);
    tb_plugins_record_upload(&w->plugins, t->cb);
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
    tb_hull_table_record_upload(&w->narrowphase, t);
    tb_shapes_record_mesh_uploads(w, t);
    tb_body_store_record_uploads(&w->store, t);
    tb_joints_record_uploads(&w->joints, t);
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
    if (!w->store.dirty_count && !w->shapes_dirty && !w->narrowphase.hulls.dirty &&
        !w->mesh_uploads && !w->joints.table_dirty && !w->joints.filter_dirty &&
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

/* The block solver's colouring rounds the step records (block_rounds, 0: as many as a
 * colouring of its colours may need, tb_block_record_colouring). */
static uint32_t block_rounds_recorded(const tb_world* w)
{
    return w->block_rounds ? w->block_rounds : tb_block_colouring_rounds(w->colour_rounds);
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
    if (!r && (c->state.x & TB_ABORT_EVENTS)) r = tb_events_grow(w, c->events.x);
    if (!r && (c->state.x & TB_ABORT_COLOURS)) {
        /* The block solver records the colours the step used (solver.x counts them all) and
         * one more, as a count that rose may rise again (a pile landing); fit_block_colours
         * gives it up once it has gone unused a while. */
        uint32_t rounds = w->colour_rounds + w->colour_rounds / 2;
        if (w->block_solver) rounds = (c->solver.x > w->colour_rounds ? c->solver.x
                                                                      : w->colour_rounds) + 1;
        w->colour_rounds = rounds < TB_MAX_COLOURS ? rounds : TB_MAX_COLOURS;
        w->block_colours_unused = 0;
    }
    if (!r && (c->state.x & TB_ABORT_ROUNDS)) {
        /* Twice as many as the step had (a round is one dispatch, a step run again a whole
         * step; a colouring of few colours may need more than tb_block_colouring_rounds
         * gives them). */
        uint32_t had = block_rounds_recorded(w);
        uint32_t most = tb_block_colouring_rounds(TB_MAX_COLOURS);
        uint32_t rounds = 2 * had;
        w->block_rounds = rounds < most ? rounds : most;
        if (had >= most) w->colour_rounds = TB_MAX_COLOURS;   /* the tail takes the rest */
    }
    if (!r && !(c->state.x & (TB_ABORT_PAIRS | TB_ABORT_COLOURS | TB_ABORT_EVENTS |
                              TB_ABORT_ROUNDS)))
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

/* The block solver's colours: each is a dispatch in every one of its many sweeps (where
 * the soft step's colours have batches), used or not. It records the colours the last step
 * used, none spare (a step that needs more is run again with them and one spare,
 * TB_ABORT_COLOURS): far fewer used at once, a few fewer only once they went unused for
 * BLOCK_SHRINK_AFTER runs in a row, so a pile whose count goes up and down by one is not
 * run again each time. */
static void fit_block_colours(tb_world* w, const tb_gpu_counters* c)
{
    uint32_t used = c->solver.x ? c->solver.x : 1;
    if (w->colour_rounds == TB_MAX_COLOURS && c->solver.y) return;   /* the tail is in use */
    if (used >= w->colour_rounds) {
        w->block_colours_unused = 0;
        return;
    }
    if (used + SHRINK_SLACK >= w->colour_rounds && ++w->block_colours_unused < BLOCK_SHRINK_AFTER)
        return;
    w->colour_rounds = used;
    w->block_colours_unused = 0;
    w->step_built = 0;
}

/* The block solver's colouring: its rounds are dispatches over every body, most of which
 * colour nothing once the bodies are coloured (2 c + 8 are recorded for c colours, which a
 * colouring seldom needs): record the rounds the last step used and a little room. A step
 * that needs more leaves bodies uncoloured and is run again with them all
 * (TB_ABORT_ROUNDS). With the tail recorded every round is kept: the bodies the rounds leave
 * go to the tail, solved one at a time. */
static void fit_block_rounds(tb_world* w, const tb_gpu_counters* c)
{
    uint32_t room = BLOCK_ROUNDS_ROOM(c->colouring.w), want = c->colouring.w + room;
    if (w->colour_rounds == TB_MAX_COLOURS) want = 0;
    else if (want + room > block_rounds_recorded(w)) return;
    if (want == w->block_rounds) return;
    w->block_rounds = want;
    w->step_built = 0;
}

/* The block solver's lanes a body for the bodies and contact points of the last step. */
static void fit_block_lanes(tb_world* w, const tb_gpu_counters* c)
{
    /* A CPU device (lavapipe) runs one lane a body whatever the sweep asks for
     * (glsl/block/block.glsl): the three sweeps are one kernel there. */
    if (!w->block_solver || w->gpu.is_cpu || w->block_lanes_fixed) return;
    uint32_t lanes = tb_block_lanes_for(w->body_slots.live, c->solver.w, w->block_lanes);
    if (lanes == w->block_lanes) return;
    w->block_lanes = lanes;
    w->step_built = 0;
}

/* The block solver's sweeps in one workgroup while the world is small, a dispatch a colour
 * once it is not (tb_block_fuses): bodies created or destroyed, or the tail taken up. */
static void fit_block_fused(tb_world* w)
{
    if (w->block_solver && w->block_fused != tb_step_fuses_sweeps(w)) w->step_built = 0;
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
    uint32_t completed = (uint32_t)(c->state.y - (uint32_t)w->gpu_steps);
    /* More than were submitted: the GPU's count and the host's disagree (a bug); taken as it
     * is, the caller's count of steps to go would wrap around. */
    if (completed > n)
        return tb_fail(&w->diag, TB_ERROR_DEVICE, "the GPU counts %u steps done of the %u "
                       "submitted (its count %u, the host's %llu)", completed, n, c->state.y,
                       (unsigned long long)w->gpu_steps);
    *done = completed;
    w->gpu_steps += completed;
    r = tb_events_deliver(w, c);
    if (!r) r = tb_world_guard_check(w, c);
    if (!r && c->state.x) r = grow_for(w, c);
    else if (!r) {
        if (w->block_solver) {
            fit_block_colours(w, c);
            fit_block_rounds(w, c);
        } else {
            fit_colour_rounds(w, c);
        }
        fit_block_lanes(w, c);
        fit_block_fused(w);
    }
    return r;
}

uint32_t tb_world_steps_per_submit(void)
{
    const char* v = getenv("TUMBLE_STEPS_PER_SUBMIT");
    long n = v ? strtol(v, NULL, 10) : 0;
    return n >= 1 && n <= (long)MAX_STEPS_PER_SUBMIT ? (uint32_t)n : MAX_STEPS_PER_SUBMIT;
}

tb_result tb_world_run(tb_world* w, float dt, uint32_t n)
{
    uint32_t left = n, redo = 0;
    while (left > 0) {
        uint32_t done = 0, batch = left < w->steps_per_submit ? left : w->steps_per_submit;
        tb_result r = run_steps(w, dt, batch, &done);
        w->steps += done;
        left -= done;
        if (r) return r;
        if (left == 0 || done == batch) continue;
        /* Step `done` + 1 of the batch overflowed: it runs again once its buffers grew. */
        w->steps_redone++;
        redo = done ? 1 : redo + 1;
        if (redo > MAX_REDO)
            return tb_fail(&w->diag, TB_ERROR_CAPACITY, "a step still overflowed after %d "
                           "buffer growths", MAX_REDO);
    }
    if (n) tb_graph_read_times(&w->graph, w->stage_ms, &w->gpu_ms);
    return TB_OK;
}
