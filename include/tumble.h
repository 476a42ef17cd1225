/* Tumble: a rigid-body physics engine whose whole step runs on the GPU as Vulkan compute.
 *
 * This is the only header users include. Plain C99, no Vulkan types.
 *
 * Conventions
 * - Units are SI: metres, kilograms, seconds, radians. Gravity defaults to (0, -9.81, 0).
 * - Every fallible call returns tb_result; on failure the world is unchanged and
 *   tb_world_last_error() holds a sentence that says what was wrong (the message is also
 *   passed to the log callback at TB_LOG_INFO). NULL pointers where an object is required
 *   are rejected with TB_ERROR_INVALID_ARGUMENT; output pointers of getters may be NULL.
 * - Ids are small values (index + generation). A destroyed body's id becomes stale and is
 *   rejected with TB_ERROR_STALE_ID, never dereferenced. The zero id is null.
 * - Definitions are initialised with their tb_default_*_def() function and then edited.
 *   A def that did not come from its default function is rejected.
 * - Threads: a world is used from one thread at a time. Different worlds are independent.
 */
#ifndef TUMBLE_H
#define TUMBLE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(TB_BUILDING_LIBRARY) && defined(__GNUC__)
#define TB_API __attribute__((visibility("default")))
#else
#define TB_API
#endif

/* ---------------------------------------------------------------------------------------
 * Version: MAJOR changes break the ABI (the shared library's soname is libtumble.so.MAJOR),
 * MINOR adds to it, PATCH fixes. The Makefile reads these lines.
 */
#define TB_VERSION_MAJOR 0
#define TB_VERSION_MINOR 1
#define TB_VERSION_PATCH 0
/// A version as one number: major << 22 | minor << 12 | patch (Vulkan's packing).
#define TB_MAKE_VERSION(major, minor, patch) \
    (((uint32_t)(major) << 22) | ((uint32_t)(minor) << 12) | (uint32_t)(patch))
/// The version this header belongs to.
#define TB_VERSION TB_MAKE_VERSION(TB_VERSION_MAJOR, TB_VERSION_MINOR, TB_VERSION_PATCH)

/* ---------------------------------------------------------------------------------------
 * Basic types
 */

typedef struct tb_vec3 { float x, y, z; } tb_vec3;

/// Rotation quaternion (x, y, z, w); w is the scalar part. Identity is (0, 0, 0, 1).
typedef struct tb_quat { float x, y, z, w; } tb_quat;

/// Result codes. Pinned to 32 bits; new codes are only ever appended.
typedef enum tb_result {
    TB_OK = 0,
    TB_ERROR_INVALID_ARGUMENT = 1, ///< NaN/inf, negative mass, zero size, dt <= 0, bad def
    TB_ERROR_INVALID_ID = 2,       ///< null id, or an id that never existed in this world
    TB_ERROR_STALE_ID = 3,         ///< id of a destroyed body or shape
    TB_ERROR_CAPACITY = 4,         ///< a limit set in tb_world_def would be exceeded
    TB_ERROR_OUT_OF_MEMORY = 5,    ///< host or device memory could not be allocated
    TB_ERROR_NO_DEVICE = 6,        ///< no Vulkan device (or none matching TUMBLE_DEVICE)
    TB_ERROR_DEVICE = 7,           ///< a Vulkan call failed (device lost, driver error)
    TB_ERROR_IN_USE = 8,           ///< the object is still referenced (a shape used by bodies)
    TB_RESULT_FORCE_32 = 0x7fffffff
} tb_result;

/// Sentence naming a result code ("invalid argument", ...). Never NULL.
TB_API const char* tb_result_string(tb_result result);

/// The version of the library running (TB_MAKE_VERSION packing), which may be newer than
/// the header a program was built with (TB_VERSION) within the same major version.
TB_API uint32_t tb_version(void);

typedef struct tb_world tb_world;

/// Body id: 1-based slot index, owning world's serial, generation of the slot.
typedef struct tb_body_id { uint32_t index1; uint16_t world; uint16_t generation; } tb_body_id;
/// Shape id, same scheme as tb_body_id.
typedef struct tb_shape_id { uint32_t index1; uint16_t world; uint16_t generation; } tb_shape_id;

/// Joint id, same scheme as tb_body_id.
typedef struct tb_joint_id { uint32_t index1; uint16_t world; uint16_t generation; } tb_joint_id;

static const tb_body_id tb_null_body = { 0, 0, 0 };
static const tb_joint_id tb_null_joint = { 0, 0, 0 };
static const tb_shape_id tb_null_shape = { 0, 0, 0 };

/* ---------------------------------------------------------------------------------------
 * World
 */

typedef enum tb_log_level {
    TB_LOG_DEBUG = 0, TB_LOG_INFO = 1, TB_LOG_WARNING = 2, TB_LOG_ERROR = 3,
    TB_LOG_LEVEL_FORCE_32 = 0x7fffffff
} tb_log_level;

/// Log sink. Called from the thread that made the call which logs. `message` is one line.
typedef void tb_log_fn(void* user, tb_log_level level, const char* message);

/// How the step finds the pairs of bodies whose boxes overlap (the broadphase). Every one
/// finds exactly the same pairs; they differ in speed, which depends on the scene (see the
/// README's performance section).
typedef enum tb_broadphase {
    /// The TUMBLE_BROADPHASE environment variable ("grid", "sap", "lbvh" or "isap") when it
    /// is set, else the library's choice for most scenes (now the LBVH).
    TB_BROADPHASE_DEFAULT = 0,
    /// Uniform grid of cells as wide as the largest dynamic body: bodies of similar size.
    TB_BROADPHASE_GRID = 1,
    /// Sort and sweep along the axis of largest variance: any mix of sizes.
    TB_BROADPHASE_SAP = 2,
    /// Linear bounding volume hierarchy (Morton order, rebuilt every step): huge, sparse or
    /// clustered worlds.
    TB_BROADPHASE_LBVH = 3,
    /// Incremental sort and sweep on three axes: keeps last step's order and pairs and
    /// finds what changed, for scenes that move little per step.
    TB_BROADPHASE_ISAP = 4,
    TB_BROADPHASE_FORCE_32 = 0x7fffffff
} tb_broadphase;

/// The broadphase's name ("grid", "sap", "lbvh", "isap"); "default" for the default and
/// NULL for a value that names none.
TB_API const char* tb_broadphase_name(tb_broadphase broadphase);

