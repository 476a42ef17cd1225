#version 450
#extension GL_GOOGLE_include_directive : require
// One substep of the soft step on every dynamic body's solver record (push.args.z):
// 0: gravity for the substep, v += g * scale * h;
// 1: motion, semi-implicit Euler: delta_position += v h, delta_rotation turned by the angle
//    |w| h about w (clamped to the step's largest rotation shared among the substeps).
// h = params.soft.w. Bodies that are not dynamic have zero inverse mass and stay put.
#include "world.glsl"
#include "quat.glsl"
#include "motion.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    tb_gpu_solver_body s = solver_bodies[i];
    if (s.linear.w == 0.0) return;
    float h = params.soft.w;
    if (push.args.z == 0u) {
        solver_bodies[i].linear.xyz = s.linear.xyz + params.gravity.xyz * (s.angular.w * h);
        return;
    }
    solver_bodies[i].delta_position.xyz = s.delta_position.xyz + s.linear.xyz * h;
    vec4 turn = rotation_of(s.angular.xyz, h, params.limits.x / float(params.counts.z));
    solver_bodies[i].delta_rotation = normalize(quat_mul(turn, s.delta_rotation));
}
