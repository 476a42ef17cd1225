/* Joint scenes that hang from static bodies.
 *
 * - chain: N capsule links, each 0.1 m from joint to joint, joined end to end by ball
 *   joints and hung from a static post, let go level so that they swing down; the last
 *   link weighs 100 times what the others do. Neighbours do not collide (the joints'
 *   collide_connected is off); links further apart may. Checks: nan; max_gap, the largest
 *   distance between the two anchors of a joint (m); stretch, that gap over a link's
 *   length; length_error, how much longer than at rest the chain is from the post to the
 *   heavy link's joint, relative; broken.
 * - joint_grid: a square net of floor(sqrt N)^2 spheres of radius 0.1 m at a pitch of
 *   0.5 m in a vertical plane (a curtain), each joined to its right and lower neighbours by
 *   ball joints at the point halfway; the top row is static. The spheres are too far apart
 *   to touch, so the scene measures the joints alone: how far the curtain stretches under
 *   its own weight. Checks: nan; sag, how far the sphere nearest the net's centre has come
 *   down (m); max_gap; broken.
 */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define CHAIN_RADIUS 0.02f
#define CHAIN_LINK 0.1f         /* m from a link's joint to its next, tip to tip */
#define CHAIN_MASS 1.0f         /* kg a link */
#define CHAIN_HEAVY 100.0f      /* the last link's mass over the others' */
#define CHAIN_HANG 1.0f         /* m of air below the chain when it hangs straight down */

#define GRID_RADIUS 0.1f
#define GRID_PITCH 0.5f         /* m between neighbouring spheres' centres */
#define GRID_TOP 2.0f           /* m of air below the net, above y = 0 */

/* ---- chain ---- */

/* Height of the post's joint: the chain hanging straight down keeps CHAIN_HANG clear. */
static float chain_height(uint32_t links)
{
    return CHAIN_HANG + CHAIN_LINK * (float)links;
}

/* Links along +x from the post's joint at (0, h, 0), each capsule turned to lie along x. */
static tb_result chain_links(tb_world* w, uint32_t links, float h, scene_instance* inst)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id capsule;
    float half_height = 0.5f * CHAIN_LINK - CHAIN_RADIUS;
    tb_result r = tb_shape_create_capsule(w, &sd, CHAIN_RADIUS, half_height, &capsule);
    tb_body_def* defs = malloc((links ? links : 1) * sizeof *defs);
    if (r == TB_OK && !defs) r = TB_ERROR_OUT_OF_MEMORY;
    tb_quat along_x = joints_axis_angle((tb_vec3){ 0, 0, 1 }, -JOINTS_HALF_PI);
    for (uint32_t i = 0; r == TB_OK && i < links; i++) {
        defs[i] = tb_default_body_def();
        defs[i].shape = capsule;
        defs[i].position = (tb_vec3){ CHAIN_LINK * ((float)i + 0.5f), h, 0 };
        defs[i].rotation = along_x;
        defs[i].mass = i + 1 == links ? CHAIN_HEAVY * CHAIN_MASS : CHAIN_MASS;
        inst->x0[i] = defs[i].position;
        inst->v0[i] = (tb_vec3){ 0, 0, 0 };
    }
    if (r == TB_OK && links) r = tb_body_create_many(w, defs, links, inst->ids);
    free(defs);
    return r;
}

/* Joint i holds link i to the one before it (the post for the first), at their meeting
 * point; the axis does not matter to a ball joint. */
static tb_result chain_joints(tb_world* w, tb_body_id post, uint32_t links, float h,
                              const scene_instance* inst)
{
    tb_joint_def* defs = malloc((links ? links : 1) * sizeof *defs);
    tb_result r = defs ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; r == TB_OK && i < links; i++) {
        tb_body_id before = i == 0 ? post : inst->ids[i - 1];
        r = joints_def_at(w, TB_JOINT_BALL, before, inst->ids[i],
                          (tb_vec3){ CHAIN_LINK * (float)i, h, 0 }, (tb_vec3){ 0, 0, 1 },
                          &defs[i]);
    }
    if (r == TB_OK) r = joints_create(w, defs, links);
    free(defs);
    return r;
}

tb_result chain_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t links = params->n;
    float h = chain_height(links);
    scene_instance* inst = instance_alloc(links);
    if (!inst) return TB_ERROR_OUT_OF_MEMORY;
    tb_body_id post;
    tb_result r = chain_links(w, links, h, inst);
    if (r == TB_OK)
        r = joints_static_box(w, (tb_vec3){ -0.1f, h, 0 }, (tb_vec3){ 0.1f, 0.1f, 0.1f }, &post);
    if (r == TB_OK) r = chain_joints(w, post, links, h, inst);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

static tb_vec3 midpoint(tb_vec3 a, tb_vec3 b)
{
    return (tb_vec3){ 0.5f * (a.x + b.x), 0.5f * (a.y + b.y), 0.5f * (a.z + b.z) };
}

/* The chain's length through its joints (each joint at its anchors' midpoint) from the
 * post to the heavy link's joint, over its length at rest, less 1. */
static tb_result chain_length_error(tb_world* w, uint32_t links, double* out)
{
    *out = 0.0;
    uint32_t n = tb_world_joint_ids(w, NULL, 0);
    if (n < 2 || n != links) return TB_OK;
    tb_joint_id* ids = malloc(n * sizeof *ids);
    tb_vec3* a = malloc(n * sizeof *a);
    tb_vec3* b = malloc(n * sizeof *b);
    tb_result r = ids && a && b ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) tb_world_joint_ids(w, ids, n);   /* slot order: the order made */
    if (r == TB_OK) r = tb_joint_read_anchors(w, ids, n, a, b);
    double length = 0.0;
    for (uint32_t i = 1; r == TB_OK && i < n; i++) {
        length += joints_distance(midpoint(a[i], b[i]), midpoint(a[i - 1], b[i - 1]));
    }
    if (r == TB_OK) *out = length / (CHAIN_LINK * (double)(n - 1)) - 1.0;
    free(ids);
    free(a);
    free(b);
    return r;
}