/// What the API takes, at most: larger values are refused with a sentence and change
/// nothing. Far beyond them float loses the digits a step needs, or products overflow, and
/// a body turned into NaN a few steps later while every step returned TB_OK.
#define TB_MAX_DT 1.0f              ///< s: dt of tb_world_step
#define TB_MAX_GRAVITY 1000.0f      ///< m/s^2: |gravity| (about 100 g)
#define TB_MAX_GRAVITY_SCALE 100.0f ///< |tb_body_def.gravity_scale|
#define TB_MAX_SPEED 1000.0f        ///< m/s: |linear velocity| given to a body
#define TB_MAX_REUSE_ANGLE 0.78539816f ///< rad: tb_world_set_contact_reuse's angle (pi / 4)
#define TB_MAX_SPIN 1000.0f         ///< rad/s: |angular velocity| given to a body
#define TB_MAX_COORDINATE 1.0e6f    ///< m: each coordinate of a position, a plane's offset,
                                    ///< a sphere's radius, a box's half extent
#define TB_MAX_INERTIA_RATIO 1.0e6f ///< largest over smallest principal moment given in a
                                    ///< body def (a shape's own may be further apart)

typedef struct tb_world_def {
    /// Gravity acceleration, m/s^2. Default (0, -9.81, 0).
    tb_vec3 gravity;
    /// Bodies the GPU buffers hold at first; they grow (doubling) as bodies are added.
    /// Growth re-records the step's command buffer, so set this near the expected count.
    /// Default 1024.
    uint32_t initial_body_capacity;
    /// Hard limit on live bodies; creating more fails with TB_ERROR_CAPACITY.
    /// 0 means the default, 16777216 (2^24).
    uint32_t max_bodies;
    /// Hard limit on live shapes. 0 means the default, 1048576.
    uint32_t max_shapes;
    /// Largest rotation a body may make in one step, radians. Faster spins are clamped for
    /// the orientation update (their stored angular velocity is kept). Default pi/4.
    float max_rotation_per_step;
    /// Contact pairs the GPU buffers hold at first (per step); they grow when a step finds
    /// more (the step is then run again, see tb_world_stats.steps_redone). 0: 4 per body
    /// of initial_body_capacity.
    uint32_t initial_pair_capacity;
    /// Substeps per step. The soft step (TB_SOLVER_SOFT_STEP): each applies gravity,
    /// warm-starts, solves, moves the bodies and relaxes, as Box2D v3 does it; more
    /// substeps make tall stacks and heavy-on-light contacts stiffer (see contact_hertz).
    /// The block solver (the default) predicts each body's free motion in this many pieces
    /// (a projectile's arc is the same with either solver). Default 6. In [1, 64].
    uint32_t substeps;
    /// Velocity iterations of the soft step per substep. Default 1. In [1, 1000]. (The
    /// block solver's sweeps are tb_world_set_solver's `iterations`.)
    uint32_t solver_iterations;
    /// Contact margin, m: shapes closer than this get (speculative) contact points, so a
    /// resting contact does not flicker on and off. Default 0.02. >= 0.
    float contact_margin;
    /// Approach speed, m/s, above which restitution applies; slower impacts do not bounce,
    /// so resting bodies settle. Default 0.5. >= 0.
    float restitution_threshold;
    /// Stiffness of the soft step's contacts, Hz (the block solver's contacts are hard; it
    /// ignores this and the next two settings): penetration is pushed out like a damped
    /// spring of this frequency, twice as stiff against static bodies. A load compresses a
    /// contact by about g / (2 pi hertz)^2 per unit of load-to-contact mass ratio: at 60 Hz
    /// a column of ten 1 m boxes settles 6 mm, at 30 Hz 28 mm. Stiffer needs more
    /// substeps: it is capped at a quarter of the substep rate, and above about a sixth a
    /// thin wall of boxes starts to rock. Default 60 (a sixth of the rate at 60 steps/s and
    /// 6 substeps). 0: the cap.
    float contact_hertz;
    /// Damping ratio of that spring; above 1 it is overdamped (no bounce from pushing out).
    /// Default 10. >= 0.
    float contact_damping_ratio;
    /// Fastest speed, m/s, at which penetration is pushed out. In a deep pile the push of
    /// each layer adds up (one relax sweep cannot take it all back), so a faster push can
    /// launch the top of the pile: a million-box pile erupts at 3 m/s, not at 1. Default 1.
    /// >= 0.
    float contact_push_speed;
    /// Device choice: an index into the Vulkan device list, or a case-insensitive substring
    /// of the device name. NULL: the TUMBLE_DEVICE environment variable, else a discrete
    /// GPU, else any GPU, else a CPU device (lavapipe).
    const char* device;
    /// Enable the Khronos validation layer (with synchronization validation). Its messages
    /// go to the log callback and are counted in tb_world_stats.validation_messages.
    /// Also enabled by the environment variable TUMBLE_VALIDATION=1.
    int validation;
    /// Optional file for the Vulkan pipeline cache: read at creation when its header matches
    /// this device, written at destruction. NULL: no file.
    const char* pipeline_cache_path;
    /// Log callback and its user pointer. NULL: warnings and errors go to stderr.
    tb_log_fn* log;
    void* log_user;
    /// The broadphase (see tb_broadphase). Default TB_BROADPHASE_DEFAULT.
    tb_broadphase broadphase;
    /// Internal: set by tb_default_world_def(). Do not touch.
    int32_t internal_cookie;
} tb_world_def;

TB_API tb_world_def tb_default_world_def(void);

/// Create a world on a Vulkan device. On failure *out is NULL and
/// tb_world_last_error(NULL) says why.
TB_API tb_result tb_world_create(const tb_world_def* def, tb_world** out);

/// Destroy the world and everything in it. NULL is ignored. From a plugin's contact
/// callback (within a step) the call is refused: an error is logged and the world kept.
TB_API void tb_world_destroy(tb_world* world);

/// Last error message for this world, or, with NULL, of the last failed tb_world_create
/// on this thread. Empty string when there was none.
TB_API const char* tb_world_last_error(const tb_world* world);

/// Gravity, m/s^2. Takes effect at the next step; does not re-record anything.
TB_API tb_result tb_world_set_gravity(tb_world* world, tb_vec3 gravity);
TB_API tb_vec3 tb_world_get_gravity(const tb_world* world);

