/* vehicles: N cars on a static plane, each a box chassis (2 m long along x, 1 m wide,
 * 0.5 m tall, 1,000 kg from the default density) on four cylinder wheels (radius 0.35 m,
 * 0.2 m wide, 77 kg) held by hinges whose axes run across the car, their motors on: each
 * wheel turns at up to WHEEL_SPEED rad/s relative to the chassis with up to WHEEL_TORQUE
 * (four of them push the 1,308 kg car at up to 2.6 m/s^2; a wheel's grip, 0.6 of its
 * quarter of the weight on its radius, holds 670 N m, so the wheels roll rather than
 * spin). The cars stand in
 * columns 5 m apart along x, rows 2.5 m apart along z, their wheels 1 cm above the plane,
 * and all drive towards +x, so they never meet while they go straight. At WHEEL_SPEED a
 * rolling car goes 1.75 m/s.
 *
 * Checks: nan; mean_speed, the chassis' mean velocity along +x (m/s); min_speed and
 * max_speed, the slowest and fastest chassis'; flipped, chassis whose up axis leans more
 * than 60 degrees from the vertical; max_gap, the largest distance between a hinge's two
 * anchors (m); max_twist, the largest angle between a wheel's axle and its chassis' z axis
 * (rad); broken. */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define CAR_WHEELS 4u
#define CAR_BODIES (1u + CAR_WHEELS)
#define CHASSIS_HALF_X 1.0f
#define CHASSIS_HALF_Y 0.25f
#define CHASSIS_HALF_Z 0.5f
#define WHEEL_RADIUS 0.35f
#define WHEEL_HALF_WIDTH 0.1f
#define WHEEL_AXLE_X 0.7f        /* m: the axles before and behind the chassis' centre */
#define WHEEL_GAP 0.02f          /* m between a wheel and the chassis' side */
#define CAR_LIFT 0.01f           /* m of air under the wheels at the start */
#define CAR_PITCH_X 5.0f
#define CAR_PITCH_Z 2.5f
#define WHEEL_SPEED 5.0f         /* rad/s */
#define WHEEL_TORQUE 300.0f      /* N m a wheel */

static tb_result car_shapes(tb_world* w, tb_shape_id* chassis, tb_shape_id* wheel)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_result r = tb_shape_create_box(w, &sd, (tb_vec3){ CHASSIS_HALF_X, CHASSIS_HALF_Y,
                                                         CHASSIS_HALF_Z }, chassis);
    if (r == TB_OK) r = tb_shape_create_cylinder(w, &sd, WHEEL_RADIUS, WHEEL_HALF_WIDTH, wheel);
    return r;
}

/* Centre of car k's chassis: columns along x, rows along z. */
static tb_vec3 car_position(uint32_t k, uint32_t side)
{
    float half_x = 0.5f * CAR_PITCH_X * (float)(side - 1);
    float half_z = 0.5f * CAR_PITCH_Z * (float)(side - 1);
    /* The chassis' bottom 0.1 m below the axles: clear of the ground by 0.25 m. */
    return (tb_vec3){ CAR_PITCH_X * (float)(k / side) - half_x,
                      CAR_LIFT + WHEEL_RADIUS + CHASSIS_HALF_Y - 0.1f,
                      CAR_PITCH_Z * (float)(k % side) - half_z };
}

/* Wheel j's centre relative to its chassis: front left, front right, rear left, rear right. */
static tb_vec3 wheel_offset(uint32_t j)
{
    float x = j < 2 ? WHEEL_AXLE_X : -WHEEL_AXLE_X;
    float z = (j % 2 == 0 ? 1.0f : -1.0f) * (CHASSIS_HALF_Z + WHEEL_GAP + WHEEL_HALF_WIDTH);
    return (tb_vec3){ x, -(CHASSIS_HALF_Y - 0.1f), z };
}

/* Chassis first (inst->ids[0 .. n-1]), then the wheels, car by car. */
static tb_result car_bodies(tb_world* w, uint32_t n, scene_instance* inst)
{
    tb_shape_id chassis, wheel;
    tb_result r = car_shapes(w, &chassis, &wheel);
    uint32_t side = (uint32_t)ceil(sqrt((double)(n ? n : 1)));
    tb_body_def* defs = malloc((n ? n : 1) * CAR_BODIES * sizeof *defs);
    if (r == TB_OK && !defs) r = TB_ERROR_OUT_OF_MEMORY;
    /* A cylinder's axis is its body's y: turned to lie across the car, along z. */
    tb_quat across = joints_axis_angle((tb_vec3){ 1, 0, 0 }, JOINTS_HALF_PI);
    for (uint32_t k = 0; r == TB_OK && k < n; k++) {
        tb_vec3 at = car_position(k, side);
        defs[k] = tb_default_body_def();
        defs[k].shape = chassis;
        defs[k].position = at;
        for (uint32_t j = 0; j < CAR_WHEELS; j++) {
            tb_body_def* d = &defs[n + k * CAR_WHEELS + j];
            *d = tb_default_body_def();
            d->shape = wheel;
            d->position = joints_add(at, wheel_offset(j));
            d->rotation = across;
        }
    }
    for (uint32_t i = 0; r == TB_OK && i < n * CAR_BODIES; i++) {
        inst->x0[i] = defs[i].position;
        inst->v0[i] = (tb_vec3){ 0, 0, 0 };
    }
    if (r == TB_OK && n) r = tb_body_create_many(w, defs, n * CAR_BODIES, inst->ids);
    free(defs);
    return r;
}

