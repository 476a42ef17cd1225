#version 450
#extension GL_GOOGLE_include_directive : require
// One substep of the soft step on every dynamic body's solver record (push.args.z):
// 0: the velocities' change over the substep without contacts: gravity, v += g * scale * h,
//    and the gyroscopic term, w turned and shifted among the body axes as Euler's equations
//    of a torque-free body say (gyroscopic_change, in the body's current frame);
// 1: motion, semi-implicit Euler: delta_position += v h, delta_rotation turned by the angle
//    |w| h about w (clamped to the step's largest rotation shared among the substeps);
// 2: the free motion over the substep in push.args.y pieces, each 0 then 1 over its share
//    of h (the block solver's step predicts it so, as the soft step's substeps move a body).
// h = params.soft.w. Bodies that are not dynamic have zero inverse mass and stay put.
#include "world.glsl"
#include "quat.glsl"
#include "motion.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

// The world angular velocity after the gyroscopic step, in the frame the substeps have
// turned the body to. A body with an infinite moment (inverse 0) keeps its spin.
vec3 gyroscopic(uint i, tb_gpu_solver_body s, float h)
{
    vec3 inv = body_inv_inertia[i].xyz;
    if (any(equal(inv, vec3(0.0)))) return s.angular.xyz;
    vec4 q = normalize(quat_mul(s.delta_rotation, body_rot[i]));
    vec4 q_inv = vec4(-q.xyz, q.w);
    vec3 w = quat_rotate(q_inv, s.angular.xyz);
    return s.angular.xyz + quat_rotate(q, gyroscopic_change(w, 1.0 / inv, h));
}

// Pass 0 over a time h on record s of body i.
void accelerate(uint i, inout tb_gpu_solver_body s, float h)
{
    s.angular.xyz = gyroscopic(i, s, h);
    s.linear.xyz += params.gravity.xyz * (s.angular.w * h);
}

// Pass 1 over a time h, the turn clamped to `limit`.
void move(inout tb_gpu_solver_body s, float h, float limit)
{
    s.delta_position.xyz += s.linear.xyz * h;
    s.delta_rotation = normalize(quat_mul(rotation_of(s.angular.xyz, h, limit), s.delta_rotation));
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    tb_gpu_solver_body s = solver_bodies[i];
    if (s.linear.w == 0.0) return;
    float h = params.soft.w, turn_limit = params.limits.x / float(params.counts.z);
    if (push.args.z == 0u) {
        accelerate(i, s, h);
    } else if (push.args.z == 1u) {
        move(s, h, turn_limit);
    } else {
        uint pieces = max(push.args.y, 1u);
        for (uint k = 0u; k < pieces; k++) {
            accelerate(i, s, h / float(pieces));
            move(s, h / float(pieces), turn_limit / float(pieces));
        }
    }
    // Only what the pass changed goes back (the soft step runs passes 0 and 1 every substep).
    if (push.args.z != 1u) {
        solver_bodies[i].linear = s.linear;
        solver_bodies[i].angular = s.angular;
    }
    if (push.args.z != 0u) {
        solver_bodies[i].delta_position = s.delta_position;
        solver_bodies[i].delta_rotation = s.delta_rotation;
    }
}