/// The contact solver a world steps with (tb_world_set_solver). Pinned to 32 bits.
typedef enum tb_solver_kind {
    /// The soft step: tb_world_def's substeps, each with `solver_iterations` sweeps over
    /// contacts that are stiff damped springs (contact_hertz). Smooth and cheap, but a
    /// load sinks into its springs: a column of 20 boxes sags 27 mm, and deep piles and
    /// tall pyramids can lean and fall.
    TB_SOLVER_SOFT_STEP = 0,
    /// The block solver (the default): hard contacts reached by an augmented Lagrangian;
    /// each sweep moves every dynamic body by one 6x6 Newton step on its inertia and its
    /// contacts (bodies of one colour at once), `iterations` sweeps a step (default 30).
    /// Columns, deep piles and pyramids of 5,000 boxes stand (a column of 20 sinks 4 mm)
    /// at about the soft step's cost on a GPU. It predicts free motion in tb_world_def's
    /// substeps and ignores solver_iterations and the contact spring settings.
    TB_SOLVER_BLOCK = 1,
    TB_SOLVER_FORCE_32 = 0x7fffffff
} tb_solver_kind;

/// Choose the contact solver, before the world's first step (after it: an error, and
/// nothing changes). A world starts with the block solver; the environment variable
/// TUMBLE_SOLVER=soft gives it the soft step at creation instead. `iterations`: the block
/// solver's sweeps a step, in [1, 1000], 0 for its default (30); the soft step takes its
/// substeps and iterations from tb_world_def and ignores it.
TB_API tb_result tb_world_set_solver(tb_world* world, tb_solver_kind solver,
                                     uint32_t iterations);
/// The world's contact solver, and the block solver's sweeps a step in *iterations (may be
/// NULL). A NULL world gives the default, TB_SOLVER_BLOCK.
TB_API tb_solver_kind tb_world_get_solver(const tb_world* world, uint32_t* iterations);

/// Contact reuse: a pair whose bodies have moved less than `distance` (m) and turned less
/// than `angle` (radians) against each other since its contact points were last found keeps
/// those points, measured again at the bodies' poses now (each point's separation, on round
/// surfaces where they touch now), instead of running the narrowphase again; beyond either
/// bound the narrowphase finds them anew. In a pile at rest most pairs take this path.
/// Applies to pairs of capsules, cylinders and cones with any whole convex body or plane
/// (not compound children or mesh triangles). Defaults 0.001 m and 2 degrees (0.0349 rad);
/// 0 for either turns reuse off. Both finite, >= 0, angle at most pi / 4; settable between
/// steps.
#define TB_DEFAULT_REUSE_DISTANCE 0.001f   ///< m
#define TB_DEFAULT_REUSE_ANGLE 0.034906585f ///< rad (2 degrees)
TB_API tb_result tb_world_set_contact_reuse(tb_world* world, float distance, float angle);
/// The world's contact reuse bounds (either pointer may be NULL).
TB_API void tb_world_get_contact_reuse(const tb_world* world, float* distance, float* angle);

/// Advance the simulation by dt seconds (usually 1/60). One queue submission; returns when
/// the GPU has finished the step. dt must be finite and > 0.
TB_API tb_result tb_world_step(tb_world* world, float dt);

/// Advance n steps of dt, in one queue submission for every 4096 of them (one for n <= 4096).
/// Equal to n calls of tb_world_step;
/// n = 0 does nothing and returns TB_OK.
TB_API tb_result tb_world_step_n(tb_world* world, float dt, uint32_t n);

/// Snapshots, for rollback, resets and debugging: everything the world's next step depends
/// on (bodies and their slots, last step's pairs and manifolds with their warm-start
/// impulses, the step counters, gravity), as bytes of this library version and machine.
/// tb_world_restore puts them back into the world they came from, or into another world
/// made with the same def, solver and broadphase whose shapes were made alike and in the
/// same order; it then continues bit for bit as the original did from the snapshot (with
/// isap, where the world's body capacity differs from the snapshot's, the first step
/// searches from scratch: the same pairs, perhaps in another order). Shapes and plugins
/// are not in a snapshot. Ids of bodies made after the snapshot are stale after a restore
/// (a later body may reuse such an id); user_data is restored as the pointer it was.
/// tb_world_snapshot writes at most `capacity` bytes to `out` and the snapshot's size to
/// *size; `out` NULL (capacity 0) asks for the size only. Fails with TB_ERROR_CAPACITY,
/// writing the size, when it does not fit.
TB_API tb_result tb_world_snapshot(tb_world* world, void* out, size_t capacity, size_t* size);
/// Restore a snapshot (see tb_world_snapshot). Bytes that are not a whole snapshot of this
/// build, damaged ones, and a world whose shapes, solver or broadphase differ are refused
/// with a sentence, and nothing changes.
TB_API tb_result tb_world_restore(tb_world* world, const void* snapshot, size_t size);

typedef struct tb_device_info {
    char name[256];           ///< e.g. "NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)"
    char driver[256];         ///< driver name and version text
    uint32_t vendor_id;
    uint32_t device_id;
    uint32_t api_version;     ///< VK_MAKE_API_VERSION encoding
    uint32_t subgroup_size;   ///< 8 on lavapipe, 32 on NVIDIA, 64 on AMD
    int is_cpu;               ///< 1 for a CPU implementation (lavapipe)
} tb_device_info;

TB_API tb_result tb_world_device_info(const tb_world* world, tb_device_info* out);

/// Stage timings and counts, as of the last completed step.
#define TB_MAX_STAGES 32
typedef struct tb_stage_time {
    const char* name;   ///< stage name, equal to its shader's name ("integrate/integrate")
    double ms;          ///< GPU time of the stage in the last step, milliseconds
} tb_stage_time;

typedef struct tb_world_stats {
    uint32_t body_count;          ///< live bodies
    uint32_t body_capacity;       ///< bodies the GPU buffers hold now
    uint32_t shape_count;         ///< live shapes
    uint64_t steps;               ///< steps taken since creation
    uint64_t submits;             ///< queue submissions of step work since creation
    uint64_t records;             ///< times the step command buffer was recorded
    uint64_t buffer_growths;      ///< times a GPU buffer was grown
    uint64_t validation_messages; ///< validation layer messages (warnings and errors)
    double gpu_ms;                ///< GPU time of the last step, first to last stage
    uint32_t pair_count;          ///< broadphase pairs in the last step
    uint32_t pair_capacity;       ///< pairs the GPU buffers hold per step
    uint32_t contact_count;       ///< contact points in the last step
    uint32_t colour_count;        ///< constraint colours (solver dispatches per iteration)
    uint32_t batch_count;         ///< subgroup-wide constraint batches of the last step
    uint32_t colour_rounds;       ///< colouring rounds recorded in the step
    uint64_t steps_redone;        ///< steps run again after a GPU buffer grew
    const char* broadphase;       ///< the broadphase in use: "grid", "sap", "lbvh" or "isap"
    uint32_t stage_count;         ///< the step's stages below, in order; none before the first step
    tb_stage_time stages[TB_MAX_STAGES];
} tb_world_stats;

TB_API tb_result tb_world_get_stats(const tb_world* world, tb_world_stats* out);

