/* Pipelines and pass lists of the block solver. */
#include "solver/block.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

tb_block_settings tb_block_default_settings(void)
{
    tb_block_settings s = { 30, 1.0f, 300.0f, 1000.0f, 0.95f, 0.97f, 0.99f, 1.0f, 1.2f,
                            1000.0f, 0.475f, 0.9f, 15 };
    const char* env = getenv("TUMBLE_BLOCK");
    if (env) sscanf(env, "%u,%f,%f,%f,%f,%f,%f,%f,%f", &s.iterations, &s.stiffness, &s.growth,
                    &s.max_stiffness, &s.warm_share, &s.stabilisation, &s.stiffness_carry,
                    &s.anchored_friction, &s.over_relaxation);
    const char* joints = getenv("TUMBLE_BLOCK_JOINTS");
    if (joints) sscanf(joints, "%f,%f,%f,%u", &s.joint_max_stiffness, &s.joint_warm_share,
                       &s.joint_stiffness_carry, &s.joint_holds);
    return s;
}

static const tb_pipeline_slot kernels[] = {
    { "block/reset", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, reset) },
    { "block/count", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, count) },
    { "block/fill", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, fill) },
    { "block/sort", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, sort) },
    { "block/colour", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, colour) },
    { "block/list", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, list) },
    { "block/finish", TB_MAX_COLOURS, offsetof(tb_block_solver, finish) },
    { "block/start", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, start) },
    { "block/guess", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, guess) },
    { "block/end", TB_WORKGROUP_SIZE, offsetof(tb_block_solver, end) },
    { "block/bounce", TB_SOLVER_WORKGROUP_SIZE, offsetof(tb_block_solver, bounce) },
};
#define KERNEL_COUNT (sizeof kernels / sizeof kernels[0])

/* The sweeps with 8, 16 and 32 lanes a body, made when a world first wants them
 * (tb_block_prepare_lanes, as its step is first recorded): block/solve is among the
 * longest kernels to compile (82 ms of a world's 0.49 s of compiles on lavapipe), and a
 * world that never steps never needs it. */
static const tb_pipeline_slot wide_kernels[] = {
    { "block/solve", TB_SOLVER_WORKGROUP_SIZE, offsetof(tb_block_solver, solve) },
    { "block/solve_16", TB_SOLVER_WORKGROUP_SIZE, offsetof(tb_block_solver, solve_16) },
    { "block/solve_32", TB_SOLVER_WORKGROUP_SIZE, offsetof(tb_block_solver, solve_32) },
};
#define WIDE_KERNEL_COUNT (sizeof wide_kernels / sizeof wide_kernels[0])

tb_result tb_block_init(tb_block_solver* s, tb_pipelines* pipelines)
{
    memset(s, 0, sizeof *s);
    tb_result r = tb_pipeline_create_slots(pipelines, kernels, KERNEL_COUNT, s);
    /* The tail's workgroup shares each body on a GPU. A CPU device runs a workgroup's
     * invocations on one core, where each lane and barrier costs: lavapipe keeps the
     * sweep's own tail, one lane a body (500 spheres in one place: 1.8 s a step; 8.1 with
     * 256 invocations a body, 2.5 with one). TUMBLE_WIDE_TAIL=1 takes the GPU's kernel
     * there too (the tests run it so). */
    const char* wide = getenv("TUMBLE_WIDE_TAIL");
    if (!pipelines->gpu->is_cpu || (wide && strcmp(wide, "1") == 0))
        r = r ? r : tb_pipeline_create(pipelines, "block/solve_tail", pipelines->gpu->is_cpu
                                       ? TB_SOLVER_WORKGROUP_SIZE : TB_BLOCK_TAIL_WORKGROUP_SIZE,
                                       &s->solve_tail);
    if (!r) s->pipelines = pipelines;
    return r;
}

void tb_block_destroy(tb_block_solver* s)
{
    if (!s->pipelines) return;
    tb_pipeline_destroy_slots(s->pipelines, kernels, KERNEL_COUNT, s);
    tb_pipeline_destroy_slots(s->pipelines, wide_kernels, WIDE_KERNEL_COUNT, s);
    if (s->joint_count) tb_pipeline_destroy(s->pipelines, s->joint_count);
    if (s->joint_fill) tb_pipeline_destroy(s->pipelines, s->joint_fill);
    if (s->joint_start) tb_pipeline_destroy(s->pipelines, s->joint_start);
    if (s->solve_joints) tb_pipeline_destroy(s->pipelines, s->solve_joints);
    if (s->solve_tail_joints) tb_pipeline_destroy(s->pipelines, s->solve_tail_joints);
    if (s->solve_tail) tb_pipeline_destroy(s->pipelines, s->solve_tail);
    if (s->solve_fused) tb_pipeline_destroy(s->pipelines, s->solve_fused);
    if (s->solve_fused_joints) tb_pipeline_destroy(s->pipelines, s->solve_fused_joints);
    memset(s, 0, sizeof *s);
}

