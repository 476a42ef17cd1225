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

typedef struct kernel_def { const char* shader; uint32_t workgroup; } kernel_def;

static const kernel_def kernel_defs[TB_KERNEL_COUNT] = {
    [TB_KERNEL_STEP_BEGIN] = { "step/begin", TB_WORKGROUP_SIZE },
    [TB_KERNEL_WORLD_AABB] = { "broadphase/world_aabb", TB_WORKGROUP_SIZE },
    [TB_KERNEL_CONTACTS] = { "narrowphase/contacts", TB_WORKGROUP_SIZE },
    [TB_KERNEL_HULL_POINTS] = { "narrowphase/hull_points", TB_WORKGROUP_SIZE },
    [TB_KERNEL_KEEP_CONTACTS] = { "narrowphase/keep", TB_WORKGROUP_SIZE },
    [TB_KERNEL_APPLY_FORCES] = { "integrate/apply_forces", TB_WORKGROUP_SIZE },
    [TB_KERNEL_INTEGRATE] = { "integrate/integrate", TB_WORKGROUP_SIZE },
    [TB_KERNEL_STEP_END] = { "step/end", 1 },
};

tb_result tb_step_kernels_create(tb_world* w)
{
    for (int k = 0; k < TB_KERNEL_COUNT; k++) {
        tb_result r = tb_pipeline_create(&w->pipelines, kernel_defs[k].shader,
                                         kernel_defs[k].workgroup, &w->kernels[k]);
        if (r) return r;
    }
    return TB_OK;
}

void tb_step_kernels_destroy(tb_world* w)
{
    for (int k = 0; k < TB_KERNEL_COUNT; k++)
        tb_pipeline_destroy(&w->pipelines, w->kernels[k]);
}

/* ---- pass helpers ---------------------------------------------------------------------- */

typedef struct builder {
    tb_world* w;
    tb_pass_list list;
    tb_result r;
} builder;

static void add(builder* b, tb_kernel k, tb_dispatch_rule rule, VkDeviceSize indirect_offset,
                uint32_t colour, uint32_t iteration, uint32_t mode)
{
    if (b->r) return;
    tb_pass pass = tb_pass_with_args(b->w->kernels[k], rule, b->w->sim.counters.buffer,
                                     indirect_offset, colour, iteration, mode);
    b->r = tb_pass_list_add(&b->list, &b->w->diag, &pass);
}

static void per_body(builder* b, tb_kernel k, uint32_t mode)
{
    add(b, k, TB_DISPATCH_PER_BODY, 0, 0, 0, mode);
}

static void per_pair(builder* b, tb_kernel k, uint32_t colour)
{
    add(b, k, TB_DISPATCH_INDIRECT, TB_COUNTERS_PAIR_DISPATCH_OFFSET, colour, 0, 0);
}

static void once(builder* b, tb_kernel k)
{
    add(b, k, TB_DISPATCH_FIXED, 0, 0, 0, 0);
}

static void end_stage(builder* b, const char* name)
{
    if (!b->r) b->r = tb_graph_append_passes(&b->w->graph, name, &b->list);
    tb_pass_list_free(&b->list);
}

/* ---- stages ---------------------------------------------------------------------------- */

/* The world's broadphase (src/broadphase): the stage broadphase/<name>, what it builds to
 * search in; then broadphase/pairs, its search run by the shared pair output. */
static void broadphase_stage(builder* b)
{
    tb_world* w = b->w;
    tb_broadphase_search search = { .n = 0 };
    if (!b->r) b->r = w->broadphase->record(w, &b->list, &search);
    end_stage(b, w->broadphase->stage);
    if (!b->r) b->r = tb_broadphase_record_pair_output(w, &b->list, &search);
    end_stage(b, "broadphase/pairs");
}

/* Manifolds of every pair, then the points of the touching hull pairs (see contacts.comp),
 * a pass recorded only while the world has hull shapes (box pairs never defer theirs). */
static void narrowphase_stage(builder* b)
{
    per_pair(b, TB_KERNEL_CONTACTS, 0);
    if (b->w->hull_shapes) per_pair(b, TB_KERNEL_HULL_POINTS, 0);
    end_stage(b, "narrowphase/contacts");
}

/* The colouring; when it runs all TB_MAX_COLOURS rounds, also the list of the constraints
 * it may leave to the solver's tail. */
