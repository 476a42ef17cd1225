#version 450
#extension GL_GOOGLE_include_directive : require
// The end of the step: the solver's substeps moved each dynamic body by delta_position and
// turned it by delta_rotation (solver/substep, semi-implicit Euler per substep); the pose
// takes both and the body arrays take the final velocities.
// Every slot's colouring claim is released here, even in an abandoned step: the next step's
// colouring (or this step's redo) then starts clean whether or not apply_forces runs first.
#include "world.glsl"
#include "quat.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x) return;
    body_claim[i] = 0xffffffffu;
    if (step_aborted() || !body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    tb_gpu_solver_body s = solver_bodies[i];
    body_linvel[i].xyz = s.linear.xyz;
    body_angvel[i].xyz = s.angular.xyz;
    body_pos[i].xyz += s.delta_position.xyz;
    body_rot[i] = normalize(quat_mul(s.delta_rotation, body_rot[i]));
}