/* Bodies from which a world keeps 8 lanes a body whatever its points (below it, 16 or 32 were
 * faster on every scene of the H100 run in tb_block_lanes_for's note); and the list entries
 * a body (two per contact point) from which 16 and 32 lanes pay. */
#define FEW_BODIES 8192.0
#define ENTRIES_FOR_16 4.0
#define ENTRIES_FOR_32 16.0

/* The lanes for these counts, with the bounds made `slack` times harder to pass for more
 * lanes (fewer bodies, more entries a body). */
static uint32_t lanes_at(double bodies, double entries, double slack)
{
    if (bodies <= 0.0 || bodies * slack >= FEW_BODIES) return 8;
    if (entries >= ENTRIES_FOR_32 * slack * bodies) return 32;
    if (entries >= ENTRIES_FOR_16 * slack * bodies) return 16;
    return 8;
}

tb_result tb_block_prepare_lanes(tb_block_solver* s, uint32_t lanes)
{
    tb_result r = TB_OK;
    if (!s->solve) r = tb_pipeline_create_slots(s->pipelines, wide_kernels, 1, s);
    if (!r && lanes >= 16 && !s->solve_16)
        r = tb_pipeline_create_slots(s->pipelines, wide_kernels + 1, 1, s);
    if (!r && lanes >= 32 && !s->solve_32)
        r = tb_pipeline_create_slots(s->pipelines, wide_kernels + 2, 1, s);
    return r;
}

uint32_t tb_block_lanes_for(uint32_t bodies, uint32_t contact_points, uint32_t current)
{
    double entries = 2.0 * contact_points;
    uint32_t eager = lanes_at(bodies, entries, 1.0);
    /* A change must hold with the bounds a quarter harder to cross, so a world near one
     * does not record its step again and again. */
    if (eager > current) {
        uint32_t sure = lanes_at(bodies, entries, 1.25);
        return sure > current ? sure : current;
    }
    if (eager < current) {
        uint32_t sure = lanes_at(bodies, entries, 0.8);
        return sure < current ? sure : current;
    }
    return current;
}

static tb_result add(const tb_block_solver* s, tb_pass_list* list, VkPipeline pipeline,
                     tb_dispatch_rule rule, VkBuffer counters, VkDeviceSize offset, uint32_t x)
{
    tb_pass pass = tb_pass_with_args(pipeline, rule, counters, offset, x, 0, 0);
    /* block/finish writes the sweeps' dispatch arguments; block/list writes the counters
     * buffer, where the next stage's arguments are (what synchronization validation sees
     * is the buffer, not the bytes). */
    pass.writes_no_arguments = pipeline != s->finish && pipeline != s->list;
    return tb_pass_list_add(list, s->pipelines->gpu->diag, &pass);
}

static tb_result per_body(const tb_block_solver* s, tb_pass_list* list, VkPipeline pipeline,
                          VkBuffer counters, uint32_t x)
{
    return add(s, list, pipeline, TB_DISPATCH_PER_BODY, counters, 0, x);
}

static tb_result per_pair(const tb_block_solver* s, tb_pass_list* list, VkPipeline pipeline,
                          VkBuffer counters)
{
    return add(s, list, pipeline, TB_DISPATCH_INDIRECT, counters,
               TB_COUNTERS_PAIR_DISPATCH_OFFSET, 0);
}

/* A thread per joint slot the lists have room for (the kernels skip slots past those in
 * use, tb_gpu_params.joint_info.x). */
static tb_result per_joint(const tb_block_solver* s, tb_pass_list* list, VkPipeline pipeline,
                           uint32_t joint_capacity)
{
    tb_pass pass = tb_pass_with_args(pipeline, TB_DISPATCH_FIXED, VK_NULL_HANDLE, 0, 0, 0, 0);
    pass.groups[0] = (joint_capacity + TB_WORKGROUP_SIZE - 1) / TB_WORKGROUP_SIZE;
    pass.writes_no_arguments = 1;
    return tb_pass_list_add(list, s->pipelines->gpu->diag, &pass);
}

