/* The step as a graph of stages, built from the kernels and the parallel primitives.
 *
 * Order (DESIGN.md §1): bounds -> broadphase -> narrowphase -> colouring -> solver
 * data -> forces -> solver -> integration. The solver data (restitution) comes before the
 * step's velocities change, so a bounce reflects the speed the body hit with. Forces
 * (damping, the solver records) come after the pairs and colours are known, so a step that
 * overflows a buffer is abandoned before any body changes; gravity is applied in each of the
 * solver's substeps, so a resting body's weight is cancelled by its contact in the same
 * substep and it does not sink or jitter. Plugins' stages join at their points: pre-step
 * after step/begin, post-broadphase after the pairs, post-solve and post-step after
 * integration.
 */
#include "world/world.h"

tb_result tb_step_kernels_create(tb_world* w)
{
    tb_result r = tb_pipeline_create(&w->pipelines, "step/begin", TB_WORKGROUP_SIZE,
                                     &w->step_begin);
    if (!r) r = tb_pipeline_create(&w->pipelines, "step/end", 1, &w->step_end);
    return r;
}

void tb_step_kernels_destroy(tb_world* w)
{
    tb_pipeline_destroy(&w->pipelines, w->step_begin);
    tb_pipeline_destroy(&w->pipelines, w->step_end);
}

/* What the broadphase reads and writes of the step's buffers (broadphase.h). */
void tb_step_broadphase_io(tb_world* w)
{
    const tb_sim* sim = &w->sim;
    const tb_buffer* body = sim->body;
    w->bp.io = (tb_broadphase_io){
        .body_capacity = sim->body_capacity,
        .grid_key_bits = sim->table_bits + 1,
        .slots = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, grid) + 8),
        .large_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, grid) + 4),
        .pair_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, state) + 8),
        .abandoned = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, state)),
        .body_pair_counts = tb_gpu_ptr_of(&body[TB_SIM_BODY_PAIR_COUNT], 0),
        .scratch = tb_gpu_ptr_of(&body[TB_SIM_BODY_SCRATCH], 0),
        .grid_keys = tb_gpu_ptr_of(&body[TB_SIM_GRID_KEYS], 0),
        .grid_bodies = tb_gpu_ptr_of(&body[TB_SIM_GRID_BODIES], 0),
        .large_flags = tb_gpu_ptr_of(&body[TB_SIM_LARGE_FLAGS], 0),
        .large_list = tb_gpu_ptr_of(&body[TB_SIM_LARGE_LIST], 0),
        .aabb_min = tb_gpu_ptr_of(&w->store.gpu[TB_ARRAY_AABB_MIN], 0),
        .aabb_max = tb_gpu_ptr_of(&w->store.gpu[TB_ARRAY_AABB_MAX], 0),
    };
}

/* ---- the builder ----------------------------------------------------------------------- */

typedef struct builder {
    tb_world* w;
    VkBuffer counters;         /* bound at TB_BIND_COUNTERS; the indirect arguments */
    tb_pass_list list;
    tb_result r;
} builder;

static void end_stage(builder* b, const char* name)
{
    if (!b->r) b->r = tb_graph_append_passes(&b->w->graph, name, &b->list);
    tb_pass_list_free(&b->list);
}

/* A stage of one of the step's own kernels (step/begin, step/end): one workgroup. */
static void step_kernel(builder* b, VkPipeline pipeline, const char* name)
{
    tb_pass pass = tb_pass_with_args(pipeline, TB_DISPATCH_FIXED, b->counters, 0, 0, 0, 0);
    if (!b->r) b->r = tb_pass_list_add(&b->list, &b->w->diag, &pass);
    end_stage(b, name);
}

/* ---- stages ---------------------------------------------------------------------------- */

/* The world's broadphase (src/broadphase): the bodies' world boxes, the stage
 * broadphase/<name>, what it builds to search in; then broadphase/pairs, its search run by
 * the shared pair output; then, while the world has mesh or compound shapes, midphase/split,
 * the split of their pairs by triangle or by children (pair_split.h). */
static void broadphase_stage(builder* b)
{
    tb_world* w = b->w;
    tb_broadphase_search search = { .n = 0 };
    if (!b->r) b->r = tb_broadphase_record_world_aabb(&w->bp, &b->list, b->counters);
    end_stage(b, "broadphase/world_aabb");
    if (!b->r) b->r = w->broadphase->record(&w->bp, &b->list, &search);
    end_stage(b, w->broadphase->stage);
    if (!b->r) b->r = tb_broadphase_record_pair_output(&w->bp, &b->list, &search);
    end_stage(b, "broadphase/pairs");
    if (!w->compound_shapes && !w->mesh_shapes) return;
    tb_pair_split_io io = { &w->sim.counters, &w->sim.pair[TB_SIM_SPLIT], w->sim.pair_capacity,
                            w->broadphase->reads_last_pairs };
    if (!b->r) b->r = tb_pair_split_record(&w->split, &b->list, &io);
    end_stage(b, "midphase/split");
}

