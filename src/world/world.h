/* The world: everything a tb_world owns, and the work the API calls hand it once their
 * arguments are checked.
 *
 * It owns the GPU plumbing (src/gpu), the bodies (host records, the body store on the GPU),
 * the shapes (records, the GPU shape table), the step's buffers (sim.h), and one of each
 * stage: the broadphase, the narrowphase, the solver and the plugins. It assembles the
 * stages into the step graph (step.c), submits steps, grows what overflowed and runs the
 * step again (run.c), reads results back (readback.c, stats.c) and hands each step's
 * contact events to the plugins that want them (events.c). A stage sees the world
 * only through its own narrow struct, which the world fills in: tb_broadphase_ctx,
 * tb_narrowphase, tb_solver, tb_plugin_host.
 */
#ifndef TB_WORLD_WORLD_H
#define TB_WORLD_WORLD_H

#include "base/base.h"
#include "broadphase/broadphase.h"
#include "geom/geom.h"
#include "gpu/gpu.h"
#include "joints/joints.h"
#include "layout.h"
#include "narrowphase/narrowphase.h"
#include "broadphase/pair_split.h"
#include "plugin/plugin.h"
#include "solver/block.h"
#include "solver/solver.h"
#include "tumble.h"
#include "world/body_store.h"
#include "world/sim.h"

#define TB_DEF_COOKIE 0x54554d42 /* "TUMB" */

/// Host-side record of a body; what the GPU needs lives in the body store.
typedef struct tb_body_record {
    uint16_t generation;
    uint8_t alive;
    uint8_t type;           ///< tb_body_type
    uint8_t isolated;       ///< its state stopped being finite in a step (guard.c)
    uint32_t shape;         ///< shape slot
    float mass;             ///< kg, 0 for static
    tb_vec3 inertia;        ///< principal moments, kg m^2
    void* user_data;
} tb_body_record;

typedef struct tb_shape_record {
    uint16_t generation;
    uint8_t alive;
    tb_shape_type type;
    tb_shape_def material;
    float volume;           ///< m^3; 0 for planes
    tb_vec3 unit_inertia;   ///< principal moments of inertia per kg of mass
    uint32_t users;         ///< live bodies and compounds using the shape
    tb_hull* hull;          ///< hulls and boxes: the geometry the GPU gets (owned); else NULL
    tb_mesh* mesh;          ///< meshes: their geometry (owned); else NULL
    tb_heightfield* heightfield; ///< heightfields: their grid (owned); else NULL
    tb_compound* compound;  ///< compounds: their children (owned); else NULL
    tb_buffer mesh_buffer;  ///< meshes, heightfields and compounds: the GPU image, by address
    int mesh_pending;       ///< meshes, heightfields and compounds: the image is not uploaded yet
} tb_shape_record;

/// Contact events of one step, as the callbacks get them.
typedef struct tb_event_list {
    tb_contact_event* events;
    uint32_t count, capacity;
} tb_event_list;

/// The contact events the GPU finds in each step while a plugin wants them (events.c).
typedef struct tb_events {
    VkPipeline find;                       ///< narrowphase/events
    tb_buffer buffer;                      ///< tb_gpu_contact_event[capacity]
    uint32_t capacity;
    tb_gpu_contact_event* sorted;          ///< a submission's events, sorted
    uint32_t sorted_capacity;
    tb_event_list begin, end;              ///< one step's, for the callbacks
} tb_events;

