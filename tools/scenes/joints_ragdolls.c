/* ragdolls: N ragdolls of 11 bodies (a box pelvis and torso, a sphere head, capsule upper
 * and lower arms and legs, about 65 kg in all from the default density) joined by
 * cone-twist joints at the spine, neck, shoulders and hips (each limb swinging within a
 * cone about where it points at the start, and twisting within a limit) and by hinges
 * across the body at the elbows and knees, limited to bend one way as a person's do. They stand on a square grid
 * of pitch 1.2 m, each turned about the vertical and tilted by a fixed random angle so
 * that no two fall alike, their feet at least 0.5 m above a static plane, and fall onto
 * it: onto each other only where a neighbour topples that way.
 *
 * Checks: nan; below_ground, bodies whose centre ended below the plane; max_gap, the
 * largest distance between a joint's two anchors (m); max_twist, the largest angle between
 * the axes an elbow's or knee's hinge holds together (rad); max_swing_over, the most a
 * cone-twist joint's swing passed its cone (rad); broken; resting, the share of bodies
 * slower than 0.1 m/s; max_penetration. */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define RAGDOLL_PARTS 11u
#define RAGDOLL_JOINTS 10u
#define RAGDOLL_PITCH 1.2f     /* m between neighbouring ragdolls' pelvises */
#define RAGDOLL_PELVIS_Y 1.5f  /* m: the pelvis's height (the feet hang 0.93 m below it) */
#define RAGDOLL_TILT 0.4f      /* rad: the most a ragdoll leans from upright at the start */
#define RAGDOLL_REST_SPEED 0.1f
#define KNEE_BEND 2.4f         /* rad: the most a knee or elbow bends */

typedef enum part_shape { PART_BOX, PART_SPHERE, PART_CAPSULE } part_shape;

/* A body of the ragdoll standing upright facing +z, pelvis at the origin: its shape (box
 * half extents; sphere radius in x; capsule radius in x and half height in y, along y),
 * where it is, and the joint that holds it to `parent` (none for the pelvis) at `joint`:
 * a hinge about `axis` whose limit is lower..upper, or a cone-twist joint whose cone of
 * half angle `cone` is about `axis` and whose twist about it is within lower..upper. */
typedef struct ragdoll_part {
    part_shape shape;
    tb_vec3 size;
    tb_vec3 centre;
    int parent;
    tb_joint_kind kind;
    tb_vec3 joint, axis;
    float lower, upper, cone;
} ragdoll_part;

#define ACROSS { 1, 0, 0 }
#define UP { 0, 1, 0 }
#define DOWN { 0, -1, 0 }
#define CONE TB_JOINT_CONE_TWIST

/* A knee turned by a positive angle about +x swings its foot backwards (-z), an elbow
 * turned by a negative one swings its hand forwards. */
static const ragdoll_part PARTS[RAGDOLL_PARTS] = {
    { PART_BOX, { 0.15f, 0.08f, 0.10f }, { 0, 0, 0 }, -1, CONE, { 0, 0, 0 }, UP, 0, 0, 0 },
    { PART_BOX, { 0.17f, 0.20f, 0.10f }, { 0, 0.32f, 0 }, 0, CONE, { 0, 0.10f, 0 }, UP,
      -0.4f, 0.4f, 0.5f },
    { PART_SPHERE, { 0.10f, 0, 0 }, { 0, 0.66f, 0 }, 1, CONE, { 0, 0.54f, 0 }, UP,
      -0.8f, 0.8f, 0.6f },
    { PART_CAPSULE, { 0.045f, 0.10f, 0 }, { -0.23f, 0.34f, 0 }, 1, CONE, { -0.23f, 0.48f, 0 },
      DOWN, -1.0f, 1.0f, 1.6f },
    { PART_CAPSULE, { 0.045f, 0.10f, 0 }, { 0.23f, 0.34f, 0 }, 1, CONE, { 0.23f, 0.48f, 0 },
      DOWN, -1.0f, 1.0f, 1.6f },
    { PART_CAPSULE, { 0.04f, 0.10f, 0 }, { -0.23f, 0.05f, 0 }, 3, TB_JOINT_HINGE,
      { -0.23f, 0.19f, 0 }, ACROSS, -KNEE_BEND, 0, 0 },
    { PART_CAPSULE, { 0.04f, 0.10f, 0 }, { 0.23f, 0.05f, 0 }, 4, TB_JOINT_HINGE,
      { 0.23f, 0.19f, 0 }, ACROSS, -KNEE_BEND, 0, 0 },
    { PART_CAPSULE, { 0.06f, 0.15f, 0 }, { -0.09f, -0.29f, 0 }, 0, CONE, { -0.09f, -0.08f, 0 },
      DOWN, -0.5f, 0.5f, 1.0f },
    { PART_CAPSULE, { 0.06f, 0.15f, 0 }, { 0.09f, -0.29f, 0 }, 0, CONE, { 0.09f, -0.08f, 0 },
      DOWN, -0.5f, 0.5f, 1.0f },
    { PART_CAPSULE, { 0.05f, 0.16f, 0 }, { -0.09f, -0.72f, 0 }, 7, TB_JOINT_HINGE,
      { -0.09f, -0.505f, 0 }, ACROSS, 0, KNEE_BEND, 0 },
    { PART_CAPSULE, { 0.05f, 0.16f, 0 }, { 0.09f, -0.72f, 0 }, 8, TB_JOINT_HINGE,
      { 0.09f, -0.505f, 0 }, ACROSS, 0, KNEE_BEND, 0 },
};