tb_result tb_block_prepare_joints(tb_block_solver* s, int sweeps)
{
    tb_result r = TB_OK;
    r = tb_pipeline_create_once(s->pipelines, "block/joint_count", TB_WORKGROUP_SIZE,
                                &s->joint_count);
    if (!r) r = tb_pipeline_create_once(s->pipelines, "block/joint_fill", TB_WORKGROUP_SIZE,
                                        &s->joint_fill);
    if (!r) r = tb_pipeline_create_once(s->pipelines, "block/joint_start", TB_WORKGROUP_SIZE,
                                        &s->joint_start);
    if (!r && sweeps) r = tb_pipeline_create_once(s->pipelines, "block/solve_joints",
                                                  TB_SOLVER_WORKGROUP_SIZE, &s->solve_joints);
    /* The tail's own sweep only where block/solve_tail is made (tb_block_init). */
    if (!r && sweeps && s->solve_tail)
        r = tb_pipeline_create_once(s->pipelines, "block/solve_tail_joints",
                                    s->pipelines->gpu->is_cpu ? TB_SOLVER_WORKGROUP_SIZE
                                                              : TB_BLOCK_TAIL_WORKGROUP_SIZE,
                                    &s->solve_tail_joints);
    return r;
}

int tb_block_fuses(uint32_t bodies, uint32_t colours, int cpu_device, int forced)
{
    if (colours >= TB_MAX_COLOURS) return 0;   /* the tail is solved by its own pass */
    if (forced >= 0) return forced;
    return bodies <= (cpu_device ? TB_BLOCK_FUSED_BODIES_CPU : TB_BLOCK_FUSED_BODIES);
}

tb_result tb_block_prepare_fused(tb_block_solver* s, int joints)
{
    return tb_pipeline_create_once(s->pipelines, joints ? "block/solve_fused_joints"
                                                        : "block/solve_fused",
                                   s->pipelines->gpu->is_cpu ? TB_BLOCK_FUSED_WORKGROUP_SIZE_CPU
                                                             : TB_BLOCK_FUSED_WORKGROUP_SIZE,
                                   joints ? &s->solve_fused_joints : &s->solve_fused);
}

uint32_t tb_block_colouring_rounds(uint32_t colours)
{
    return 2 * colours + 8;
}

/* The bodies a colouring of all TB_MAX_COLOURS left over (list.comp flagged them), in body
 * order so the tail's serial solve is repeatable, then written after the colours' runs of
 * block_list. The list fits colour_work: a body is left over only when it has a contact, so
 * there are at most two per pair. */
static tb_result record_tail_list(const tb_block_solver* s, tb_pass_list* list,
                                  VkBuffer counters, const tb_block_lists* lists)
{
    tb_result r = tb_prims_compact(lists->prims, list, lists->tail_flags, lists->tail,
                                   lists->slots, lists->body_capacity, lists->tail_count,
                                   lists->scratch);
    if (!r) r = per_body(s, list, s->list, counters, 2);
    return r;
}

tb_result tb_block_record_colouring(const tb_block_solver* s, tb_pass_list* list,
                                    VkBuffer counters, const tb_block_lists* lists,
                                    uint32_t colours, uint32_t rounds, uint32_t lanes)
{
    tb_gpu_ptr no_total = { 0 };
    tb_result r = per_body(s, list, s->reset, counters, 0);
    if (!r) r = per_pair(s, list, s->count, counters);
    if (!r && lists->joint_capacity) r = per_joint(s, list, s->joint_count, lists->joint_capacity);
    if (!r) r = tb_prims_scan(lists->prims, list, lists->starts, lists->starts, lists->slots,
                              lists->body_capacity, no_total, lists->scratch);
    if (!r) r = per_pair(s, list, s->fill, counters);
    if (!r && lists->joint_capacity) r = per_joint(s, list, s->joint_fill, lists->joint_capacity);
    if (!r) r = per_body(s, list, s->sort, counters, 0);
    if (rounds == 0) rounds = tb_block_colouring_rounds(colours);
    for (uint32_t round = 0; round < rounds && !r; round++)
        r = per_body(s, list, s->colour, counters, round);
    if (!r) r = per_body(s, list, s->list, counters, 0);
    if (!r) r = add(s, list, s->finish, TB_DISPATCH_FIXED, counters, 0, lanes);
    if (!r) r = per_body(s, list, s->list, counters, 1);
    if (!r && colours == TB_MAX_COLOURS) r = record_tail_list(s, list, counters, lists);
    return r;
}

