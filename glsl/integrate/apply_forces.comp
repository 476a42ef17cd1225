#version 450
#extension GL_GOOGLE_include_directive : require
// Gravity and damping change the velocities of dynamic bodies: v += g * scale * dt, then
// each velocity is scaled by 1 / (1 + dt * damping) (stable for any dt, no sign flip).
// The result goes to the body's solver record (solver_bodies), with its inverse mass, its
// world inverse inertia and no split-impulse push; the solve passes work on that record and
// integrate copies the velocities back. Every slot, static ones too, also starts the step
// with no colouring claim.
#include "world.glsl"
#include "quat.glsl"
#include "../solver/bodies.glsl"

// The velocities after gravity and damping (dynamic bodies), as they are (others).
void forced_velocities(uint i, out vec3 v, out vec3 w)
{
    vec4 lin = body_linvel[i], ang = body_angvel[i];
    v = lin.xyz;
    w = ang.xyz;
    if (!body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    float dt = params.gravity.w;
    float gravity_scale = body_inv_inertia[i].w;
    v = (v + params.gravity.xyz * (gravity_scale * dt)) * (1.0 / (1.0 + dt * lin.w));
    w = w * (1.0 / (1.0 + dt * ang.w));
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    body_claim[i] = 0xffffffffu;
    vec3 v, w;
    forced_velocities(i, v, w);
    bool dynamic = body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC);
    solver_body_begin(i, v, w, dynamic ? body_pos[i].w : 0.0,
                      dynamic ? solver_world_inv_inertia(i) : mat3(0.0));
}