/* ---------------------------------------------------------------------------------------
 * Shapes
 *
 * A shape is geometry plus material, shared by any number of bodies. Its local frame is the
 * body's frame: the body's position is the shape's origin.
 */

typedef enum tb_shape_type {
    TB_SHAPE_SPHERE = 0,
    TB_SHAPE_BOX = 1,
    TB_SHAPE_PLANE = 2,
    TB_SHAPE_HULL = 3,
    TB_SHAPE_MESH = 4,
    TB_SHAPE_HEIGHTFIELD = 5,
    TB_SHAPE_COMPOUND = 6,
    TB_SHAPE_CAPSULE = 7,
    TB_SHAPE_CYLINDER = 8,
    TB_SHAPE_CONE = 9,
    TB_SHAPE_TYPE_FORCE_32 = 0x7fffffff
} tb_shape_type;

typedef struct tb_shape_def {
    /// Mass per volume, kg/m^3; used when a body gives no mass. Default 1000 (water).
    float density;
    /// Coulomb friction coefficient, >= 0. Default 0.6. Two touching shapes slide with
    /// the geometric mean sqrt(friction_a * friction_b): ice on anything stays slippery.
    float friction;
    /// Restitution (bounciness) in [0, 1]. Default 0. Two touching shapes bounce with the
    /// larger of their restitutions, for impacts faster than the world's
    /// restitution_threshold.
    float restitution;
    /// Internal: set by tb_default_shape_def(). Do not touch.
    int32_t internal_cookie;
} tb_shape_def;

TB_API tb_shape_def tb_default_shape_def(void);

/// Sphere of the given radius (> 0) centred on the body's origin.
TB_API tb_result tb_shape_create_sphere(tb_world* world, const tb_shape_def* def, float radius,
                                        tb_shape_id* out);
/// Box with the given half extents (each > 0) centred on the body's origin.
TB_API tb_result tb_shape_create_box(tb_world* world, const tb_shape_def* def,
                                     tb_vec3 half_extents, tb_shape_id* out);
/// Half-space { p : dot(normal, p) <= offset } in body coordinates; its surface is the plane.
/// normal must be non-zero (it is normalised). Planes have no volume: only static bodies
/// may use them.
TB_API tb_result tb_shape_create_plane(tb_world* world, const tb_shape_def* def, tb_vec3 normal,
                                       float offset, tb_shape_id* out);
/// Capsule: the points within `radius` of the segment from (0, -half_height, 0) to
/// (0, half_height, 0) of the body frame (a cylinder of length 2 half_height capped by two
/// half spheres). radius > 0, half_height >= 0 (0 is a sphere), both finite and at most 1e6.
TB_API tb_result tb_shape_create_capsule(tb_world* world, const tb_shape_def* def, float radius,
                                         float half_height, tb_shape_id* out);
/// Cylinder of the given radius whose axis is the body's y axis, from y = -half_height to
/// y = half_height. radius > 0 and half_height > 0, finite and at most 1e6.
TB_API tb_result tb_shape_create_cylinder(tb_world* world, const tb_shape_def* def, float radius,
                                          float half_height, tb_shape_id* out);
/// Cone of the given base radius and height 2 half_height along the body's y axis. Like a
/// hull, a cone body turns about its centre of mass, which is its body origin: the base
/// circle lies at y = -half_height / 2 and the apex at y = 3 half_height / 2. radius > 0
/// and half_height > 0, finite and at most 1e6.
TB_API tb_result tb_shape_create_cone(tb_world* world, const tb_shape_def* def, float radius,
                                      float half_height, tb_shape_id* out);
/// Convex hull of `count` points (xyz in m, in the frame the caller gives them). Duplicate
/// and (nearly) coplanar points are fine; coplanar faces merge into polygons. Fails with
/// TB_ERROR_INVALID_ARGUMENT on non-finite points or when the points span no volume (fewer
/// than 4 points off one plane), and when the hull exceeds the GPU limits (256 vertices,
/// 256 faces, 32 vertices on one face).
///
/// A hull body turns about its centre of mass. Its body frame is the hull's principal
/// frame: origin at the centre of mass, axes along the principal axes of inertia, so poses
/// set and read through the API are of that frame. tb_shape_get_hull_info says where that
/// frame lies among the input points.
TB_API tb_result tb_shape_create_hull(tb_world* world, const tb_shape_def* def,
                                      const tb_vec3* points, uint32_t count, tb_shape_id* out);

/// Triangle mesh: `triangle_count` triangles, three indices each into `vertices` (xyz in m,
/// body frame). A triangle collides on its front, the side from which its vertices run
/// counter-clockwise; a body behind it passes through (one-sided). Triangles that share an
/// edge must share its two vertex indices: adjacency is by index, and where neighbours are
/// flat or fold concavely their shared edge is inactive, so bodies slide across it without
/// catching. Zero-area triangles are kept but never touch anything. Meshes are for static
/// bodies only (a dynamic body is refused). Fails with TB_ERROR_INVALID_ARGUMENT on NULL
/// arrays, no triangles, more than 16,777,216 triangles, an index out of range, a vertex
/// that is not finite or farther than 1e6 m from the origin, or no triangle with an area.
/// The mesh's geometry goes to the GPU with the next step.
TB_API tb_result tb_shape_create_mesh(tb_world* world, const tb_shape_def* def,
                                      const tb_vec3* vertices, uint32_t vertex_count,
                                      const uint32_t* indices, uint32_t triangle_count,
                                      tb_shape_id* out);

/// Heightfield: a grid of count_x x count_z heights (y, m), row by row along x: sample
/// (i, k) is heights[k * count_x + i], at x = (i - (count_x - 1) / 2) * cell_x and
/// z = (k - (count_z - 1) / 2) * cell_z in the body frame (the grid is centred on the
/// body's origin). Each cell is two triangles facing +y, colliding from above only (as a
/// mesh's: one-sided, active edges on creases and borders, none inside flat or concave
/// ground). `holes` may be NULL, or hold (count_x - 1) * (count_z - 1) bytes, row by row
/// along x: a nonzero byte makes that cell a hole. For static bodies only. Fails with
/// TB_ERROR_INVALID_ARGUMENT on NULL heights, fewer than 2 or more than 32,768 samples
/// along a side, a cell size not finite and > 0, a grid wider than 2e6 m, a height not
/// finite or beyond 1e6 m, or every cell a hole.
TB_API tb_result tb_shape_create_heightfield(tb_world* world, const tb_shape_def* def,
                                             const float* heights, uint32_t count_x,
                                             uint32_t count_z, float cell_x, float cell_z,
                                             const uint8_t* holes, tb_shape_id* out);

