#version 450
#extension GL_GOOGLE_include_directive : require
// The start of the solver's step: each body's solver record (solver_bodies) gets its
// velocities, damped for the step (each scaled by 1 / (1 + dt * damping): stable for any dt,
// no sign flip), its inverse mass, world inverse inertia and gravity scale; gravity itself
// is applied per substep (solver/substep). Every slot, static ones too, also starts the step
// with no colouring claim.
#include "world.glsl"
#include "quat.glsl"
#include "../solver/bodies.glsl"

// The velocities after damping (dynamic bodies), as they are (others).
void damped_velocities(uint i, out vec3 v, out vec3 w)
{
    vec4 lin = body_linvel[i], ang = body_angvel[i];
    v = lin.xyz;
    w = ang.xyz;
    if (!body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC)) return;
    float dt = params.gravity.w;
    v *= 1.0 / (1.0 + dt * lin.w);
    w *= 1.0 / (1.0 + dt * ang.w);
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    body_claim[i] = 0xffffffffu;
    vec3 v, w;
    damped_velocities(i, v, w);
    bool dynamic = body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC);
    solver_body_begin(i, v, w, body_inv_inertia[i].w, dynamic ? body_pos[i].w : 0.0,
                      dynamic ? solver_world_inv_inertia(i) : mat3(0.0));
}
