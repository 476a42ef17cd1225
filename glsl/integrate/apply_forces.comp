#version 450
#extension GL_GOOGLE_include_directive : require
// Gravity and damping change the velocities of dynamic bodies: v += g * scale * dt, then
// each velocity is scaled by 1 / (1 + dt * damping) (stable for any dt, no sign flip).
// Every slot, static ones too, also starts the step with no colouring claim and no
// split-impulse push: the solver's passes accumulate into both.
#include "world.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    body_claim[i] = 0xffffffffu;
    body_push[2u * i] = vec4(0.0);
    body_push[2u * i + 1u] = vec4(0.0);
    if (!body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    float dt = params.gravity.w;
    vec4 lin = body_linvel[i];
    vec4 ang = body_angvel[i];
    float gravity_scale = body_inv_inertia[i].w;
    vec3 v = (lin.xyz + params.gravity.xyz * (gravity_scale * dt)) * (1.0 / (1.0 + dt * lin.w));
    vec3 w = ang.xyz * (1.0 / (1.0 + dt * ang.w));
    body_linvel[i] = vec4(v, lin.w);
    body_angvel[i] = vec4(w, ang.w);
}