/// A child of a compound: a sphere, box or hull shape of the same world, placed by a pose in
/// the frame the caller builds the compound in.
typedef struct tb_compound_child {
    tb_shape_id shape;
    tb_vec3 position;   ///< where the child's origin lies
    tb_quat rotation;   ///< the child's frame: a unit quaternion (length 1 within 1e-3)
} tb_compound_child;

/// Compound: a rigid union of 1 to 64 convex children (spheres, boxes, hulls, capsules,
/// cylinders, cones). Each child
/// keeps its own density, friction and restitution; the compound's mass, centre of mass and
/// inertia are composed from them (parallel axis theorem). Like a hull body, a compound body
/// turns about its centre of mass: its body frame is the composed principal frame, and
/// tb_shape_get_compound_info says where that frame lies in the caller's frame. Pairs with
/// other bodies are found and solved per child (and per triangle against meshes), each
/// child pair with its own manifold and warm start. The children stay in use while the
/// compound lives (tb_shape_destroy refuses them). Fails with TB_ERROR_INVALID_ARGUMENT on
/// NULL children, no or more than 64 children, a child that is not convex (a sphere, box,
/// hull, capsule, cylinder or cone), a
/// position that is not finite or farther than 1e6 m, or a rotation that is not a unit
/// quaternion; with
/// TB_ERROR_INVALID_ID or TB_ERROR_STALE_ID on a child id that names no live shape.
TB_API tb_result tb_shape_create_compound(tb_world* world, const tb_compound_child* children,
                                          uint32_t count, tb_shape_id* out);

/// What a compound became.
typedef struct tb_compound_info {
    uint32_t child_count;
    float volume;             ///< m^3, the children's sum
    float mass_per_volume;    ///< kg/m^3: the children's mass over their volume
    tb_vec3 center_of_mass;   ///< in the frame the children were given in
    tb_quat principal_axes;   ///< rotation from the body frame to the children's frame
    tb_vec3 unit_inertia;     ///< principal moments of inertia per kg, about the body axes
} tb_compound_info;

TB_API tb_result tb_shape_get_compound_info(const tb_world* world, tb_shape_id shape,
                                            tb_compound_info* out);
/// A compound's children with their poses in its body frame: writes at most `capacity` to
/// `out` (may be NULL with capacity 0) and the child count to *count.
TB_API tb_result tb_shape_get_compound_children(const tb_world* world, tb_shape_id shape,
                                                tb_compound_child* out, uint32_t capacity,
                                                uint32_t* count);

/// What a mesh became.
typedef struct tb_mesh_info {
    uint32_t vertex_count, triangle_count;
    uint32_t degenerate_count;   ///< triangles of zero area (they touch nothing)
    uint32_t active_edge_count;  ///< triangle edges a body may touch with their own normal
    tb_vec3 aabb_min, aabb_max;  ///< the mesh's box, body frame
} tb_mesh_info;

TB_API tb_result tb_shape_get_mesh_info(const tb_world* world, tb_shape_id shape,
                                        tb_mesh_info* out);
/// A mesh's geometry as it was given: writes at most `vertex_capacity` vertices and
/// `triangle_capacity` triangles (three indices each) to the arrays (either may be NULL with
/// capacity 0), and the full counts to *vertex_count and *triangle_count.
TB_API tb_result tb_shape_get_mesh_geometry(const tb_world* world, tb_shape_id shape,
                                            tb_vec3* vertices, uint32_t vertex_capacity,
                                            uint32_t* indices, uint32_t triangle_capacity,
                                            uint32_t* vertex_count, uint32_t* triangle_count);

/// A sphere's radius and a box's half extents, as created.
TB_API tb_result tb_shape_get_sphere_radius(const tb_world* world, tb_shape_id shape, float* out);
TB_API tb_result tb_shape_get_box_half_extents(const tb_world* world, tb_shape_id shape,
                                               tb_vec3* out);

/// A capsule's, cylinder's or cone's radius and half height, as created.
TB_API tb_result tb_shape_get_round_size(const tb_world* world, tb_shape_id shape, float* radius,
                                         float* half_height);

/// What a hull became.
typedef struct tb_hull_info {
    uint32_t vertex_count, face_count, edge_count;
    float volume;             ///< m^3
    tb_vec3 center_of_mass;   ///< in the frame of the input points
    tb_quat principal_axes;   ///< rotation from the body frame to the input points' frame
    tb_vec3 unit_inertia;     ///< principal moments of inertia per kg, about the body axes
} tb_hull_info;

TB_API tb_result tb_shape_get_hull_info(const tb_world* world, tb_shape_id shape,
                                        tb_hull_info* out);
/// Vertices of a hull in its body frame: writes at most `capacity` to `out` (may be NULL
/// with capacity 0) and the vertex count to *count.
TB_API tb_result tb_shape_get_hull_vertices(const tb_world* world, tb_shape_id shape,
                                            tb_vec3* out, uint32_t capacity, uint32_t* count);
/// Destroy a shape. Fails with TB_ERROR_IN_USE while a body uses it.
TB_API tb_result tb_shape_destroy(tb_world* world, tb_shape_id shape);
TB_API int tb_shape_is_valid(const tb_world* world, tb_shape_id shape);
TB_API tb_result tb_shape_get_type(const tb_world* world, tb_shape_id shape, tb_shape_type* out);
/// Ids of live shapes in slot order (a shape's slot is index1 - 1, the index the GPU shape
/// table and tb_vulkan_bodies use); returns how many were written (at most `capacity`).
TB_API uint32_t tb_world_shape_ids(const tb_world* world, tb_shape_id* out, uint32_t capacity);

/* ---------------------------------------------------------------------------------------
 * Distance queries
 */

/// How a distance query measures the depth where the shapes' cores overlap.
typedef enum tb_penetration {
    /// EPA: the accurate one on the measured pairs (docs/shapes.md), so the default.
    TB_PENETRATION_DEFAULT = 0,
    /// The expanding polytope algorithm: the least overlap over all directions, to within
    /// the polytope it builds (its depth is at most the true one).
    TB_PENETRATION_EPA = 1,
    /// Minkowski portal refinement: the overlap along the direction in which the ray from
    /// the centre difference through the origin leaves the shapes' Minkowski difference. No
    /// polytope is kept; it is exact where the line between the centres meets the surface
    /// at right angles (a ball, a face met head on) and deeper than the true depth where it
    /// does not.
    TB_PENETRATION_MPR = 2,
    TB_PENETRATION_FORCE_32 = 0x7fffffff
} tb_penetration;

