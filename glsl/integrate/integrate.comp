#version 450
#extension GL_GOOGLE_include_directive : require
// Semi-implicit Euler: the new velocities move the body. Position x += v dt. Orientation
// turns by the angle |w| dt about w / |w|, clamped to params.limits.x per step so a wild
// spin cannot wrap the quaternion update (the stored angular velocity is left alone).
// For tiny angles sin(a/2)/|w| is replaced by its Taylor series to keep precision.
// The velocities come from the solver's record (solver_bodies) and are stored back in the
// body arrays. The pose moves with them plus the solver's split-impulse push, which
// recovers penetration; the stored velocities stay without it, so recovery adds no energy.
// Every slot's colouring claim is released here, even in an abandoned step: the next step's
// colouring (or this step's redo) then starts clean whether or not apply_forces runs first.
#include "world.glsl"
#include "quat.glsl"

const float TAYLOR_BELOW = 1e-3;

// The unit quaternion turning by (clamped) angle |w| dt about w.
vec4 rotation_of(vec3 w, float dt, float max_angle)
{
    float speed = length(w);
    float angle = speed * dt;
    float s;   // sin(angle / 2) / speed: scales w into the quaternion's vector part
    if (angle > max_angle) {
        angle = max_angle;
        s = sin(0.5 * angle) / speed;
    } else if (angle < TAYLOR_BELOW) {
        s = 0.5 * dt - dt * dt * dt * speed * speed * (1.0 / 48.0);
    } else {
        s = sin(0.5 * angle) / speed;
    }
    return vec4(w * s, cos(0.5 * angle));
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x) return;
    body_claim[i] = 0xffffffffu;
    if (step_aborted() || !body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    float dt = params.gravity.w;
    vec4 p = body_pos[i];
    tb_gpu_solver_body s = solver_bodies[i];
    body_linvel[i].xyz = s.linear.xyz;
    body_angvel[i].xyz = s.angular.xyz;
    vec3 v = s.linear.xyz + s.push_linear.xyz;
    vec3 w = s.angular.xyz + s.push_angular.xyz;
    body_pos[i] = vec4(p.xyz + v * dt, p.w);
    vec4 turn = rotation_of(w, dt, params.limits.x);
    body_rot[i] = normalize(quat_mul(turn, body_rot[i]));
}