/* While the world has capsules, cylinders or cones, first every pair's kind, the round pairs
 * surely apart sorted out and the others listed grouped by kind (narrowphase/round_cull).
 * Then the manifolds of the pairs of spheres, boxes, planes and hulls (narrowphase/contacts:
 * those listed, or every pair), then the points of the touching hull pairs
 * (narrowphase/hull_points, see contacts.comp), a stage of its own so the stats tell the two
 * apart, recorded only while the world has hull shapes (box pairs never defer theirs); then
 * the round pairs' points (narrowphase/round_points); then the mesh pairs'
 * (narrowphase/mesh_points), while it has mesh shapes. */
static void narrowphase_stage(builder* b)
{
    tb_world* w = b->w;
    int listed = w->round_shapes != 0;
    if (listed) {
        if (!b->r) b->r = tb_narrowphase_record_round_cull(&w->narrowphase, &b->list,
                                                           b->counters);
        end_stage(b, "narrowphase/round_cull");
    }
    if (!b->r) b->r = tb_narrowphase_record_contacts(&w->narrowphase, &b->list, b->counters,
                                                     listed);
    end_stage(b, "narrowphase/contacts");
    if (w->hull_shapes) {
        if (!b->r) b->r = tb_narrowphase_record_hull_sat(&w->narrowphase, &b->list,
                                                         b->counters);
        end_stage(b, "narrowphase/hull_sat");
        if (!b->r) b->r = tb_narrowphase_record_hull_points(&w->narrowphase, &b->list,
                                                            b->counters, listed);
        end_stage(b, "narrowphase/hull_points");
    }
    if (listed) {
        if (!b->r) b->r = tb_narrowphase_record_round_points(&w->narrowphase, &b->list,
                                                             b->counters);
        end_stage(b, "narrowphase/round_points");
    }
    if (w->mesh_shapes) {
        if (!b->r) b->r = tb_narrowphase_record_mesh_points(&w->narrowphase, &b->list, b->counters);
        end_stage(b, "narrowphase/mesh_points");
    }
}

int tb_step_fuses_sweeps(const tb_world* w)
{
    return tb_block_fuses(w->body_slots.live, w->colour_rounds, w->gpu.is_cpu,
                          w->block_fused_forced);
}

/* The lanes a body of the block solver's sweeps: a world with joints sweeps with 8 (its
 * sweep with joints comes in that width only). */
static uint32_t block_sweep_lanes(const tb_world* w)
{
    return w->joint_passes ? 8 : w->block_lanes;
}

/* The block solver's contact lists and colouring of bodies, in place of the colouring of
 * constraints. */
static void block_colour_stage(builder* b)
{
    tb_world* w = b->w;
    tb_sim* sim = &w->sim;
    tb_block_lists lists = {
        .prims = &w->prims, .starts = tb_gpu_ptr_of(&sim->body[TB_SIM_BLOCK_START], 0),
        .slots = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, grid) + 8),
        .scratch = tb_gpu_ptr_of(&sim->body[TB_SIM_BODY_SCRATCH], 0),
        .tail_flags = tb_gpu_ptr_of(&sim->body[TB_SIM_BODY_CLAIM], 0),
        .tail = tb_gpu_ptr_of(&sim->pair[TB_SIM_COLOUR_WORK], 0),
        .tail_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, colouring) + 8),
        .body_capacity = sim->body_capacity,
        .joint_capacity = w->joints.slots.used ? w->joints.capacity : 0,
    };
    w->joint_passes = lists.joint_capacity;
    w->block_fused = tb_step_fuses_sweeps(w);
    /* Only the sweeps the step records are made: each takes long to compile on lavapipe. */
    if (!b->r && w->block_fused) b->r = tb_block_prepare_fused(&w->block, lists.joint_capacity > 0);
    if (!b->r && !w->block_fused) b->r = tb_block_prepare_lanes(&w->block, w->block_lanes);
    if (!b->r && lists.joint_capacity)
        b->r = tb_block_prepare_joints(&w->block, !w->block_fused);
    if (!b->r) b->r = tb_block_record_colouring(&w->block, &b->list, b->counters, &lists,
                                                w->colour_rounds, w->block_rounds,
                                                block_sweep_lanes(w));
    end_stage(b, "solver/colour");
}

/* The colouring; when it runs all TB_MAX_COLOURS rounds, also the list of the constraints
 * it may leave to the solver's tail. */
