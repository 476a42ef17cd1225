#version 450
#extension GL_GOOGLE_include_directive : require
// Per body, after the block solver's iterations: the velocities the body leaves the step
// with, and what the free motion's pieces add to its displacement (integrate/integrate then
// moves the pose by the solve's displacement and turn and stores them).
//
// The solve moves a body as one piece of implicit Euler: under a steady acceleration a its
// displacement is a h^2 and its velocity grows by a h. The soft step's substeps, N pieces,
// move it by only a h^2 (N + 1) / (2 N) for the same change of velocity (block_fall_share):
// a projectile then follows the same arc with either solver (one piece falls g h^2 / 2 too
// far a step, and a ball bounced off the floor rose 6-8 % short of its height). So a body
// without contact points falls g h^2 (N - 1) / (2 N) less than the solve moved it. A body
// with contacts moves as the solve left it: moved so while its contacts held no force at
// the step's end, the boxes of a settled pile that had just lost their load were lifted by
// it and hopped (lavapipe, deep pile of 4,000: 84 % at rest after 600 steps instead of 92 %).
#include "block.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    tb_gpu_solver_body s = solver_bodies[i];
    if (s.linear.w == 0.0) return;
    float h = block_h();
    // The velocity that carried the body where the solve left it; and the spin of the free
    // turn (block_target), changed by how far the solve turned the body beyond it: a free
    // body keeps its spin exactly (not through a rotation vector and back each step), and a
    // spin faster than the turn's clamp keeps its speed.
    vec4 target = block_target[2u * i + 1u];
    vec4 beyond = quat_mul(s.delta_rotation, vec4(-target.xyz, target.w));
    solver_bodies[i].linear.xyz = s.delta_position.xyz / h;
    solver_bodies[i].angular.xyz = s.angular.xyz + rotation_vector(beyond) / h;
    float lag = 1.0 - block_fall_share();
    if (lag > 0.0 && block_fill[i] == 0u)
        solver_bodies[i].delta_position.xyz -= params.gravity.xyz * (s.angular.w * h * h * lag);
}
