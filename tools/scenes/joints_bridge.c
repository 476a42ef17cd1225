/* bridge: a plank bridge. N boxes (planks 0.5 m long, 1 m wide, 0.1 m thick) joined end to
 * end by hinges whose axis runs across the bridge (z), the first and last hinged to the
 * tops of two static posts, and a heavy box (10 times a plank's mass) dropped onto the
 * middle from 1 m above. A bridge hung in a straight line would have to stretch to carry
 * anything, so the planks start on a shallow circular arc (each turned a little more than
 * the one before, the two ends BRIDGE_ARC from level) whose ends meet the posts: a rope
 * bridge with the slack such bridges have. A static plane below catches whatever falls.
 *
 * Checks: nan; sag, how far the middle plank's centre is below the posts' hinges at the
 * end (m), and sag_start, the same before the steps; max_gap, the largest distance between
 * a hinge's two anchors (m); max_twist, the largest angle between the axes (z) a hinge
 * joins (rad); broken; load_fell, 1 when the load's centre has come below the middle
 * plank's. */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define PLANK_HALF_LENGTH 0.25f
#define PLANK_HALF_THICKNESS 0.05f
#define PLANK_HALF_WIDTH 0.5f
#define BRIDGE_ARC 0.3f          /* rad: the end planks' slope at the start */
#define BRIDGE_HEIGHT 5.0f       /* m: the posts' hinges above the ground */
#define LOAD_HALF 0.25f          /* m: the load is a cube */
#define LOAD_MASS_RATIO 10.0f    /* the load's mass over a plank's */
#define LOAD_DROP 1.0f           /* m of air between the load and the middle plank */

/* Slope of plank i of n: from -BRIDGE_ARC (going down from the left post) to +BRIDGE_ARC. */
static float plank_slope(uint32_t i, uint32_t n)
{
    return BRIDGE_ARC * (2.0f * ((float)i + 0.5f) / (float)n - 1.0f);
}

/* Half the distance between the posts' hinges: the arc's planks laid end to end. */
static float bridge_half_span(uint32_t n)
{
    double span = 0.0;
    for (uint32_t i = 0; i < n; i++) span += 2.0 * PLANK_HALF_LENGTH * cos(plank_slope(i, n));
    return (float)(0.5 * span);
}

/* The hinge points from the left post's (joints[0]) to the right post's (joints[n]), and
 * the planks between them. */
static void bridge_layout(uint32_t n, tb_vec3* joints, tb_body_def* planks, tb_shape_id shape)
{
    joints[0] = (tb_vec3){ -bridge_half_span(n), BRIDGE_HEIGHT, 0 };
    for (uint32_t i = 0; i < n; i++) {
        float slope = plank_slope(i, n), length = 2.0f * PLANK_HALF_LENGTH;
        tb_vec3 along = { cosf(slope), sinf(slope), 0 };
        joints[i + 1] = (tb_vec3){ joints[i].x + length * along.x,
                                   joints[i].y + length * along.y, 0 };
        planks[i] = tb_default_body_def();
        planks[i].shape = shape;
        planks[i].position = (tb_vec3){ 0.5f * (joints[i].x + joints[i + 1].x),
                                        0.5f * (joints[i].y + joints[i + 1].y), 0 };
        planks[i].rotation = joints_axis_angle((tb_vec3){ 0, 0, 1 }, slope);
    }
}

/* A post under each end's hinge, its top inner edge at the hinge. */
static tb_result bridge_posts(tb_world* w, uint32_t n, tb_body_id posts[2])
{
    float x = bridge_half_span(n) + 0.3f;
    tb_vec3 half = { 0.3f, 0.5f * BRIDGE_HEIGHT, PLANK_HALF_WIDTH + 0.2f };
    tb_result r = joints_static_box(w, (tb_vec3){ -x, half.y, 0 }, half, &posts[0]);
    if (r == TB_OK) r = joints_static_box(w, (tb_vec3){ x, half.y, 0 }, half, &posts[1]);
    return r;
}