struct tb_world {
    uint16_t serial;
    tb_diag diag;
    tb_gpu gpu;
    tb_memory memory;
    tb_pipelines pipelines;
    tb_graph graph;
    tb_transfer transfer;
    tb_body_store store;
    tb_prims prims;
    tb_gpu_kit kit;                        ///< the above, as the stages borrow them
    tb_sim sim;
    VkPipeline step_begin, step_end;       ///< step/begin, step/end
    VkPipeline distance_query;             ///< query/distance, made by the first query
    VkCommandBuffer query_cb;              ///< the distance queries' submissions
    tb_broadphase broadphase_kind;         ///< never TB_BROADPHASE_DEFAULT
    const tb_broadphase_ops* broadphase;
    tb_broadphase_ctx bp;                  ///< what the broadphase sees
    tb_narrowphase narrowphase;
    tb_pair_split split;
    tb_solver solver;
    tb_block_solver block;
    int block_solver;            ///< the step solves with the block solver (solver/block.h)
    tb_block_settings block_settings;
    uint32_t body_set_version;             ///< bodies created and destroyed so far
    int step_built;              ///< the graph holds the current step (rounds, capacities)
    uint32_t colour_rounds;      ///< colouring rounds recorded (grows when a step needs more)
    uint32_t block_colours_unused; ///< runs of steps in a row that left a recorded colour unused
    uint32_t block_rounds;       ///< the block solver's colouring rounds recorded; 0: as many as
                                 ///< a colouring of colour_rounds colours may need
    uint32_t block_lanes;        ///< lanes a body in the block solver's sweeps (tb_block_lanes_for)
    int block_lanes_fixed;       ///< block_lanes set by TUMBLE_BLOCK_LANES, not chosen
    int block_fused;             ///< the step records the fused solve (tb_block_fuses)
    int block_fused_forced;      ///< TUMBLE_BLOCK_FUSED: 0 never, 1 always (no tail), -1 chosen
    uint32_t steps_per_submit;   ///< tb_world_step_n's batches (run.c; TUMBLE_STEPS_PER_SUBMIT)
    uint32_t substeps, solver_iterations;
    float contact_margin, restitution_threshold;
    float reuse_distance, reuse_angle;   ///< tb_world_set_contact_reuse
    float contact_hertz, contact_damping_ratio, contact_push_speed;
    uint64_t gpu_steps;          ///< steps the GPU completed (its counters.state.y)
    uint64_t steps_redone;       ///< steps run again after a buffer grew
    int in_callbacks;            ///< plugins' contact callbacks are running (within a step)
    uint32_t guard_seen;         ///< counters.guard.x the host has looked at (guard.c)
    uint32_t isolated_bodies;    ///< live bodies the step isolated (guard.c)
    tb_buffer params_buffer;
    tb_buffer params_swap;       ///< scratch through which a step swaps the manifold arrays
    tb_gpu_params params;

    tb_vec3 gravity;
    float max_rotation_per_step;
    uint32_t max_bodies, max_shapes;

    tb_slots body_slots;
    tb_body_record* bodies;
    uint32_t body_record_capacity; ///< records allocated on the host

    tb_slots shape_slots;
    tb_shape_record* shapes;
    uint32_t shape_table_capacity; ///< records allocated on the host
    tb_gpu_shape* gpu_shapes;    ///< host copy of the shape table
    tb_buffer shape_buffer;
    uint32_t shape_buffer_capacity;
    int shapes_dirty;
    tb_plugins plugins;
    tb_events events;
    tb_joints joints;
    uint32_t joint_passes;       ///< the joint capacity the step's joint passes were recorded
                                 ///< for (0: none recorded)
    int joint_ranks_dirty;       ///< the joint graph changed: rank its bodies again
                                 ///< (joint_ranks.c) before the next submission
    uint32_t bouncy_shapes;      ///< shapes ever made with restitution > 0: the block solver
                                 ///< records its restitution pass once there is one
    uint32_t hull_shapes;        ///< live TB_SHAPE_HULL shapes: the step records the hull pass
    uint32_t mesh_shapes;        ///< live mesh and heightfield shapes: the step records the
                                 ///< mesh passes
    uint32_t compound_shapes;    ///< live compound shapes: the step records the midphase split
    uint32_t round_shapes;       ///< live capsules, cylinders and cones: the step records
                                 ///< narrowphase/round_points
    uint32_t mesh_uploads;       ///< mesh images waiting for the next submission

    uint64_t buffer_generation;  ///< bumped whenever a GPU buffer is replaced
    uint64_t steps, submits;
    double stage_ms[TB_MAX_STAGES];
    double gpu_ms;
};

/// Substeps the step runs: the world's, or 1 for the block solver (one step, many sweeps).
static inline uint32_t tb_world_substeps(const tb_world* w)
{
    return w->block_solver ? 1 : w->substeps;
}

/* query.c */
/// Runs `count` distance queries on the GPU (shapes checked by the caller).
tb_result tb_world_distances(tb_world* w, const tb_gpu_distance_query* in, uint32_t count,
                             tb_gpu_distance_result* out);

/* world.c */
/// A world for a checked def and a resolved broadphase, with extra device options
/// (extensions) for Vulkan embedders. `early` holds the log sink (and any error).
tb_result tb_world_build(const tb_world_def* def, tb_broadphase broadphase, tb_diag* early,
                         const tb_gpu_options* extra, tb_world** out);
/// Free everything; NULL does nothing.
void tb_world_free(tb_world* w);
/// Make room for `slots` body slots on the GPU.
tb_result tb_world_reserve_bodies(tb_world* w, uint32_t slots);