tb_result chain_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                      scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos;
    tb_quat* rot;
    uint32_t nan;
    joints_census joints;
    double length_error = 0.0;
    tb_result r = joints_read_poses(w, inst, &pos, &rot, &nan, &joints);
    if (r == TB_OK) r = chain_length_error(w, inst->count, &length_error);
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "max_gap", joints.max_gap);
        scene_put(out, "stretch", joints.max_gap / CHAIN_LINK);
        scene_put(out, "length_error", length_error);
        scene_put(out, "broken", joints.broken);
    }
    free(pos);
    free(rot);
    return r;
}

/* ---- joint_grid ---- */

static uint32_t grid_side_for(uint32_t n)
{
    uint32_t side = (uint32_t)floor(sqrt((double)n));
    while ((uint64_t)(side + 1) * (side + 1) <= n) side++;   /* sqrt rounding */
    return side < 2 ? 2 : side;
}

/* Centre of the sphere in row `row` (0 at the top) and column `col`. */
static tb_vec3 grid_point(uint32_t side, uint32_t row, uint32_t col)
{
    float half = 0.5f * GRID_PITCH * (float)(side - 1);
    return (tb_vec3){ GRID_PITCH * (float)col - half,
                      GRID_TOP + GRID_PITCH * (float)(side - 1 - row), 0 };
}

/* The spheres: rows 1.. dynamic into inst->ids (row by row), row 0 static into `top`. */
static tb_result grid_spheres(tb_world* w, uint32_t side, scene_instance* inst, tb_body_id* top)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id ball;
    tb_result r = tb_shape_create_sphere(w, &sd, GRID_RADIUS, &ball);
    uint32_t count = side * side;
    tb_body_def* defs = malloc(count * sizeof *defs);
    if (r == TB_OK && !defs) r = TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; r == TB_OK && i < count; i++) {
        uint32_t row = i / side, col = i % side;
        defs[i] = tb_default_body_def();
        defs[i].shape = ball;
        defs[i].type = row == 0 ? TB_BODY_STATIC : TB_BODY_DYNAMIC;
        defs[i].position = grid_point(side, row, col);
        if (row > 0) {
            inst->x0[i - side] = defs[i].position;
            inst->v0[i - side] = (tb_vec3){ 0, 0, 0 };
        }
    }
    /* Dynamic bodies first, so their ids lead the instance's list. */
    if (r == TB_OK) r = tb_body_create_many(w, defs + side, count - side, inst->ids);
    if (r == TB_OK) r = tb_body_create_many(w, defs, side, top);
    free(defs);
    return r;
}

static tb_body_id grid_body(const scene_instance* inst, const tb_body_id* top, uint32_t row,
                            uint32_t col)
{
    return row == 0 ? top[col] : inst->ids[(row - 1) * inst->side + col];
}

/* Each sphere to its right neighbour (below the static top row) and to the one below it,
 * by a ball joint halfway between. */
static tb_result grid_joints(tb_world* w, const scene_instance* inst, const tb_body_id* top)
{
    uint32_t side = inst->side, max = 2 * side * side, count = 0;
    tb_joint_def* defs = malloc(max * sizeof *defs);
    tb_result r = defs ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    const tb_vec3 axis = { 0, 0, 1 };
    for (uint32_t row = 0; r == TB_OK && row < side; row++) {
        for (uint32_t col = 0; r == TB_OK && col < side; col++) {
            tb_vec3 p = grid_point(side, row, col);
            tb_body_id here = grid_body(inst, top, row, col);
            if (row > 0 && col + 1 < side)
                r = joints_def_at(w, TB_JOINT_BALL, here, grid_body(inst, top, row, col + 1),
                                  (tb_vec3){ p.x + 0.5f * GRID_PITCH, p.y, 0 }, axis,
                                  &defs[count++]);
            if (r == TB_OK && row + 1 < side)
                r = joints_def_at(w, TB_JOINT_BALL, here, grid_body(inst, top, row + 1, col),
                                  (tb_vec3){ p.x, p.y - 0.5f * GRID_PITCH, 0 }, axis,
                                  &defs[count++]);
        }
    }
    if (r == TB_OK) r = joints_create(w, defs, count);
    free(defs);
    return r;
}

tb_result joint_grid_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t side = grid_side_for(params->n);
    scene_instance* inst = instance_alloc(side * (side - 1));
    tb_body_id* top = malloc(side * sizeof *top);
    tb_result r = inst && top ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) {
        inst->side = side;
        r = grid_spheres(w, side, inst, top);
    }
    if (r == TB_OK) r = grid_joints(w, inst, top);
    free(top);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

tb_result joint_grid_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                           scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos;
    tb_quat* rot;
    uint32_t nan;
    joints_census joints;
    tb_result r = joints_read_poses(w, inst, &pos, &rot, &nan, &joints);
    if (r == TB_OK) {
        /* The sphere nearest the centre: the middle row and column (row 0 is static). */
        uint32_t side = inst->side, row = side / 2, col = side / 2;
        uint32_t centre = (row - 1) * side + col;
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "sag", (double)inst->x0[centre].y - pos[centre].y);
        scene_put(out, "max_gap", joints.max_gap);
        scene_put(out, "broken", joints.broken);
    }
    free(pos);
    free(rot);
    return r;
}