/* Hinge i joins what is left of joints[i] to what is right of it, about z. */
static tb_result bridge_hinges(tb_world* w, uint32_t n, const tb_vec3* points,
                               const tb_body_id* planks, const tb_body_id posts[2])
{
    tb_joint_def* defs = malloc((n + 1) * sizeof *defs);
    tb_result r = defs ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; r == TB_OK && i <= n; i++) {
        tb_body_id left = i == 0 ? posts[0] : planks[i - 1];
        tb_body_id right = i == n ? posts[1] : planks[i];
        r = joints_def_at(w, TB_JOINT_HINGE, left, right, points[i], (tb_vec3){ 0, 0, 1 },
                          &defs[i]);
    }
    if (r == TB_OK) r = joints_create(w, defs, n + 1);
    free(defs);
    return r;
}

/* The planks (inst->ids[0 .. n-1]) and, last, the load above the middle one. */
static tb_result bridge_bodies(tb_world* w, uint32_t n, tb_vec3* points, scene_instance* inst)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id plank, cube;
    tb_vec3 half = { PLANK_HALF_LENGTH, PLANK_HALF_THICKNESS, PLANK_HALF_WIDTH };
    tb_result r = tb_shape_create_box(w, &sd, half, &plank);
    if (r == TB_OK)
        r = tb_shape_create_box(w, &sd, (tb_vec3){ LOAD_HALF, LOAD_HALF, LOAD_HALF }, &cube);
    tb_body_def* defs = malloc((n + 1) * sizeof *defs);
    if (r == TB_OK && !defs) r = TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) {
        bridge_layout(n, points, defs, plank);
        float plank_mass = sd.density * 8.0f * half.x * half.y * half.z;
        float top = defs[n / 2].position.y + PLANK_HALF_THICKNESS;
        defs[n] = tb_default_body_def();
        defs[n].shape = cube;
        defs[n].mass = LOAD_MASS_RATIO * plank_mass;
        defs[n].position = (tb_vec3){ 0, top + LOAD_DROP + LOAD_HALF, 0 };
        for (uint32_t i = 0; i <= n; i++) {
            inst->x0[i] = defs[i].position;
            inst->v0[i] = (tb_vec3){ 0, 0, 0 };
        }
        r = tb_body_create_many(w, defs, n + 1, inst->ids);
    }
    free(defs);
    return r;
}

tb_result bridge_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n ? params->n : 1;
    scene_instance* inst = instance_alloc(n + 1);
    tb_vec3* points = malloc((n + 1) * sizeof *points);
    tb_body_id posts[2];
    tb_result r = inst && points ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) r = bridge_bodies(w, n, points, inst);
    if (r == TB_OK) r = bridge_posts(w, n, posts);
    if (r == TB_OK) r = bridge_hinges(w, n, points, inst->ids, posts);
    if (r == TB_OK) r = scene_ground_plane(w);
    free(points);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

/* The largest angle between the hinge axes (z) of neighbouring planks, and of the end
 * planks and the posts': a hinge holds it at 0. */
static double bridge_twist(const tb_quat* rot, uint32_t planks)
{
    const tb_vec3 z = { 0, 0, 1 };
    double worst = 0.0;
    tb_vec3 before = z;
    for (uint32_t i = 0; i <= planks; i++) {
        tb_vec3 axis = i < planks ? joints_rotate(rot[i], z) : z;
        double angle = joints_angle_between(before, axis);
        if (!(angle <= worst)) worst = angle;
        before = axis;
    }
    return worst;
}

tb_result bridge_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
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
        uint32_t planks = inst->count - 1, middle = planks / 2;
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "sag", BRIDGE_HEIGHT - (double)pos[middle].y);
        scene_put(out, "sag_start", BRIDGE_HEIGHT - (double)inst->x0[middle].y);
        scene_put(out, "max_gap", joints.max_gap);
        scene_put(out, "max_twist", bridge_twist(rot, planks));
        scene_put(out, "broken", joints.broken);
        scene_put(out, "load_fell", pos[planks].y < pos[middle].y);
    }
    free(pos);
    free(rot);
    return r;
}