/* One shape per part, shared by every ragdoll. */
static tb_result part_shapes(tb_world* w, tb_shape_id shapes[RAGDOLL_PARTS])
{
    tb_shape_def sd = tb_default_shape_def();
    tb_result r = TB_OK;
    for (uint32_t i = 0; r == TB_OK && i < RAGDOLL_PARTS; i++) {
        const ragdoll_part* p = &PARTS[i];
        if (p->shape == PART_BOX) r = tb_shape_create_box(w, &sd, p->size, &shapes[i]);
        else if (p->shape == PART_SPHERE) r = tb_shape_create_sphere(w, &sd, p->size.x, &shapes[i]);
        else r = tb_shape_create_capsule(w, &sd, p->size.x, p->size.y, &shapes[i]);
    }
    return r;
}

/* Where ragdoll k stands (its pelvis) and how it is turned: about y by up to a full turn,
 * then leaning about a horizontal axis by up to RAGDOLL_TILT. */
static void ragdoll_pose(uint32_t k, uint32_t side, uint32_t* rng, tb_vec3* at, tb_quat* turn)
{
    float half = 0.5f * RAGDOLL_PITCH * (float)(side - 1);
    *at = (tb_vec3){ RAGDOLL_PITCH * (float)(k % side) - half, RAGDOLL_PELVIS_Y,
                     RAGDOLL_PITCH * (float)(k / side) - half };
    tb_quat yaw = joints_axis_angle((tb_vec3){ 0, 1, 0 }, 3.14159265f * scene_rng_signed(rng));
    tb_quat lean = joints_axis_angle((tb_vec3){ 1, 0, 0 }, RAGDOLL_TILT * scene_rng_signed(rng));
    *turn = joints_quat_mul(yaw, lean);
}

/* The bodies of ragdoll k: inst->ids[k * RAGDOLL_PARTS + part]. */
static void ragdoll_bodies(uint32_t k, tb_vec3 at, tb_quat turn, const tb_shape_id* shapes,
                           tb_body_def* defs, scene_instance* inst)
{
    for (uint32_t i = 0; i < RAGDOLL_PARTS; i++) {
        uint32_t b = k * RAGDOLL_PARTS + i;
        defs[b] = tb_default_body_def();
        defs[b].shape = shapes[i];
        defs[b].position = joints_add(at, joints_rotate(turn, PARTS[i].centre));
        defs[b].rotation = turn;   /* every part's own axes are the ragdoll's */
        inst->x0[b] = defs[b].position;
        inst->v0[b] = (tb_vec3){ 0, 0, 0 };
    }
}

/* The joints of ragdoll k, its bodies made: RAGDOLL_JOINTS defs from defs[0]. */
static tb_result ragdoll_joints(tb_world* w, uint32_t k, tb_vec3 at, tb_quat turn,
                                const scene_instance* inst, tb_joint_def* defs)
{
    const tb_body_id* ids = inst->ids + k * RAGDOLL_PARTS;
    tb_result r = TB_OK;
    for (uint32_t i = 1; r == TB_OK && i < RAGDOLL_PARTS; i++) {
        const ragdoll_part* p = &PARTS[i];
        tb_joint_def* d = &defs[i - 1];
        r = joints_def_at(w, p->kind, ids[p->parent], ids[i],
                          joints_add(at, joints_rotate(turn, p->joint)),
                          joints_rotate(turn, p->axis), d);
        d->enable_limit = 1;
        d->lower = p->lower;
        d->upper = p->upper;
        d->cone_angle = p->cone;
    }
    return r;
}