static void colour_stage(builder* b)
{
    tb_world* w = b->w;
    tb_sim* sim = &w->sim;
    if (!b->r) b->r = tb_solver_record_colouring(&w->solver, &b->list, sim->counters.buffer,
                                                 w->colour_rounds, TB_SOLVER_SUB_ROUNDS);
    tb_solver_tail tail = {
        .prims = &w->prims, .work = tb_gpu_ptr_of(&sim->pair[TB_SIM_COLOUR_WORK], 0),
        .pair_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, state) + 8),
        .list_count = tb_gpu_ptr_of(&sim->counters, offsetof(tb_gpu_counters, colouring) + 8),
        .scratch = tb_gpu_ptr_of(&sim->pair[TB_SIM_TAIL_SCRATCH], 0),
        .pair_capacity = sim->pair_capacity,
    };
    if (!b->r && w->colour_rounds == TB_MAX_COLOURS)
        b->r = tb_solver_record_tail_list(&w->solver, &b->list, sim->counters.buffer, &tail);
    end_stage(b, "solver/colour");
}

static void prepare_stage(builder* b)
{
    tb_world* w = b->w;
    if (!b->r) b->r = tb_solver_record_prepare(&w->solver, &b->list, w->sim.counters.buffer);
    end_stage(b, "solver/prepare");
}

/* Every iteration visits the colours in order, one dispatch each
 * (constraints of a colour touch disjoint dynamic bodies: solved in parallel, no conflict). */
static void solve_stage(builder* b)
{
    tb_world* w = b->w;
    if (!b->r) b->r = tb_solver_record_solve(&w->solver, &b->list, w->sim.counters.buffer,
                                             w->colour_rounds, w->substeps,
                                             w->solver_iterations);
    end_stage(b, "solver/solve");
}

/* The stages plugins add at `point` (src/api/plugin_stages.c). */
static void plugin_stages(builder* b, tb_plugin_point point)
{
    if (!b->r) b->r = tb_plugins_record(b->w, point, &b->list);
    tb_pass_list_free(&b->list);
}

/* The contact events plugins' callbacks get, once the solver's impulses are final and before
 * narrowphase/keep makes this step's manifolds last step's (src/api/contact_events.c). */
static void contact_event_stage(builder* b)
{
    if (!b->r) b->r = tb_plugins_record_events(b->w, &b->list);
    tb_pass_list_free(&b->list);
}

static void single(builder* b, tb_kernel k, tb_dispatch_rule rule, const char* name)
{
    if (rule == TB_DISPATCH_PER_BODY) per_body(b, k, 0);
    else if (rule == TB_DISPATCH_FIXED) once(b, k);
    else per_pair(b, k, 0);
    end_stage(b, name);
}

tb_result tb_step_build(tb_world* w)
{
    tb_graph_clear(&w->graph);
    builder b = { .w = w };
    single(&b, TB_KERNEL_STEP_BEGIN, TB_DISPATCH_FIXED, "step/begin");
    plugin_stages(&b, TB_PLUGIN_PRE_STEP);
    single(&b, TB_KERNEL_WORLD_AABB, TB_DISPATCH_PER_BODY, "broadphase/world_aabb");
    broadphase_stage(&b);
    plugin_stages(&b, TB_PLUGIN_POST_BROADPHASE);
    narrowphase_stage(&b);
    colour_stage(&b);
    prepare_stage(&b);
    single(&b, TB_KERNEL_APPLY_FORCES, TB_DISPATCH_PER_BODY, "integrate/apply_forces");
    solve_stage(&b);
    contact_event_stage(&b);
    single(&b, TB_KERNEL_KEEP_CONTACTS, TB_DISPATCH_INDIRECT, "narrowphase/keep");
    single(&b, TB_KERNEL_INTEGRATE, TB_DISPATCH_PER_BODY, "integrate/integrate");
    plugin_stages(&b, TB_PLUGIN_POST_SOLVE);
    plugin_stages(&b, TB_PLUGIN_POST_STEP);
    single(&b, TB_KERNEL_STEP_END, TB_DISPATCH_FIXED, "step/end");
    tb_pass_list_free(&b.list);
    w->graph.tail = (tb_tail_copy){ w->sim.counters.buffer, w->sim.readback.buffer,
                                    sizeof(tb_gpu_counters) };
    w->step_built = !b.r;
    return b.r;
}
