#version 450
#extension GL_GOOGLE_include_directive : require
// The end of the step: the solver's substeps moved each dynamic body by delta_position and
// turned it by delta_rotation (solver/substep, semi-implicit Euler per substep); the pose
// takes both and the body arrays take the final velocities.
// Every slot's colouring claim is released here, even in an abandoned step: the next step's
// colouring (or this step's redo) then starts clean whether or not apply_forces runs first.
//
// The guard: a body whose pose or velocities would stop being finite is isolated instead.
// It keeps the pose it began the step with, its velocities become zero, and its flags lose
// ALIVE and DYNAMIC (and gain ISOLATED): every stage then passes it by as it passes a
// destroyed body's slot, so its NaN reaches no other body in any later step. The solvers
// keep a non-finite step or multiplier from reaching its neighbours within this one.
// counters.guard.x counts them; the host finds them by their flag (run.c).
#define TB_BODY_INFO_WRITABLE
#include "world.glsl"
#include "quat.glsl"

void isolate(uint i)
{
    body_linvel[i].xyz = vec3(0.0);
    body_angvel[i].xyz = vec3(0.0);
    uint flags = body_info[i].y & ~(TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC);
    body_info[i].y = flags | TB_BODY_FLAG_ISOLATED;
    atomicAdd(counters.guard.x, 1u);
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x) return;
    body_claim[i] = 0xffffffffu;
    if (step_aborted() || !body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    tb_gpu_solver_body s = solver_bodies[i];
    vec3 pos = body_pos[i].xyz + s.delta_position.xyz;
    vec4 rot = normalize(quat_mul(s.delta_rotation, body_rot[i]));
    if (!finite_all(pos) || !finite_all(rot) || !finite_all(s.linear.xyz) ||
        !finite_all(s.angular.xyz)) {
        isolate(i);
        return;
    }
    body_linvel[i].xyz = s.linear.xyz;
    body_angvel[i].xyz = s.angular.xyz;
    body_pos[i].xyz = pos;
    body_rot[i] = rot;
}
