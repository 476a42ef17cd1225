/* The block solver: the host side of glsl/block/ (augmented vertex block descent).
 *
 * The default solver: a world uses it unless tb_world_set_solver chose the soft step before
 * the first step, or the environment variable TUMBLE_SOLVER=soft was set at its creation
 * (TUMBLE_BLOCK overrides its settings while it is being tuned).
 *
 * Instead of the soft step's constraints coloured and solved one at a time, it colours the
 * dynamic bodies (no two touching bodies share a colour) and moves each body in turn to
 * the pose that best balances its inertia against its contacts, one 6x6 Newton step per
 * body, all bodies of a colour at once; a contact is a hard constraint reached by an
 * augmented Lagrangian (glsl/block/block.glsl), so loads are carried without the soft
 * contact's give.
 *
 * Its passes read and write the world's set 0: the pairs and manifolds of the step, the
 * constraints solver/prepare wrote (lever arms, friction directions, effective masses), the
 * solver records apply_forces wrote, and its own per-body lists (block_start, block_fill,
 * block_entries), colours (body_colour, block_list, counters.colour) and stiffnesses
 * (constraints' mass.w).
 *
 * In the step: lists and colouring (in place of the soft step's constraint colouring) ->
 * prepare -> apply_forces -> the velocities' gravity and the inertial guess (the soft
 * step's substep passes with one substep) -> the iterations -> velocities -> restitution
 * (while any shape has some) -> integrate.
 */
#ifndef TB_SOLVER_BLOCK_H
#define TB_SOLVER_BLOCK_H

#include "gpu/graph.h"
#include "gpu/prims.h"
#include "layout.h"

typedef struct tb_block_solver {
    tb_pipelines* pipelines;
    VkPipeline reset, count, fill, sort, colour, list, finish, start, guess, end, bounce;
    VkPipeline joint_count, joint_fill, joint_start; ///< made when a world first records joints
    VkPipeline solve_joints, solve_tail_joints;    ///< the sweeps with joints (8 lanes a body)
    VkPipeline solve, solve_16, solve_32;   ///< the sweep with 8, 16 and 32 lanes a body
    VkPipeline solve_tail;                  ///< the sweep over the tail, a workgroup a body
                                            ///< (GPUs; NULL: the sweep's own tail)
    VkPipeline solve_fused, solve_fused_joints; ///< every sweep in one workgroup (small worlds)
} tb_block_solver;

/// What building the contact lists needs: the list starts (uint per body slot, scanned in
/// place), the number of body slots (a GPU uint), the body capacity and scan scratch for it;
/// and for the tail (the bodies a colouring of all TB_MAX_COLOURS leaves over) the flags
/// list.comp writes (body_claim), where the compaction lists them (colour_work) and counts
/// them (counters.colouring.z).
typedef struct tb_block_lists {
    tb_prims* prims;
    tb_gpu_ptr starts, slots, scratch;
    tb_gpu_ptr tail_flags, tail, tail_count;
    uint32_t body_capacity;
    uint32_t joint_capacity;   ///< joint slots the joint passes cover (0: no joint passes)
} tb_block_lists;

/// How the block solver solves (tb_gpu_params.block and block_more; see glsl/block/).
typedef struct tb_block_settings {
    uint32_t iterations;     ///< sweeps over the colours per step
    float stiffness;         ///< a contact's starting stiffness, in effective mass / dt^2
    float growth;            ///< its growth per metre of error and sweep, same unit
    float max_stiffness;     ///< the most it grows to, same unit
    float warm_share;        ///< the share of last step's force a contact starts from
    float stabilisation;     ///< the share of a starting penetration left to later steps
    float stiffness_carry;   ///< the share of last step's stiffness a contact starts from
    float anchored_friction; ///< 1 (the default): friction counts from where a point began
                             ///< to stick, and its multiplier starts each step from nothing;
                             ///< 0: from where the step began (a sticking load creeps:
                             ///< docs/performance.md, "Why the pile creeps"); between: that
                             ///< share of the slip, the multiplier from the rest
    float over_relaxation;   ///< how far a body moves along its Newton step in a sweep
    float joint_max_stiffness;   ///< the most a joint's rows stiffen to, in their unit
    float joint_warm_share;      ///< the share of last step's multipliers a joint starts from
    float joint_stiffness_carry; ///< and of its stiffness
    uint32_t joint_holds;        ///< the first sweeps (at most half), in a world with joints,
                                 ///< in which a joint's hard rows hold the error its step
                                 ///< began with (glsl/block/solve.glsl, sweep_set)
} tb_block_settings;

/// The defaults (TUMBLE_BLOCK="iterations,stiffness,growth,max,warm,stabilisation,carry,
/// anchored,over-relaxation" and TUMBLE_BLOCK_JOINTS="max,warm,carry,holds"
/// override them while the solver is being tuned).
tb_block_settings tb_block_default_settings(void);