/// Two convex shapes (spheres, boxes, hulls, capsules, cylinders, cones) of the world, each
/// placed by a pose of its body frame (no body is needed).
typedef struct tb_distance_query {
    tb_shape_id a, b;
    tb_vec3 position_a;
    tb_quat rotation_a;     ///< unit within 1e-3 (then normalised)
    tb_vec3 position_b;
    tb_quat rotation_b;
    tb_penetration penetration;   ///< the depth's method; 0 (zero-initialised) the default
} tb_distance_query;

typedef enum tb_distance_status {
    TB_DISTANCE_SEPARATED = 0,   ///< apart, or touching through a sphere's or capsule's radius
    TB_DISTANCE_OVERLAP = 1,     ///< the shapes' cores overlap: distance is minus the depth
    TB_DISTANCE_LIMIT = 2,       ///< GJK stopped at its iteration limit with its best answer
    TB_DISTANCE_FAILED = 3,      ///< overlapping, and EPA or MPR found no depth (degenerate)
    TB_DISTANCE_STATUS_FORCE_32 = 0x7fffffff
} tb_distance_status;

typedef struct tb_distance_result {
    float distance;          ///< m between the surfaces; negative: the depth of overlap
    tb_vec3 normal;          ///< unit, from a towards b (moving b along it parts them)
    tb_vec3 point_a;         ///< world point on a's surface: closest to b, or deepest in b
    tb_vec3 point_b;         ///< world point on b's surface
    uint32_t status;         ///< tb_distance_status
    uint32_t iterations;     ///< GJK iterations
} tb_distance_result;

/// Distances between `count` pairs of posed convex shapes, computed on the GPU (one thread a
/// query: GJK with the signed-volume sub-algorithm on the shapes' cores; where the cores
/// overlap, EPA or MPR as the query's `penetration` asks), written to out[0..count). Runs
/// between steps and changes nothing in the world. Fails with TB_ERROR_INVALID_ARGUMENT
/// (nothing run, nothing written) on NULL arrays with count > 0, a shape that is not convex,
/// a position that is not finite, a rotation that is not a unit quaternion, or an unknown
/// `penetration`; with TB_ERROR_INVALID_ID or TB_ERROR_STALE_ID on a shape id that names no
/// live shape. The error names the first bad query.
TB_API tb_result tb_world_query_distances(tb_world* world, const tb_distance_query* queries,
                                          uint32_t count, tb_distance_result* out);

/* ---------------------------------------------------------------------------------------
 * Bodies
 */

typedef enum tb_body_type {
    TB_BODY_STATIC = 0,  ///< never moves, infinite mass (mass 0 in Bullet's terms)
    TB_BODY_DYNAMIC = 1, ///< moved by gravity, forces, impulses and contacts
    TB_BODY_TYPE_FORCE_32 = 0x7fffffff
} tb_body_type;

typedef struct tb_body_def {
    /// Default TB_BODY_DYNAMIC.
    tb_body_type type;
    /// Required: the body's shape.
    tb_shape_id shape;
    /// Position of the body's origin in world space, m. Default origin.
    tb_vec3 position;
    /// Orientation. Must be unit length within 1e-3 (it is then normalised); further off is
    /// rejected. Default identity.
    tb_quat rotation;
    /// m/s, world frame. Default zero.
    tb_vec3 linear_velocity;
    /// rad/s, world frame. Default zero.
    tb_vec3 angular_velocity;
    /// kg. 0: from the shape's volume and density. Must not be negative. Ignored for static.
    float mass;
    /// Principal moments of inertia about the body's axes, kg m^2. All 0: from the shape
    /// (scaled to the mass). Otherwise each must be > 0.
    tb_vec3 inertia;
    /// Linear and angular damping rates, 1/s, >= 0: velocity is scaled by 1/(1 + dt*rate)
    /// each step. Default 0 (none).
    float linear_damping;
    float angular_damping;
    /// Multiplier on the world's gravity for this body. Default 1.
    float gravity_scale;
    /// Returned by tb_body_get_user_data. Default NULL.
    void* user_data;
    /// Internal: set by tb_default_body_def(). Do not touch.
    int32_t internal_cookie;
} tb_body_def;

TB_API tb_body_def tb_default_body_def(void);

/// Create one body. The body exists on the GPU from the next step on.
TB_API tb_result tb_body_create(tb_world* world, const tb_body_def* def, tb_body_id* out);

/// Create `count` bodies in one call (all or none: if any def is bad, none is created and
/// the error names the first bad index). out_ids receives count ids.
TB_API tb_result tb_body_create_many(tb_world* world, const tb_body_def* defs, uint32_t count,
                                     tb_body_id* out_ids);

TB_API tb_result tb_body_destroy(tb_world* world, tb_body_id body);
TB_API int tb_body_is_valid(const tb_world* world, tb_body_id body);

TB_API tb_result tb_body_set_pose(tb_world* world, tb_body_id body, tb_vec3 position,
                                  tb_quat rotation);
/// Either output may be NULL (as in tb_body_get_velocity and tb_body_get_mass).
TB_API tb_result tb_body_get_pose(tb_world* world, tb_body_id body, tb_vec3* position,
                                  tb_quat* rotation);
TB_API tb_result tb_body_set_velocity(tb_world* world, tb_body_id body, tb_vec3 linear,
                                      tb_vec3 angular);
TB_API tb_result tb_body_get_velocity(tb_world* world, tb_body_id body, tb_vec3* linear,
                                      tb_vec3* angular);
/// Apply an impulse (N s) at a world point; changes linear and angular velocity at once.
/// No effect on static bodies (returns TB_OK).
TB_API tb_result tb_body_apply_impulse(tb_world* world, tb_body_id body, tb_vec3 impulse,
                                       tb_vec3 world_point);
/// Mass (kg, 0 for static) and principal inertia (kg m^2) the body was given.
TB_API tb_result tb_body_get_mass(const tb_world* world, tb_body_id body, float* mass,
                                  tb_vec3* inertia);
TB_API tb_result tb_body_get_type(const tb_world* world, tb_body_id body, tb_body_type* out);
TB_API void* tb_body_get_user_data(const tb_world* world, tb_body_id body);

/// Read the poses of `count` bodies into caller arrays (either may be NULL). One GPU
/// read-back serves any number of reads until the next step.
TB_API tb_result tb_world_read_transforms(tb_world* world, const tb_body_id* ids,
                                          uint32_t count, tb_vec3* positions,
                                          tb_quat* rotations);