/// Step with the block solver (`block`) or the soft step from the next step on, the block
/// solver with `iterations` sweeps (0: as it was). Only for a world that has not stepped:
/// the step buffers are made anew (tb_sim_set_block_lists).
tb_result tb_world_use_solver(tb_world* w, int block, uint32_t iterations);

/* run.c: submitting steps, growing what overflowed and running the step again. */
/// Run n steps of dt (checked), redoing any step a buffer overflowed in.
tb_result tb_world_run(tb_world* w, float dt, uint32_t n);
/// The steps a submission holds at the most (4096, or TUMBLE_STEPS_PER_SUBMIT's fewer).
uint32_t tb_world_steps_per_submit(void);
/// Upload what the host wrote and the GPU has not seen yet.
tb_result tb_world_flush(tb_world* w);
/// Bring the arrays in `mask` of the body mirror up to date (uploading first what is dirty).
tb_result tb_world_fetch(tb_world* w, uint32_t mask);

/* step.c */
tb_result tb_step_kernels_create(tb_world* w);
void tb_step_kernels_destroy(tb_world* w);
/// Build the step graph for the current capacities and colouring rounds.
tb_result tb_step_build(tb_world* w);
/// Whether the world's step, recorded now, would fuse the block solver's sweeps
/// (tb_block_fuses of its live bodies, recorded colours, device and TUMBLE_BLOCK_FUSED).
int tb_step_fuses_sweeps(const tb_world* w);
/// Fill in what the broadphase sees of the step's buffers (they move when they grow).
void tb_step_broadphase_io(tb_world* w);

/* bodies.c: a body def the API checked, and what the GPU needs of it. */
typedef struct tb_body_resolved {
    uint32_t shape;         ///< shape slot
    tb_quat rotation;       ///< normalised
    float mass;
    tb_vec3 inertia;
} tb_body_resolved;

/// The record of a valid id, or an error and NULL.
tb_body_record* tb_body_lookup(tb_world* w, tb_body_id id, uint32_t* slot, tb_result* r);
/// The id of the live body in a slot; the null id for a dead or unused slot.
tb_body_id tb_body_id_of_slot(const tb_world* w, uint32_t slot);
/// Add `count` checked bodies (ids to out); all or none.
tb_result tb_bodies_add(tb_world* w, const tb_body_def* defs, const tb_body_resolved* resolved,
                        uint32_t count, tb_body_id* out);
void tb_bodies_remove(tb_world* w, uint32_t slot);
/// Host records for `needed` slots (new ones zeroed).
tb_result tb_bodies_reserve_records(tb_world* w, uint32_t needed);
void tb_bodies_set_pose(tb_world* w, uint32_t slot, tb_vec3 p, tb_quat unit);
void tb_bodies_set_velocity(tb_world* w, uint32_t slot, tb_vec3 v, tb_vec3 av);
tb_result tb_bodies_get_velocity(tb_world* w, uint32_t slot, tb_vec3* v, tb_vec3* av);
/// An impulse at a world point of a dynamic body: velocities change at once.
tb_result tb_bodies_apply_impulse(tb_world* w, uint32_t slot, tb_vec3 impulse, tb_vec3 point);
/// Two arrays of the body mirror, fresh, for ids already checked: a as vec3, b as quat or vec3.
tb_result tb_bodies_gather(tb_world* w, const tb_body_id* ids, uint32_t count,
                           tb_body_array a, tb_body_array b, tb_vec3* out_a, void* out_b,
                           int b_is_quat);
uint32_t tb_bodies_ids(const tb_world* w, tb_body_id* out, uint32_t capacity);

/* shapes.c */
/// The record of a valid id, or an error and NULL.
tb_shape_record* tb_shape_lookup(tb_world* w, tb_shape_id id, uint32_t* slot, tb_result* r);
/// Capsules, cylinders and cones: convex shapes whose pairs narrowphase/round_points solves.
int tb_shape_type_is_round(tb_shape_type type);
/// Spheres, boxes, hulls and the round shapes: what distance queries measure and compounds
/// take as children.
int tb_shape_type_is_convex(tb_shape_type type);
/// Add a checked shape: its record (a hull it holds becomes the world's) and its GPU entry.
tb_result tb_shapes_add(tb_world* w, tb_shape_record* record, const tb_gpu_shape* gpu,
                        tb_shape_id* out);