tb_result tb_block_init(tb_block_solver* s, tb_pipelines* pipelines);
void tb_block_destroy(tb_block_solver* s);

/// Colouring rounds recorded for `colours` colours: more rounds than colours, as a round
/// colours only the bodies that beat their uncoloured neighbours.
uint32_t tb_block_colouring_rounds(uint32_t colours);

/// Make the sweep with `lanes` lanes a body, and the 8-lane one the first time (each is made
/// on first use, as the step is recorded).
tb_result tb_block_prepare_lanes(tb_block_solver* s, uint32_t lanes);

/// Make the joints' count, fill and start, and with `sweeps` the sweeps with joints (the
/// first time a world records joints; its sweeps then have 8 lanes a body).
tb_result tb_block_prepare_joints(tb_block_solver* s, int sweeps);

/// Whether a world of `bodies` live bodies whose step records `colours` colours solves in
/// one workgroup (block/solve_fused: every sweep of the step in one dispatch, the same
/// results to the bit at the same lanes a body): while its bodies are few
/// (TB_BLOCK_FUSED_BODIES on a GPU, where a colour's dispatch is then mostly launch and
/// barrier; TB_BLOCK_FUSED_BODIES_CPU on a CPU device) and it has no tail. `forced` 0 or 1
/// decides instead (TUMBLE_BLOCK_FUSED; -1: not set). H200 figures: docs/performance.md.
int tb_block_fuses(uint32_t bodies, uint32_t colours, int cpu_device, int forced);

/// Make the fused solve, with or without the joints' rows (on its first use).
tb_result tb_block_prepare_fused(tb_block_solver* s, int joints);

/// The lanes a body for the sweeps (8, 16 or 32; a GPU whose subgroup is narrower, or a CPU
/// device, uses fewer: glsl/block/block.glsl), from the world's bodies and the contact
/// points of its last step, and the lanes in use now (`current`, which the choice keeps
/// unless it is clearly better to change: each change records the step again). More lanes
/// shorten each lane's chain of loads, which pays while the bodies are few and have many
/// points each (H100, solve ms: pyramid of 5,050, 24 list entries a body, 1.90 with 8 lanes,
/// 1.64 with 16, 1.43 with 32; deep pile of 4,000 0.78, 0.72, 0.81), and costs once a
/// colour's bodies outnumber the threads the GPU runs at once (boxes 10,000: 1.13, 1.17,
/// 1.48; 100,000: 4.00, 5.57, 9.50).
uint32_t tb_block_lanes_for(uint32_t bodies, uint32_t contact_points, uint32_t current);

#define TB_BLOCK_FUSED_BODIES 64        ///< a GPU's small world (tb_block_fuses)
#define TB_BLOCK_FUSED_BODIES_CPU 0     ///< a CPU device's: none (lavapipe's barriers cost more)
#define TB_BLOCK_FUSED_WORKGROUP_SIZE 256       ///< on a GPU: 32 bodies at once
#define TB_BLOCK_FUSED_WORKGROUP_SIZE_CPU 64    ///< on a CPU device, one lane a body

/// The contact list of every dynamic body and the colouring of the dynamic bodies:
/// reset, count (and the joints' count, with lists->joint_capacity), scan, fill (and the
/// joints' fill), sort, `rounds` colouring rounds (0: tb_block_colouring_rounds(colours)),
/// then the bodies listed by colour (their sweeps' dispatches sized for `lanes` lanes a
/// body); with all TB_MAX_COLOURS, then the bodies the colouring left over listed, in body
/// order, as the tail. `counters` is the buffer bound at TB_BIND_COUNTERS.
tb_result tb_block_record_colouring(const tb_block_solver* s, tb_pass_list* list,
                                    VkBuffer counters, const tb_block_lists* lists,
                                    uint32_t colours, uint32_t rounds, uint32_t lanes);

/// The iterations (after the solver records hold the velocities with gravity and the
/// inertial pose): start (and the joints' start, with `joint_capacity` slots), guess, then `iterations` sweeps (`lanes` lanes a body, as the
/// colouring was recorded with), each a solve of colours 0..colours-1 (and, with all
/// TB_MAX_COLOURS, of the tail, one body at a time) that also updates the multipliers;
/// then the velocities, and with `restitution` (some shape of the world has restitution) a
/// pass over the colours that makes fast contacts bounce (glsl/block/bounce.comp).
/// (Sweeping the colours back on every other iteration, a symmetric Gauss-Seidel, measured
/// worse: a 20-box column sank 8.4 cm instead of 8.6 mm.) With `fused` (tb_block_fuses;
/// never with the tail) every sweep is one dispatch of block/solve_fused instead.
tb_result tb_block_record_solve(const tb_block_solver* s, tb_pass_list* list, VkBuffer counters,
                                uint32_t colours, uint32_t lanes,
                                const tb_block_settings* settings, int restitution,
                                uint32_t joint_capacity, int fused);

#endif