tb_result ragdolls_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n, side = (uint32_t)ceil(sqrt((double)(n ? n : 1)));
    tb_shape_id shapes[RAGDOLL_PARTS];
    tb_result r = part_shapes(w, shapes);
    scene_instance* inst = r == TB_OK ? instance_alloc(n * RAGDOLL_PARTS) : NULL;
    tb_body_def* bodies = malloc((n ? n : 1) * RAGDOLL_PARTS * sizeof *bodies);
    tb_joint_def* joints = malloc((n ? n : 1) * RAGDOLL_JOINTS * sizeof *joints);
    tb_vec3* at = malloc((n ? n : 1) * sizeof *at);
    tb_quat* turn = malloc((n ? n : 1) * sizeof *turn);
    if (r == TB_OK && (!inst || !bodies || !joints || !at || !turn)) r = TB_ERROR_OUT_OF_MEMORY;
    uint32_t rng = scene_rng_seed(params->seed);
    for (uint32_t k = 0; r == TB_OK && k < n; k++) {
        ragdoll_pose(k, side, &rng, &at[k], &turn[k]);
        ragdoll_bodies(k, at[k], turn[k], shapes, bodies, inst);
    }
    if (r == TB_OK && n) r = tb_body_create_many(w, bodies, n * RAGDOLL_PARTS, inst->ids);
    for (uint32_t k = 0; r == TB_OK && k < n; k++)
        r = ragdoll_joints(w, k, at[k], turn[k], inst, joints + k * RAGDOLL_JOINTS);
    if (r == TB_OK) r = joints_create(w, joints, n * RAGDOLL_JOINTS);
    if (r == TB_OK) r = scene_ground_plane(w);
    free(bodies);
    free(joints);
    free(at);
    free(turn);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

/* Over the joints of `kind`: the largest angle between the joint's axis as its two bodies
 * carry it (every part starts with the ragdoll's axes) less `slack` (the cone's), rad: a
 * hinge holds it at 0, a cone-twist joint within its cone. */
static double ragdolls_axis_error(const tb_quat* rot, uint32_t ragdolls, tb_joint_kind kind)
{
    double worst = 0.0;
    for (uint32_t k = 0; k < ragdolls; k++) {
        const tb_quat* parts = rot + k * RAGDOLL_PARTS;
        for (uint32_t i = 1; i < RAGDOLL_PARTS; i++) {
            const ragdoll_part* p = &PARTS[i];
            if (p->kind != kind) continue;
            double angle = joints_angle_between(joints_rotate(parts[p->parent], p->axis),
                                                joints_rotate(parts[i], p->axis)) - p->cone;
            if (!(angle <= worst)) worst = angle;
        }
    }
    return worst;
}

tb_result ragdolls_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                         scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos;
    tb_quat* rot;
    uint32_t nan, below = 0, resting = 0;
    joints_census joints;
    double depth = 0.0;
    tb_result r = joints_read_poses(w, inst, &pos, &rot, &nan, &joints);
    for (uint32_t i = 0; r == TB_OK && i < inst->count; i++) {
        tb_vec3 v, av;
        below += pos[i].y < 0.0f;
        r = tb_body_get_velocity(w, inst->ids[i], &v, &av);
        if (r == TB_OK && sqrtf(v.x * v.x + v.y * v.y + v.z * v.z) < RAGDOLL_REST_SPEED) resting++;
    }
    if (r == TB_OK) r = scene_max_penetration(w, &depth);
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "below_ground", below);
        scene_put(out, "max_gap", joints.max_gap);
        uint32_t ragdolls = inst->count / RAGDOLL_PARTS;
        scene_put(out, "max_twist", ragdolls_axis_error(rot, ragdolls, TB_JOINT_HINGE));
        scene_put(out, "max_swing_over", ragdolls_axis_error(rot, ragdolls, CONE));
        scene_put(out, "broken", joints.broken);
        scene_put(out, "resting", inst->count ? (double)resting / inst->count : 1.0);
        scene_put(out, "max_penetration", depth);
    }
    free(pos);
    free(rot);
    return r;
}