/// Remove a shape no body uses.
void tb_shapes_remove(tb_world* w, uint32_t slot);
/// Free a shape's hull or mesh geometry on the host, if it has any.
void tb_shape_release_hull(tb_shape_record* s);
/// Staging bytes of the mesh images not uploaded yet, and their uploads.
VkDeviceSize tb_shapes_mesh_upload_bytes(const tb_world* w);
void tb_shapes_record_mesh_uploads(tb_world* w, tb_transfer* t);
/// The GPU shape table, created at `capacity` entries (replacing any).
tb_result tb_shapes_create_buffer(tb_world* w, uint32_t capacity);
/// Pack the hulls if they changed and give the GPU shape table room for every shape slot
/// (either may replace buffers).
tb_result tb_world_prepare_shapes(tb_world* w);

/* joints.c: joints in the world (the API checked their defs). */
/// The record of a valid id, or an error and NULL.
tb_joint_record* tb_joint_lookup(tb_world* w, tb_joint_id id, uint32_t* slot, tb_result* r);
tb_joint_id tb_joint_id_of_slot(const tb_world* w, uint32_t slot);
/// Add `count` checked joints whose bodies are the slots a[i] and b[i]; all or none.
tb_result tb_world_joints_add(tb_world* w, const tb_joint_def* defs, const uint32_t* a,
                              const uint32_t* b, uint32_t count, tb_joint_id* out);
void tb_world_joint_remove(tb_world* w, uint32_t slot);
/// Remove the joints that hold the body in `body_slot` (it is being destroyed).
void tb_world_joints_of_body_remove(tb_world* w, uint32_t body_slot);
/// Ids of live joints in slot order (at most `capacity`); returns how many there are.
uint32_t tb_world_joints_ids(const tb_world* w, tb_joint_id* out, uint32_t capacity);

/* joint_ranks.c: the joint graph's colouring, the GPU colouring's first priority. */

/// When the joint graph changed: each body's colour in a greedy breadth-first colouring of
/// the joints between dynamic bodies into body_info.z (0 without joints), for upload.
tb_result tb_world_rank_joint_bodies(tb_world* w);

/* readback.c */
tb_result tb_world_contacts(tb_world* w, tb_contact* out, uint32_t capacity, uint32_t* count);
/// Manifolds of the last step for interop: buffer, count, size.
void tb_world_contact_buffer(const tb_world* w, VkBuffer* buffer, uint32_t* count,
                             VkDeviceSize* size);

/* guard.c: bodies whose state stopped being finite (integrate isolates them on the GPU). */
/// After a submission: find the bodies its steps isolated, mark their records and log them.
tb_result tb_world_guard_check(tb_world* w, const tb_gpu_counters* c);
/// Ids of the live isolated bodies in slot order (at most `capacity`); returns how many there are.
uint32_t tb_world_isolated(const tb_world* w, tb_body_id* out, uint32_t capacity);

/* snapshot.c: the state the next step depends on, out to bytes and back. */
/// Write the snapshot to out (NULL: only its size) and its size to *size.
tb_result tb_world_save(tb_world* w, void* out, size_t capacity, size_t* size);
/// Put a snapshot back, or refuse it with a sentence and change nothing.
tb_result tb_world_load(tb_world* w, const void* data, size_t size);

/* stats.c */
void tb_world_stats_read(const tb_world* w, tb_world_stats* out);
void tb_world_device(const tb_world* w, tb_device_info* out);

/* plugins.c: the plugin calls, which make the step record again. */
tb_result tb_world_plugins_init(tb_world* w);
tb_result tb_world_plugin_load(tb_world* w, const char* path, tb_plugin_id* out);
tb_result tb_world_plugin_unload(tb_world* w, tb_plugin_id id);

/* events.c */
tb_result tb_events_init(tb_world* w);
void tb_events_destroy(tb_world* w);
/// While a plugin wants them: the stage that finds the step's events (narrowphase/events).
tb_result tb_events_record(tb_world* w, tb_pass_list* list);
/// After a submission: the events of its completed steps to the plugins, step by step.
tb_result tb_events_deliver(tb_world* w, const tb_gpu_counters* counters);
/// A step found more events than the buffer holds (TB_ABORT_EVENTS): make room for `need`.
tb_result tb_events_grow(tb_world* w, uint32_t need);

/* shader_dir.c */
/// Compile the step's shaders from a GLSL tree from now on (hot-reload).
tb_result tb_world_shader_dir(tb_world* w, const char* dir);
/// TUMBLE_SHADER_DIR, when set, as tb_world_shader_dir (before any pipeline exists).
tb_result tb_world_shader_dir_from_env(tb_world* w);
/// Between steps: swap in the shaders written since the last step (hot-reload).
void tb_world_reload_shaders(tb_world* w);

#endif
