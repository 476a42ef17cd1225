#version 450
#extension GL_GOOGLE_include_directive : require
// Per body, after the block solver's iterations: the velocities the body leaves the step
// with (integrate/integrate then moves the pose by the solve's displacement and turn and
// stores them).
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
}
