/* The solver: the host side of glsl/solver/ and glsl/integrate/.
 *
 * Reads this step's manifolds (narrowphase/contacts), the pairs and the bodies' poses,
 * velocities and inverse mass; writes the colour list and batches, the constraints (solver
 * data and accumulated impulses, kept for the next step's warm start) and the bodies'
 * velocities and poses. Its passes: graph colouring of the constraints into batches, then
 * the soft step: substeps of batched projected Gauss-Seidel with soft contacts and a relax
 * sweep (glsl/solver/).
 *
 * The passes read and write the world's set 0 (counters, pairs, manifolds, constraints,
 * colour list, body arrays, claims, push); sizes only the GPU knows come from the counters:
 * per-pair passes are dispatched with counters.pair_dispatch, the solve of colour c with
 * counters.colour_dispatch[c]. The host records every colour that may exist (`rounds`), so
 * colours the step did not use are empty dispatches.
 *
 * In the step: colouring -> prepare -> apply_forces (resets claims and push) -> solve ->
 * integrate (moves poses with velocity + push).
 */
#ifndef TB_SOLVER_SOLVER_H
#define TB_SOLVER_SOLVER_H

#include "gpu/graph.h"
#include "gpu/prims.h"
#include "layout.h"

typedef struct tb_solver {
    tb_pipelines* pipelines;
    VkPipeline colour_claim, colour_decide, colour_finish, prepare, solve, solve_tail, substep;
    VkPipeline tail_list, apply_forces, integrate;
} tb_solver;

/// What listing the tail's constraints needs: the colour work lists (2 x pair capacity
/// uints), the pair count and where the list's length goes (counters.state.z and
/// counters.colouring.z), and compaction scratch for the pair capacity.
typedef struct tb_solver_tail {
    tb_prims* prims;
    tb_gpu_ptr work, pair_count, list_count, scratch;
    uint32_t pair_capacity;
} tb_solver_tail;

/// Build the pipelines both solvers use (the constraints' preparation, the free motion, the
/// integration).
tb_result tb_solver_init(tb_solver* s, tb_pipelines* pipelines);
/// Build the soft step's own pipelines (colouring, solve, tail), once: a world makes them
/// when it first steps with the soft step.
tb_result tb_solver_prepare_soft_step(tb_solver* s);
void tb_solver_destroy(tb_solver* s);

/// Sub-rounds per colouring round that make colours nearly as few as a sequential greedy
/// colouring (2 gets within a colour or two of it on random and lattice graphs; 1 needs
/// about 1.5 times the colours).
#define TB_SOLVER_SUB_ROUNDS 2

/// Colouring: for each of `rounds` rounds (1..TB_MAX_COLOURS, params.capacity.z), `sub_rounds`
/// (>= 1; the last possible round always gets 1) times colour_claim then colour_decide; then
/// colour_finish. `counters` is the buffer bound at TB_BIND_COUNTERS.
tb_result tb_solver_record_colouring(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                     uint32_t rounds, uint32_t sub_rounds);

/// After a colouring of TB_MAX_COLOURS rounds (only then): the constraints it left, in pair
/// order, for solve_tail: flags (tail_list) into the second work list, compacted into the
/// first.
tb_result tb_solver_record_tail_list(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                     const tb_solver_tail* tail);

/// prepare: the constraints' solver data. Before gravity is applied, so restitution sees the
/// approach speed the body had when the step began (the speed it hit with).
tb_result tb_solver_record_prepare(const tb_solver* s, tb_pass_list* list, VkBuffer counters);

/// The soft step, `substeps` times: gravity (integrate/substep), a warm-start sweep,
/// `iterations` solve sweeps, the motion (integrate/substep), a relax sweep; then one
/// restitution sweep. A sweep is the solve of colours 0..rounds-1, and solve_tail when
/// rounds == TB_MAX_COLOURS (the only case that may leave constraints uncoloured without
/// abandoning the step).
tb_result tb_solver_record_solve(const tb_solver* s, tb_pass_list* list, VkBuffer counters,
                                 uint32_t rounds, uint32_t substeps, uint32_t iterations);

/// A per-body pass of integrate/substep: `what` 0 the velocities' gravity and gyroscopic
/// change over a substep, 1 the motion over a substep, 2 both in turn in `pieces` pieces of
/// the substep (`pieces` is read only then).
tb_result tb_solver_record_substep_bodies(const tb_solver* s, tb_pass_list* list, uint32_t what,
                                          uint32_t pieces);

/// apply_forces (integrate/apply_forces), per body: each body's solver record from its damped
/// velocities and mass, and no colouring claim. After prepare, before the solve.
tb_result tb_solver_record_apply_forces(const tb_solver* s, tb_pass_list* list, VkBuffer counters);
/// integrate (integrate/integrate), per body: poses from the solved velocities and push.
tb_result tb_solver_record_integrate(const tb_solver* s, tb_pass_list* list, VkBuffer counters);

/// How soft contacts are (tb_world_def.contact_hertz and contact_damping_ratio).
typedef struct tb_solver_contact {
    float hertz, damping_ratio;
} tb_solver_contact;

/// The soft contact of a substep h (tb_gpu_params.soft), `scale` times as stiff.
tb_gpu_vec4 tb_solver_softness(const tb_solver_contact* c, float h, double scale);

#endif
