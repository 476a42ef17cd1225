/* Pipelines and pass lists of the contact solver. */
#include "solver/solver.h"

#include <stddef.h>
#include <string.h>

#include "layout.h"

/* The contacts' constraints, the free motion and the integration, which both solvers use. */
static const tb_pipeline_slot kernels[] = {
    { "solver/prepare", TB_WORKGROUP_SIZE, offsetof(tb_solver, prepare) },
    { "integrate/substep", TB_WORKGROUP_SIZE, offsetof(tb_solver, substep) },
    { "integrate/apply_forces", TB_WORKGROUP_SIZE, offsetof(tb_solver, apply_forces) },
    { "integrate/integrate", TB_WORKGROUP_SIZE, offsetof(tb_solver, integrate) },
};
#define KERNEL_COUNT (sizeof kernels / sizeof kernels[0])

/* The soft step's own, made when a world first uses it (on lavapipe they take a tenth of a
 * world's creation). Workgroup sizes: per-pair passes match counters.pair_dispatch,
 * colour_finish has one thread per colour, solve matches counters.colour_dispatch, the tail
 * is one thread. */
static const tb_pipeline_slot soft_kernels[] = {
    { "solver/colour_claim", TB_WORKGROUP_SIZE, offsetof(tb_solver, colour_claim) },
    { "solver/colour_decide", TB_WORKGROUP_SIZE, offsetof(tb_solver, colour_decide) },
    { "solver/colour_finish", TB_MAX_COLOURS, offsetof(tb_solver, colour_finish) },
    { "solver/solve", TB_SOLVER_WORKGROUP_SIZE, offsetof(tb_solver, solve) },
    { "solver/solve_tail", 1, offsetof(tb_solver, solve_tail) },
    { "solver/tail_list", TB_WORKGROUP_SIZE, offsetof(tb_solver, tail_list) },
};
#define SOFT_KERNEL_COUNT (sizeof soft_kernels / sizeof soft_kernels[0])

tb_result tb_solver_init(tb_solver* s, tb_pipelines* pipelines)
{
    memset(s, 0, sizeof *s);
    tb_result r = tb_pipeline_create_slots(pipelines, kernels, KERNEL_COUNT, s);
    if (!r) s->pipelines = pipelines;
    return r;
}

tb_result tb_solver_prepare_soft_step(tb_solver* s)
{
    /* The slots are made all or none (tb_pipeline_create_slots), so one stands for all. */
    if (s->solve) return TB_OK;
    return tb_pipeline_create_slots(s->pipelines, soft_kernels, SOFT_KERNEL_COUNT, s);
}

void tb_solver_destroy(tb_solver* s)
{
    if (!s->pipelines) return;
    tb_pipeline_destroy_slots(s->pipelines, kernels, KERNEL_COUNT, s);
    tb_pipeline_destroy_slots(s->pipelines, soft_kernels, SOFT_KERNEL_COUNT, s);
    memset(s, 0, sizeof *s);
}

static tb_result add(const tb_solver* s, tb_pass_list* list, const tb_pass* pass)
{
    return tb_pass_list_add(list, s->pipelines->gpu->diag, pass);
}

/* A pass over this step's pairs with push arguments (x, y, z). */
static tb_pass per_pair(VkPipeline pipeline, VkBuffer counters, uint32_t x, uint32_t y, uint32_t z)
{
    return tb_pass_with_args(pipeline, TB_DISPATCH_INDIRECT, counters,
                             TB_COUNTERS_PAIR_DISPATCH_OFFSET, x, y, z);
}

/* A colouring pass: per pair, and push w numbers the pass (it picks the work lists). */
static tb_pass colouring_pass(VkPipeline pipeline, VkBuffer counters, uint32_t round,
                              uint32_t sub, uint32_t subs, uint32_t pass_number)
{
    tb_pass pass = per_pair(pipeline, counters, round, sub, subs);
    tb_gpu_push push;
    memcpy(&push, pass.push, sizeof push);
    push.args.w = pass_number;
    memcpy(pass.push, &push, sizeof push);
    return pass;
}

static tb_result check_rounds(const tb_solver* s, uint32_t rounds)
{
    if (rounds >= 1 && rounds <= TB_MAX_COLOURS) return TB_OK;
    return tb_fail(s->pipelines->gpu->diag, TB_ERROR_INVALID_ARGUMENT,
                   "colouring rounds must be 1..%d, not %u", TB_MAX_COLOURS, rounds);
}

tb_result tb_solver_record_colouring(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                     uint32_t rounds, uint32_t sub_rounds)
{
    tb_result r = check_rounds(s, rounds);
    if (!r && sub_rounds == 0)
        r = tb_fail(s->pipelines->gpu->diag, TB_ERROR_INVALID_ARGUMENT, "sub_rounds must be >= 1");
    uint32_t pass_number = 0;
    for (uint32_t round = 0; round < rounds && !r; round++) {
        /* The last possible round's taken mark would read as free: it gets one sub-round. */
        uint32_t subs = round + 1 < TB_MAX_COLOURS ? sub_rounds : 1;
        for (uint32_t sub = 0; sub < subs && !r; sub++, pass_number++) {
            tb_pass claim = colouring_pass(s->colour_claim, counters, round, sub, subs, pass_number);
            tb_pass decide = colouring_pass(s->colour_decide, counters, round, sub, subs,
                                            pass_number);
            r = add(s, list, &claim);
            if (!r) r = add(s, list, &decide);
        }
    }
    tb_pass finish = { .pipeline = s->colour_finish, .rule = TB_DISPATCH_FIXED, .groups = { 1, 1, 1 } };
    return r ? r : add(s, list, &finish);
}