/// World-space AABBs of `count` bodies as the broadphase of the last step saw them: from
/// the poses at the start of that step (zero before the first step that saw the body). Either array may be NULL. Boxes and spheres get their
/// tight box; planes an unbounded one (half extent 1e18 on every axis).
TB_API tb_result tb_world_read_aabbs(tb_world* world, const tb_body_id* ids, uint32_t count,
                                     tb_vec3* mins, tb_vec3* maxs);

/// One contact point of the last step.
typedef struct tb_contact {
    tb_body_id a, b;          ///< the two bodies; the normal points from a to b
    tb_vec3 point;            ///< world point midway between the two surfaces
    tb_vec3 normal;           ///< unit normal, from a towards b
    float separation;         ///< m along the normal; negative when the shapes overlap
    float normal_impulse;     ///< N s the solver applied along the normal in the last step
    /// N s of friction over the last step, world frame: its last substep's times the
    /// substeps (friction is not summed substep by substep).
    tb_vec3 friction_impulse;
    uint32_t feature;         ///< which features touch; equal across steps for the same ones
} tb_contact;

/// Contact points of the last step, grouped by pair. Writes at most `capacity` contacts
/// to `out` (may be NULL with capacity 0) and the number that exist to *count.
TB_API tb_result tb_world_read_contacts(tb_world* world, tb_contact* out, uint32_t capacity,
                                        uint32_t* count);

/// Ids of live bodies in slot order; returns how many were written (at most `capacity`).
TB_API uint32_t tb_world_body_ids(const tb_world* world, tb_body_id* out, uint32_t capacity);

/// The guard: a dynamic body whose pose or velocity stops being finite in a step (a
/// plugin's stage wrote NaN, or the solve broke down) is isolated by that step. It keeps the
/// last finite pose it had, its velocities become zero, and it no longer moves or collides,
/// so its NaN reaches no other body; a warning names it in the log, and setting its pose or
/// velocity is refused. Destroy it to free its slot. Writes the ids of the live isolated
/// bodies in slot order to `out` (at most `capacity`; NULL with capacity 0) and returns how
/// many there are.
TB_API uint32_t tb_world_isolated_bodies(const tb_world* world, tb_body_id* out,
                                         uint32_t capacity);

/* ---------------------------------------------------------------------------------------
 * Joints
 *
 * A joint holds two bodies together: a point of each (the anchors) and, for most kinds, a
 * frame of each (an orientation in the body's frame whose x axis is a hinge's or slider's
 * axis). The block solver (the default) solves its rows in the same sweeps as the contacts,
 * as hard constraints reached by an augmented Lagrangian, so chains with heavy ends keep
 * their length; worlds that step with the soft step refuse joints. Destroying a body
 * destroys its joints.
 */
/// Most joints a world holds.
#define TB_MAX_JOINTS 2097152u

typedef enum tb_joint_kind {
    TB_JOINT_BALL = 1,     ///< spherical: the anchors meet; any rotation
    TB_JOINT_HINGE = 2,    ///< revolute: the anchors meet and the frames' x axes align;
                           ///< turning about the axis is free (limit, motor)
    TB_JOINT_FIXED = 3,    ///< weld: anchors and frames held together
    TB_JOINT_DISTANCE = 4, ///< the anchors keep `length` apart (a rod), or stay between
                           ///< lower and upper (a rope: limit on), or are pulled to `length`
                           ///< by a spring (spring on); any rotation
    TB_JOINT_SLIDER = 5,   ///< prismatic: frames held, the anchors move apart only along the
                           ///< frames' x axis (limit in m, motor in m/s)
    TB_JOINT_CONE_TWIST = 6, ///< the anchors meet; b's frame's x axis stays within
                           ///< `cone_angle` of a's (the swing), and b turns about it (the
                           ///< twist) within lower..upper rad when the limit is on: shoulders,
                           ///< hips, necks
    TB_JOINT_SIX_DOF = 7,  ///< each of six coordinates of b's frame in a's is free, limited
                           ///< or locked (`axes`): the offset of b's anchor from a's along a's
                           ///< frame's x, y and z axes (m), then the turn from a's frame to
                           ///< b's about those axes (rad: the components of its rotation
                           ///< vector, so a turn about one axis is that angle)
    TB_JOINT_KIND_FORCE_32 = 0x7fffffff
} tb_joint_kind;

/// What a 6-dof joint does with one of its coordinates.
typedef enum tb_joint_axis_mode {
    TB_JOINT_AXIS_LOCKED = 0,  ///< held at 0 (the default: a 6-dof joint starts as a weld)
    TB_JOINT_AXIS_FREE = 1,    ///< anything
    TB_JOINT_AXIS_LIMITED = 2, ///< within [lower, upper] (turns within [-pi, pi])
    TB_JOINT_AXIS_MODE_FORCE_32 = 0x7fffffff
} tb_joint_axis_mode;

/// One coordinate of a 6-dof joint.
typedef struct tb_joint_axis {
    tb_joint_axis_mode mode;
    float lower, upper;
} tb_joint_axis;

typedef struct tb_joint_def {
    /// Required.
    tb_joint_kind kind;
    /// Required, two different bodies of the world, at least one of them dynamic.
    tb_body_id body_a, body_b;
    /// The joint's point in each body's frame, m. Default origin (tb_joint_def_at sets
    /// them from a world point).
    tb_vec3 anchor_a, anchor_b;
    /// The joint's frame in each body's frame (unit quaternions within 1e-3, normalised);
    /// its x axis is the hinge's or slider's axis. Default identity.
    tb_quat frame_a, frame_b;
    /// Distance joints: the anchors' distance, m, >= 0. Default 1.
    float length;
    /// Limit (hinge and cone-twist's twist: rad, within [-pi, pi]; slider and distance: m),
    /// lower <= upper. Default off, 0 and 0.
    int32_t enable_limit;
    float lower, upper;
    /// Motor (hinges: target rad/s of b about the axis relative to a, most torque N m;
    /// sliders: m/s, N). Default off, 0 and 0.
    int32_t enable_motor;
    float motor_speed, max_motor_force;
    /// A spring, Hz (> 0) and damping ratio (>= 0), on the bodies' effective mass (or
    /// moment): distance joints pull to `length` with it instead of being a rod; hinges to
    /// the angle `spring_target` (rad, within [-pi, pi]) and sliders to the offset
    /// `spring_target` (m) along the axis, beside a limit and a motor if they have them.
    /// Default off, 1 Hz, 0, target 0.
    int32_t enable_spring;
    float spring_hertz, spring_damping_ratio, spring_target;
    /// Cone-twist joints: the largest angle between the frames' x axes, rad, in [0, pi].
    /// Default pi/4.
    float cone_angle;
    /// 6-dof joints: the three offsets along a's frame's axes, then the three turns about
    /// them. Default all locked.
    tb_joint_axis axes[6];
    /// A soft joint: what the kind holds (the anchors together, the frames aligned, a rod's
    /// length, a 6-dof joint's locked axes) is held by springs of this frequency, Hz, and
    /// damping ratio on the bodies' effective mass or moment instead of rigidly; limits
    /// stay hard. 0 Hz: rigid. Default 0 and 0.
    float constraint_hertz, constraint_damping_ratio;
    /// Whether the two bodies collide with each other. Default 0 (they do not).
    int32_t collide_connected;
    /// The joint breaks (stops holding; tb_joint_read_forces reports it) once the force
    /// (N) or torque (N m) it holds passes these. 0: never. Default 0.
    float break_force, break_torque;
    /// Returned by tb_joint_get_user_data. Default NULL.
    void* user_data;
    /// Internal: set by tb_default_joint_def(). Do not touch.
    int32_t internal_cookie;
} tb_joint_def;

