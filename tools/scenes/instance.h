/* What the scene files share: the instance every scene returns, the jitter generator, and
 * the pile scenes' entry points. Internal to tools/scenes. */
#ifndef TUMBLE_SCENES_INSTANCE_H
#define TUMBLE_SCENES_INSTANCE_H

#include "scenes.h"

/* What any scene keeps after building: the ids it made (dynamic first), for scenes whose
 * result has a closed form each body's initial position and velocity, and for scenes in
 * a container the container's inner bounds. */
struct scene_instance {
    uint32_t count;
    tb_body_id* ids;
    tb_vec3* x0;
    tb_vec3* v0;
    tb_vec3 box_min, box_max;   ///< interior of the container (pile scenes)
    uint32_t side;              ///< joint_grid: spheres along a row
};

scene_instance* instance_alloc(uint32_t count);
void instance_free(scene_instance* inst);

/* Deterministic jitter: xorshift32, so every run of a seed builds the same scene. */
uint32_t scene_rng_seed(uint32_t seed);
uint32_t scene_rng_next(uint32_t* state);
/// Uniform in [-1, 1).
float scene_rng_signed(uint32_t* state);

int scene_vec3_finite(tb_vec3 v);
int scene_quat_finite(tb_quat q);

/// Deepest overlap among the last step's contact points, m (0 when none overlap).
tb_result scene_max_penetration(tb_world* world, double* out);
/// A static plane y = 0 (stacks.c).
tb_result scene_ground_plane(tb_world* world);
/// Append a named figure to `out` (dropped beyond SCENE_MAX_CHECKS).
void scene_put(scene_checks* out, const char* key, double value);

/* piles.c */
/* The pile scenes' grid of start positions and their container. */
typedef struct pile_layout {
    uint32_t side;           ///< columns along x and along z
    uint32_t layers;
    float pitch;             ///< centre to centre, m
    float half_width;        ///< interior half width, m
    float height;            ///< interior height (walls), m
} pile_layout;

/// A footprint about as wide as the pile is tall, walls above the top of the grid.
pile_layout pile_layout_for(uint32_t n);
/// Floor (its top at y = 0) and four walls around [-hw, hw] x [0, height] x [-hw, hw], of
/// the given material.
tb_result pile_build_container(tb_world* world, const pile_layout* layout,
                               const tb_shape_def* material);
/// Is p outside [lo, hi] by more than the escape tolerance?
int pile_outside(tb_vec3 p, tb_vec3 lo, tb_vec3 hi);
/// The end of a pile's build: creates the n bodies of `defs` (then frees it), then the
/// container, and hands the instance over; on any failure (r included) frees it instead.
tb_result pile_finish(tb_world* world, const pile_layout* layout, tb_body_def* defs, uint32_t n,
                      tb_result r, scene_instance* inst, scene_instance** out);
/// The same with a container of the given material.
tb_result pile_finish_of(tb_world* world, const pile_layout* layout, const tb_shape_def* container,
                         tb_body_def* defs, uint32_t n, tb_result r, scene_instance* inst,
                         scene_instance** out);
/// What a pile's checks count of its bodies.
typedef struct pile_counts {
    uint32_t nan, escaped;   ///< not finite; outside the container (others)
    double resting;          ///< share slower than 0.1 m/s (1 when there are none)
    double max_penetration;  ///< m, among the last step's contact points
} pile_counts;
/// Read the bodies' positions into pos (inst->count of them) and count them.
tb_result pile_census(tb_world* world, const scene_instance* inst, tb_vec3* pos,
                      pile_counts* out);
/// Jittered start of body i: cells of one layer first, layers upwards.
tb_vec3 pile_grid_slot(const pile_layout* layout, uint32_t i, uint32_t* rng);
tb_result spheres_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result boxes_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result mixed_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result pile_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                     scene_checks* out);

/* crowd.c */
tb_result crowd_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result crowd_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out);

/* deep.c */
tb_result deep_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result deep_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                     scene_checks* out);

/* sizes.c */
tb_result sizes_build(tb_world* world, const scene_params* params, scene_instance** out);