/* Each wheel hinged to its chassis at the wheel's centre. The axis points to the car's
 * right (-z) so that a positive motor speed rolls the car forwards (+x). */
static tb_result car_hinges(tb_world* w, uint32_t n, const scene_instance* inst)
{
    tb_joint_def* defs = malloc((n ? n : 1) * CAR_WHEELS * sizeof *defs);
    tb_result r = defs ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t k = 0; r == TB_OK && k < n; k++) {
        for (uint32_t j = 0; r == TB_OK && j < CAR_WHEELS; j++) {
            uint32_t wheel = n + k * CAR_WHEELS + j;
            tb_joint_def* d = &defs[k * CAR_WHEELS + j];
            r = joints_def_at(w, TB_JOINT_HINGE, inst->ids[k], inst->ids[wheel],
                              inst->x0[wheel], (tb_vec3){ 0, 0, -1 }, d);
            d->enable_motor = 1;
            d->motor_speed = WHEEL_SPEED;
            d->max_motor_force = WHEEL_TORQUE;
        }
    }
    if (r == TB_OK) r = joints_create(w, defs, n * CAR_WHEELS);
    free(defs);
    return r;
}

tb_result vehicles_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    scene_instance* inst = instance_alloc(n * CAR_BODIES);
    if (!inst) return TB_ERROR_OUT_OF_MEMORY;
    tb_result r = car_bodies(w, n, inst);
    if (r == TB_OK) r = car_hinges(w, n, inst);
    if (r == TB_OK) r = scene_ground_plane(w);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

/* The largest angle between a wheel's axle (its cylinder's y axis) and its chassis' z axis,
 * which the hinge holds at 0, rad. */
static double vehicles_twist(const tb_quat* rot, uint32_t cars)
{
    double worst = 0.0;
    for (uint32_t k = 0; k < cars; k++) {
        tb_vec3 across = joints_rotate(rot[k], (tb_vec3){ 0, 0, 1 });
        for (uint32_t j = 0; j < CAR_WHEELS; j++) {
            tb_vec3 axle = joints_rotate(rot[cars + k * CAR_WHEELS + j], (tb_vec3){ 0, 1, 0 });
            double angle = joints_angle_between(across, axle);
            if (!(angle <= worst)) worst = angle;
        }
    }
    return worst;
}

tb_result vehicles_check(tb_world* w, const scene_instance* inst, uint32_t steps, float dt,
                         scene_checks* out)
{
    (void)steps;
    (void)dt;
    tb_vec3* pos;
    tb_quat* rot;
    uint32_t nan, flipped = 0, cars = inst->count / CAR_BODIES;
    double sum = 0.0, slowest = INFINITY, fastest = -INFINITY;
    joints_census joints;
    tb_result r = joints_read_poses(w, inst, &pos, &rot, &nan, &joints);
    for (uint32_t k = 0; r == TB_OK && k < cars; k++) {
        tb_vec3 v, av;
        r = tb_body_get_velocity(w, inst->ids[k], &v, &av);
        sum += v.x;
        if (v.x < slowest) slowest = v.x;
        if (v.x > fastest) fastest = v.x;
        flipped += joints_rotate(rot[k], (tb_vec3){ 0, 1, 0 }).y < 0.5f;
    }
    if (r == TB_OK) {
        out->count = 0;
        scene_put(out, "nan", nan);
        scene_put(out, "mean_speed", cars ? sum / cars : 0.0);
        scene_put(out, "min_speed", cars ? slowest : 0.0);
        scene_put(out, "max_speed", cars ? fastest : 0.0);
        scene_put(out, "flipped", flipped);
        scene_put(out, "max_gap", joints.max_gap);
        scene_put(out, "max_twist", vehicles_twist(rot, cars));
        scene_put(out, "broken", joints.broken);
    }
    free(pos);
    free(rot);
    return r;
}