tb_result tb_solver_record_tail_list(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                     const tb_solver_tail* tail)
{
    tb_pass flags = per_pair(s->tail_list, counters, 0, 0, 0);
    tb_gpu_ptr second = tb_gpu_ptr_add(tail->work, (VkDeviceSize)tail->pair_capacity * 4);
    tb_result r = add(s, list, &flags);
    if (!r) r = tb_prims_compact(tail->prims, list, second, tail->work, tail->pair_count,
                                 tail->pair_capacity, tail->list_count, tail->scratch);
    return r;
}

/* One sweep over the colours (TB_SOLVE_* in push z, the substep in y), and the tail. */
static tb_result record_sweep(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                              uint32_t rounds, uint32_t substep, uint32_t mode)
{
    tb_result r = TB_OK;
    for (uint32_t colour = 0; colour < rounds && !r; colour++) {
        tb_pass solve = tb_pass_with_args(s->solve, TB_DISPATCH_INDIRECT, counters,
                                          TB_COUNTERS_COLOUR_DISPATCH_OFFSET + 16 * (VkDeviceSize)colour,
                                          colour, substep, mode);
        solve.writes_no_arguments = 1;
        r = add(s, list, &solve);
    }
    if (!r && rounds == TB_MAX_COLOURS) {
        tb_pass tail = tb_pass_with_args(s->solve_tail, TB_DISPATCH_FIXED, counters, 0, 0,
                                         substep, mode);
        tail.writes_no_arguments = 1;
        r = add(s, list, &tail);
    }
    return r;
}

tb_result tb_solver_record_substep_bodies(const tb_solver* s, tb_pass_list* list, uint32_t what,
                                          uint32_t pieces)
{
    tb_pass pass = tb_pass_with_args(s->substep, TB_DISPATCH_PER_BODY, VK_NULL_HANDLE, 0, 0,
                                     pieces, what);
    pass.writes_no_arguments = 1;
    return add(s, list, &pass);
}

tb_result tb_solver_record_prepare(const tb_solver* s, tb_pass_list* list, VkBuffer counters)
{
    tb_pass prepare = per_pair(s->prepare, counters, 0, 0, 0);
    return add(s, list, &prepare);
}

tb_result tb_solver_record_solve(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                 uint32_t rounds, uint32_t substeps, uint32_t iterations)
{
    tb_result r = check_rounds(s, rounds);
    for (uint32_t sub = 0; sub < substeps && !r; sub++) {
        r = tb_solver_record_substep_bodies(s, list, 0, 1);
        if (!r) r = record_sweep(s, list, counters, rounds, sub, TB_SOLVE_WARM);
        for (uint32_t it = 0; it < iterations && !r; it++)
            r = record_sweep(s, list, counters, rounds, sub, TB_SOLVE_BIAS);
        if (!r) r = tb_solver_record_substep_bodies(s, list, 1, 1);
        if (!r) r = record_sweep(s, list, counters, rounds, sub, TB_SOLVE_RELAX);
    }
    if (!r) r = record_sweep(s, list, counters, rounds, substeps, TB_SOLVE_RESTITUTION);
    return r;
}

/* A per-body pass of the step's own (indirect buffer: the counters, as every step kernel). */
static tb_result record_per_body(const tb_solver* s, tb_pass_list* list, VkPipeline pipeline,
                                 VkBuffer counters)
{
    tb_pass pass = tb_pass_with_args(pipeline, TB_DISPATCH_PER_BODY, counters, 0, 0, 0, 0);
    return add(s, list, &pass);
}

tb_result tb_solver_record_apply_forces(const tb_solver* s, tb_pass_list* list, VkBuffer counters)
{
    return record_per_body(s, list, s->apply_forces, counters);
}

tb_result tb_solver_record_integrate(const tb_solver* s, tb_pass_list* list, VkBuffer counters)
{
    return record_per_body(s, list, s->integrate, counters);
}

/* The soft contact of a substep h (Box2D v3's soft step): a damped spring of contact_hertz,
 * capped at a quarter of the substep rate so it stays stable (at half the rate a 10-box
 * column already rocks itself over); 0 takes the cap (twice as stiff against static
 * bodies, which cannot give way), written as the bias rate, mass
 * scale and impulse scale the solve uses (see glsl/solver/contact.glsl). */
tb_gpu_vec4 tb_solver_softness(const tb_solver_contact* c, float h, double scale)
{
    if (!(h > 0)) return (tb_gpu_vec4){ 0, 1, 0, 0 };
    double cap = 0.25 / h;
    double hertz = scale * (c->hertz > 0 && c->hertz < cap ? c->hertz : cap);
    double omega = 2.0 * 3.14159265358979323846 * hertz, zeta = c->damping_ratio;
    double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
    return (tb_gpu_vec4){ (float)(omega / a1), (float)(a2 * a3), (float)a3, h };
}
