/* The world as the API layer sees it: ids, host-side records and the GPU objects. */
#ifndef TB_WORLD_H
#define TB_WORLD_H

#include "base/diag.h"
#include "plugin/plugin.h"
#include "broadphase/broadphase.h"
#include "geom/hull.h"
#include "world/body_store.h"
#include "gpu/graph.h"
#include "gpu/memory.h"
#include "gpu/pipeline.h"
#include "gpu/prims.h"
#include "world/sim.h"
#include "solver/solver.h"
#include "gpu/transfer.h"
#include "layout.h"
#include "tumble.h"

#define TB_DEF_COOKIE 0x54554d42 /* "TUMB" */

/// The step's compute kernels (src/api/step.c names their shaders).
typedef enum tb_kernel {
    TB_KERNEL_STEP_BEGIN, TB_KERNEL_WORLD_AABB, TB_KERNEL_CONTACTS, TB_KERNEL_HULL_POINTS,
    TB_KERNEL_KEEP_CONTACTS,
    TB_KERNEL_APPLY_FORCES,
    TB_KERNEL_INTEGRATE, TB_KERNEL_STEP_END, TB_KERNEL_COUNT
} tb_kernel;

/// Host-side record of a body; what the GPU needs lives in the body store.
typedef struct tb_body_record {
    uint16_t generation;
    uint8_t alive;
    uint8_t type;           ///< tb_body_type
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
    uint32_t users;         ///< live bodies using the shape
    tb_hull* hull;          ///< hulls and boxes: the geometry the GPU gets (owned); else NULL
} tb_shape_record;

/// Every live hull's GPU data, packed (src/api/hulls.c).
typedef struct tb_hull_table {
    tb_buffer vector_buffer, topology_buffer;
    uint32_t vector_capacity, topology_capacity; ///< elements of the buffers and host images
    tb_gpu_vec4* vectors;        ///< host image of hull_vectors
    uint32_t* topology;          ///< host image of hull_topology
    uint32_t vectors_used, topology_used;
    int dirty;                   ///< a hull shape came or went: pack again
    int upload;                  ///< packed data not yet uploaded
} tb_hull_table;

/// Generic slot table bookkeeping: free slots are reused last-in first-out.
typedef struct tb_slots {
    uint32_t used;          ///< slots handed out at least once (high-water)
    uint32_t live;
    uint32_t* free;
    uint32_t free_count, capacity;
} tb_slots;

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
    tb_sim sim;
    tb_solver solver;
    VkPipeline kernels[TB_KERNEL_COUNT];
    tb_broadphase broadphase_kind;         ///< never TB_BROADPHASE_DEFAULT
    const tb_broadphase_ops* broadphase;
    void* broadphase_state;                ///< the broadphase's own (kernels, buffers)
    VkPipeline pair_check;                 ///< broadphase/pair_check, shared by all
    uint32_t body_set_version;             ///< bodies created and destroyed so far
    int step_built;              ///< the graph holds the current step (rounds, capacities)
    uint32_t colour_rounds;      ///< colouring rounds recorded (grows when a step needs more)
    uint32_t substeps, solver_iterations;
    float contact_margin, restitution_threshold;
    float contact_hertz, contact_damping_ratio, contact_push_speed;
    uint64_t gpu_steps;          ///< steps the GPU completed (its counters.state.y)
    uint64_t steps_redone;       ///< steps run again after a buffer grew
    tb_buffer params_buffer;
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
    tb_hull_table hulls;
    tb_plugins plugins;
    uint32_t hull_shapes;        ///< live TB_SHAPE_HULL shapes: the step records the hull pass

    uint64_t buffer_generation;  ///< bumped whenever a GPU buffer is replaced
    uint64_t steps, submits;
    double stage_ms[TB_MAX_STAGES];
    double gpu_ms;
};

/* slots.c */
tb_result tb_slots_take(tb_slots* slots, uint32_t* out);
void tb_slots_give(tb_slots* slots, uint32_t slot);
void tb_slots_free(tb_slots* slots);

/* world.c */
/// tb_world_create with extra device options (extensions) for Vulkan embedders.
tb_result tb_world_create_with(const tb_world_def* def, const tb_gpu_options* extra,
                               tb_world** out);
/// Upload what the host wrote and the GPU has not seen yet.
tb_result tb_world_flush(tb_world* w);
/// Give the GPU shape table room for every shape slot (may replace its buffer).
tb_result tb_world_prepare_shapes(tb_world* w);
/// Bring the arrays in `mask` of the body mirror up to date (uploading first what is dirty).
tb_result tb_world_fetch(tb_world* w, uint32_t mask);
/// Make room for `slots` body slots on the GPU.
tb_result tb_world_reserve_bodies(tb_world* w, uint32_t slots);

/* hulls.c */
tb_result tb_hull_table_init(tb_world* w);
void tb_hull_table_destroy(tb_world* w);
/// Pack the hulls again if shapes changed (may replace the buffers).
tb_result tb_hull_table_prepare(tb_world* w);
VkDeviceSize tb_hull_table_upload_bytes(const tb_world* w);
void tb_hull_table_record_upload(tb_world* w, tb_transfer* transfer);

/// The soft contact of a substep h (tb_gpu_params.soft), `scale` times as stiff.
tb_gpu_vec4 tb_contact_softness(const tb_world* w, float h, double scale);

/* step.c */
tb_result tb_step_kernels_create(tb_world* w);
void tb_step_kernels_destroy(tb_world* w);
/// Build the step graph for the current capacities and colouring rounds.
tb_result tb_step_build(tb_world* w);

/* shader_dir.c */
/// TUMBLE_SHADER_DIR, when set, as tb_world_set_shader_dir (before any pipeline exists).
tb_result tb_world_shader_dir_from_env(tb_world* w);
/// Between steps: swap in the shaders written since the last step (hot-reload).
void tb_world_reload_shaders(tb_world* w);

/* checks.c */
int tb_finite3(tb_vec3 v);
int tb_finite_quat(tb_quat q);
/// Check a rotation and return it normalised; fails beyond the 1e-3 tolerance.
tb_result tb_check_rotation(tb_diag* diag, tb_quat q, tb_quat* out, const char* what);

/* body.c / shape.c lookups: the record of a valid id, or an error and NULL. */
tb_body_record* tb_body_lookup(tb_world* w, tb_body_id id, uint32_t* slot, tb_result* r);
tb_shape_record* tb_shape_lookup(tb_world* w, tb_shape_id id, uint32_t* slot, tb_result* r);
/* contacts.c */
/// The id of the live body in a slot; the null id for a dead or unused slot.
tb_body_id tb_body_id_of_slot(const tb_world* w, uint32_t slot);

/// Free a shape's hull geometry, if it has any.
void tb_shape_release_hull(tb_shape_record* s);

#endif