/* hulls.c */
#define HULLS_SHAPES 6   ///< hull shapes a hull scene makes and its bodies share
tb_result hulls_build(tb_world* world, const scene_params* params, scene_instance** out);
/// The hull scene's HULLS_SHAPES random hull shapes, made in `world`.
tb_result hulls_make_shapes(tb_world* world, uint32_t* rng, tb_shape_id shapes[HULLS_SHAPES]);
/// A rotation uniform over all rotations.
tb_quat hulls_random_rotation(uint32_t* rng);
/// The end of a pile of made shapes (r their result): n bodies, shape i % kinds, on the
/// pile grid at rotations uniform over all, in the container (as pile_finish).
tb_result pile_pour_turned(tb_world* world, const pile_layout* layout, const tb_shape_id* shapes,
                           uint32_t kinds, uint32_t n, uint32_t* rng, tb_result r,
                           scene_instance** out);

/* compounds.c */
tb_result compounds_build(tb_world* world, const scene_params* params, scene_instance** out);

/* shapes.c */
tb_result shapes_build(tb_world* world, const scene_params* params, scene_instance** out);

/* terrain.c */
tb_result terrain_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result heightfield_build(tb_world* world, const scene_params* params, scene_instance** out);

/* stacks.c */
tb_result stack_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result columns_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result pyramid_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result stack_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out);
tb_result columns_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                        scene_checks* out);
uint32_t pyramid_base(uint32_t n);

/* joints.c: what the joint scenes share */
#define JOINTS_HALF_PI 1.57079633f
/// A static box (posts, anchors to hang things from).
tb_result joints_static_box(tb_world* world, tb_vec3 centre, tb_vec3 half, tb_body_id* out);
/// A static plane, its surface at y = 0.
/// A default joint of `kind` between a and b, anchors and frames set at the world point
/// `point` with the frames' x axes along `axis` (tb_joint_def_at).
tb_result joints_def_at(tb_world* world, tb_joint_kind kind, tb_body_id a, tb_body_id b,
                        tb_vec3 point, tb_vec3 axis, tb_joint_def* out);
/// Create `count` joints (tb_joint_create_many) whose ids the scene does not keep (the
/// checks list them with tb_world_joint_ids, in the order made).
tb_result joints_create(tb_world* world, const tb_joint_def* defs, uint32_t count);
/// Rotation by `angle` rad about the unit `axis`.
tb_quat joints_axis_angle(tb_vec3 axis, float angle);
tb_quat joints_quat_mul(tb_quat a, tb_quat b);
tb_vec3 joints_rotate(tb_quat q, tb_vec3 v);
tb_vec3 joints_add(tb_vec3 a, tb_vec3 b);
double joints_distance(tb_vec3 a, tb_vec3 b);
/// The angle between two directions, rad (atan2, exact near 0 where acos is not).
double joints_angle_between(tb_vec3 u, tb_vec3 v);
/// Every joint of the world: how many, the largest distance between a joint's two world
/// anchors (m; every kind the scenes use holds them together) and how many broke.
typedef struct joints_census {
    uint32_t count, broken;
    double max_gap;
} joints_census;
/// The instance's bodies' poses (malloc'd; free both), how many are not finite, and the
/// census of the world's joints: what every joint scene checks.
tb_result joints_read_poses(tb_world* world, const scene_instance* inst, tb_vec3** pos,
                            tb_quat** rot, uint32_t* nan, joints_census* census);

/* joints_chain.c */
tb_result chain_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result chain_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out);
tb_result joint_grid_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result joint_grid_check(tb_world* world, const scene_instance* inst, uint32_t steps,
                           float dt, scene_checks* out);

/* joints_bridge.c */
tb_result bridge_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result bridge_check(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                       scene_checks* out);

/* joints_ragdolls.c */
tb_result ragdolls_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result ragdolls_check(tb_world* world, const scene_instance* inst, uint32_t steps,
                         float dt, scene_checks* out);

/* joints_vehicles.c */
tb_result vehicles_build(tb_world* world, const scene_params* params, scene_instance** out);
tb_result vehicles_check(tb_world* world, const scene_instance* inst, uint32_t steps,
                         float dt, scene_checks* out);

#endif