/* One pass of `pipeline` over each colour's bodies (its dispatch covers the sweep's lanes
 * a body), with push args (colour, y, z); with all TB_MAX_COLOURS, then one workgroup of
 * `tail` over the tail (colour TB_MAX_COLOURS), which returns at once when it is empty. */
static tb_result over_colours(const tb_block_solver* s, tb_pass_list* list, VkBuffer counters,
                              VkPipeline pipeline, VkPipeline tail_pipeline, uint32_t colours,
                              uint32_t y, uint32_t z)
{
    tb_result r = TB_OK;
    for (uint32_t c = 0; c < colours && !r; c++) {
        tb_pass pass = tb_pass_with_args(pipeline, TB_DISPATCH_INDIRECT, counters,
                                         TB_COUNTERS_COLOUR_DISPATCH_OFFSET + 16 * (VkDeviceSize)c,
                                         c, y, z);
        pass.writes_no_arguments = 1;
        r = tb_pass_list_add(list, s->pipelines->gpu->diag, &pass);
    }
    if (!r && colours == TB_MAX_COLOURS) {
        tb_pass tail = tb_pass_with_args(tail_pipeline, TB_DISPATCH_FIXED, counters, 0,
                                         TB_MAX_COLOURS, y, z);
        tail.writes_no_arguments = 1;
        r = tb_pass_list_add(list, s->pipelines->gpu->diag, &tail);
    }
    return r;
}

/* The sweeps, the first of a step, in which a world with joints holds their starting
 * error: joint_holds, at most half of them. */
static uint32_t joint_holds(const tb_block_settings* settings)
{
    uint32_t half = settings->iterations / 2;
    return settings->joint_holds < half ? settings->joint_holds : half;
}

/* The step's sweeps: all in one dispatch of the fused solve, or a dispatch a colour and
 * sweep (the tail's own pass where the world has one). */
static tb_result record_sweeps(const tb_block_solver* s, tb_pass_list* list, VkBuffer counters,
                               uint32_t colours, uint32_t lanes, uint32_t iterations,
                               uint32_t holds, uint32_t relax, uint32_t joint_capacity,
                               int fused)
{
    if (fused) {
        uint32_t sweeps = iterations | holds << TB_BLOCK_FUSED_HOLDS_SHIFT;
        tb_pass all = tb_pass_with_args(joint_capacity ? s->solve_fused_joints : s->solve_fused,
                                        TB_DISPATCH_FIXED, counters, 0, colours, sweeps, relax);
        all.writes_no_arguments = 1;
        return tb_pass_list_add(list, s->pipelines->gpu->diag, &all);
    }
    VkPipeline sweep = lanes >= 32 ? s->solve_32 : lanes >= 16 ? s->solve_16 : s->solve;
    VkPipeline tail = s->solve_tail ? s->solve_tail : sweep;
    if (joint_capacity) {
        sweep = s->solve_joints;
        tail = s->solve_tail_joints ? s->solve_tail_joints : sweep;
    }
    tb_result r = TB_OK;
    for (uint32_t it = 0; it < iterations && !r; it++)
        r = over_colours(s, list, counters, sweep, tail, colours,
                         TB_BLOCK_SWEEP_BITS(it, iterations, holds), relax);
    return r;
}

tb_result tb_block_record_solve(const tb_block_solver* s, tb_pass_list* list, VkBuffer counters,
                                uint32_t colours, uint32_t lanes,
                                const tb_block_settings* settings, int restitution,
                                uint32_t joint_capacity, int fused)
{
    /* block/solve takes the over-relaxation in thousandths (0: none). */
    uint32_t relax = (uint32_t)lroundf(settings->over_relaxation * 1000.0f);
    tb_result r = per_pair(s, list, s->start, counters);
    if (!r && joint_capacity) r = per_joint(s, list, s->joint_start, joint_capacity);
    if (!r) r = per_body(s, list, s->guess, counters, 0);
    uint32_t holds = joint_capacity ? joint_holds(settings) : 0;
    if (!r) r = record_sweeps(s, list, counters, colours, lanes, settings->iterations, holds,
                              relax, joint_capacity, fused);
    if (!r) r = per_body(s, list, s->end, counters, 0);
    if (!r && restitution)
        r = over_colours(s, list, counters, s->bounce, s->bounce, colours, 0, 0);
    return r;
}