TB_API tb_joint_def tb_default_joint_def(void);

/// Sets def's anchors to the world point `point` and its frames so that their x axes lie
/// along the world direction `axis` (non-zero; normalised), from the bodies' present poses.
TB_API tb_result tb_joint_def_at(tb_world* world, tb_joint_def* def, tb_vec3 point,
                                 tb_vec3 axis);

/// Create one joint; it holds from the next step on.
TB_API tb_result tb_joint_create(tb_world* world, const tb_joint_def* def, tb_joint_id* out);
/// Create `count` joints in one call (all or none: if any def is bad, none is created and
/// the error names the first bad index).
TB_API tb_result tb_joint_create_many(tb_world* world, const tb_joint_def* defs,
                                      uint32_t count, tb_joint_id* out_ids);
TB_API tb_result tb_joint_destroy(tb_world* world, tb_joint_id joint);
TB_API int tb_joint_is_valid(const tb_world* world, tb_joint_id joint);
TB_API void* tb_joint_get_user_data(const tb_world* world, tb_joint_id joint);
/// The two bodies of a joint (either pointer may be NULL).
TB_API tb_result tb_joint_get_bodies(const tb_world* world, tb_joint_id joint,
                                     tb_body_id* body_a, tb_body_id* body_b);

/// Between steps: the motor's target speed and most force or torque (>= 0), and whether it
/// is on. Hinges and sliders only.
TB_API tb_result tb_joint_set_motor(tb_world* world, tb_joint_id joint, int32_t enable,
                                    float speed, float max_force);
/// Between steps: the limit and whether it is on (lower <= upper). Hinges, sliders,
/// distance joints and cone-twist joints (the twist).
TB_API tb_result tb_joint_set_limit(tb_world* world, tb_joint_id joint, int32_t enable,
                                    float lower, float upper);
/// Between steps: the spring (hertz > 0, damping ratio >= 0) and what it pulls to (hinges:
/// the angle, rad; sliders: the offset, m; distance joints: the length, m, which is the
/// joint's `length`), and whether it is on. Hinges, sliders and distance joints; a hinge's
/// spring with its target moved each step is a position servo.
TB_API tb_result tb_joint_set_spring(tb_world* world, tb_joint_id joint, int32_t enable,
                                     float hertz, float damping_ratio, float target);

/// What `count` joints held in the last step: the force (N) and torque (N m, about b's
/// anchor) each applied to its body b, world frame, and whether it has broken (1) (any
/// array may be NULL). A broken joint holds nothing and stays broken until destroyed.
TB_API tb_result tb_joint_read_forces(tb_world* world, const tb_joint_id* ids,
                                      uint32_t count, tb_vec3* forces, tb_vec3* torques,
                                      int32_t* broken);
/// The anchors of `count` joints in world space, from the bodies' present poses (for
/// drawing); either array may be NULL.
TB_API tb_result tb_joint_read_anchors(tb_world* world, const tb_joint_id* ids,
                                       uint32_t count, tb_vec3* anchors_a,
                                       tb_vec3* anchors_b);
/// Ids of live joints in slot order, at most `capacity` of them to `out` (NULL with
/// capacity 0); returns how many joints there are.
TB_API uint32_t tb_world_joint_ids(const tb_world* world, tb_joint_id* out,
                                   uint32_t capacity);

/* ---------------------------------------------------------------------------------------
 * Plugins (abi/tumble_plugin.h says what a plugin is and how it is built)
 */

/// Plugin id, same scheme as tb_body_id.
typedef struct tb_plugin_id { uint32_t index1; uint16_t world; uint16_t generation; } tb_plugin_id;

/// Load the plugin at `path` (a shared object exporting tb_plugin_entry) into the world:
/// its stages join the step (compiled now, when given as GLSL) and its callbacks run after
/// each step call. Refused, with the world unchanged, when the file cannot be loaded, has no
/// entry point, was built for a newer plugin ABI, describes itself wrongly (names, sizes,
/// points, dispatch rules), or a stage's shader is not valid SPIR-V for the step (or its
/// GLSL does not compile). At most 16 plugins and 16 plugin stages per world.
TB_API tb_result tb_world_load_plugin(tb_world* world, const char* path, tb_plugin_id* out);
/// Remove the plugin's stages and callbacks from the world and unload it.
TB_API tb_result tb_world_unload_plugin(tb_world* world, tb_plugin_id plugin);
/// Write `size` bytes at `offset` of the plugin's parameter block (the plugin defines its
/// layout); the GPU sees it from the next step on. Refused beyond the block, or when the
/// plugin's check rejects the block that would result.
TB_API tb_result tb_world_set_plugin_param(tb_world* world, tb_plugin_id plugin, uint32_t offset,
                                           const void* data, uint32_t size);

/* ---------------------------------------------------------------------------------------
 * Shader hot-reload, while developing shaders
 */

/// Compile the step's shaders at run time from the GLSL tree at `dir` (laid out as the
/// source's glsl/: <dir>/integrate/substep.comp, includes in <dir>/common) instead of the
/// SPIR-V built into the library, and watch them: between steps, a shader written since the
/// last step (or a file it includes) is compiled again, its pipeline swapped in and the step
/// recorded again. A shader that does not compile keeps the pipeline it had (the built-in
/// one at first) and its error, "file:line: error: message", goes to the log callback as a
/// TB_LOG_ERROR; the world keeps stepping. Plugin stages given as GLSL are watched too.
/// The environment variable TUMBLE_SHADER_DIR sets it when a world is created.
/// NULL stops watching; the pipelines in use stay. Refused when `dir` is not a directory.
TB_API tb_result tb_world_set_shader_dir(tb_world* world, const char* dir);

#ifdef __cplusplus
}
#endif
#endif /* TUMBLE_H */