static void colour_stage(builder* b)
{
    tb_world* w = b->w;
    tb_sim* sim = &w->sim;
    if (w->block_solver) {
        block_colour_stage(b);
        return;
    }
    if (!b->r) b->r = tb_solver_record_colouring(&w->solver, &b->list, b->counters,
                                                 w->colour_rounds, TB_SOLVER_SUB_ROUNDS);
    tb_solver_tail tail = {
        .prims = &w->prims, .work = tb_gpu_ptr_of(&sim->pair[TB_SIM_COLOUR_WORK], 0),
        .pair_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, state) + 8),
        .list_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, colouring) + 8),
        .scratch = tb_gpu_ptr_of(&sim->pair[TB_SIM_TAIL_SCRATCH], 0),
        .pair_capacity = sim->pair_capacity,
    };
    if (!b->r && w->colour_rounds == TB_MAX_COLOURS)
        b->r = tb_solver_record_tail_list(&w->solver, &b->list, b->counters, &tail);
    end_stage(b, "solver/colour");
}

static void prepare_stage(builder* b)
{
    tb_world* w = b->w;
    if (!b->r) b->r = tb_solver_record_prepare(&w->solver, &b->list, b->counters);
    end_stage(b, "solver/prepare");
}

/* Every iteration visits the colours in order, one dispatch each
 * (constraints of a colour touch disjoint dynamic bodies: solved in parallel, no conflict). */
static void solve_stage(builder* b)
{
    tb_world* w = b->w;
    if (w->block_solver) {
        /* The free motion over the step, in the world's substeps as pieces: the velocities
         * and the pose the solve's inertia pulls towards. */
        if (!b->r) b->r = tb_solver_record_substep_bodies(&w->solver, &b->list, 2, w->substeps);
        if (!b->r) b->r = tb_block_record_solve(&w->block, &b->list, b->counters,
                                                w->colour_rounds, block_sweep_lanes(w),
                                                &w->block_settings, w->bouncy_shapes > 0,
                                                w->joint_passes, w->block_fused);
        end_stage(b, "solver/solve");
        return;
    }
    if (!b->r) b->r = tb_solver_record_solve(&w->solver, &b->list, b->counters,
                                             w->colour_rounds, w->substeps,
                                             w->solver_iterations);
    end_stage(b, "solver/solve");
}

static void apply_forces_stage(builder* b)
{
    if (!b->r) b->r = tb_solver_record_apply_forces(&b->w->solver, &b->list, b->counters);
    end_stage(b, "integrate/apply_forces");
}

static void integrate_stage(builder* b)
{
    if (!b->r) b->r = tb_solver_record_integrate(&b->w->solver, &b->list, b->counters);
    end_stage(b, "integrate/integrate");
}

/* The stages plugins add at `point` (src/plugin/stages.c). */
static void plugin_stages(builder* b, tb_plugin_point point)
{
    tb_plugins_io io = { b->counters };
    if (!b->r) b->r = tb_plugins_record(&b->w->plugins, point, &b->list, &io);
    tb_pass_list_free(&b->list);
}

/* The contact events plugins' callbacks get, once the solver's impulses are final and before
 * step/end makes this step's manifolds last step's (events.c). */
static void contact_event_stage(builder* b)
{
    if (!b->r) b->r = tb_events_record(b->w, &b->list);
    tb_pass_list_free(&b->list);
}

tb_result tb_step_build(tb_world* w)
{
    tb_graph_clear(&w->graph);
    tb_step_broadphase_io(w);
    builder b = { .w = w, .counters = w->sim.counters.buffer };
    step_kernel(&b, w->step_begin, "step/begin");
    plugin_stages(&b, TB_PLUGIN_PRE_STEP);
    broadphase_stage(&b);
    plugin_stages(&b, TB_PLUGIN_POST_BROADPHASE);
    narrowphase_stage(&b);
    colour_stage(&b);
    prepare_stage(&b);
    apply_forces_stage(&b);
    solve_stage(&b);
    contact_event_stage(&b);
    integrate_stage(&b);
    plugin_stages(&b, TB_PLUGIN_POST_SOLVE);
    plugin_stages(&b, TB_PLUGIN_POST_STEP);
    step_kernel(&b, w->step_end, "step/end");
    tb_pass_list_free(&b.list);
    w->graph.tail = (tb_tail_copy){ w->sim.counters.buffer, w->sim.readback.buffer,
                                    sizeof(tb_gpu_counters) };
    /* This step's manifolds are the next one's last step's where they lie. */
    w->graph.swap = (tb_tail_swap){ w->params_buffer.buffer, w->params_swap.buffer,
                                    offsetof(tb_gpu_params, contact_arrays) };
    w->step_built = !b.r;
    return b.r;
}
