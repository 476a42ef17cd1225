#version 450
#extension GL_GOOGLE_include_directive : require
// Per body, after the block solver's iterations: the velocities that carried the body from
// where the step began to where the solve left it (integrate/integrate then moves the pose
// by the same displacement and stores them).
#include "block.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    tb_gpu_solver_body s = solver_bodies[i];
    if (s.linear.w == 0.0) return;
    float h = block_h();
    solver_bodies[i].linear.xyz = s.delta_position.xyz / h;
    solver_bodies[i].angular.xyz = rotation_vector(s.delta_rotation) / h;
}
