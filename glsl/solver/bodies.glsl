// A body as the contact solver sees it: velocities, split-impulse pseudo velocities and
// inverse mass properties in world space. Static bodies (and anything not dynamic) have
// zero inverse mass and inertia, so impulses leave them as they are, and they are never
// written: many constraints of one colour may share a static body.
#ifndef TB_SOLVER_BODIES_GLSL
#define TB_SOLVER_BODIES_GLSL

#include "world.glsl"
#include "quat.glsl"

struct solver_body {
    vec3 v, w;          // linear and angular velocity
    vec3 pv, pw;        // split-impulse pseudo velocities (body_push)
    float inv_mass;
    mat3 rot;           // body to world
    vec3 inv_inertia;   // principal inverse inertia, body frame
    bool dynamic;
};

solver_body solver_body_load(uint i)
{
    solver_body b;
    b.dynamic = body_is(i, TB_BODY_FLAG_DYNAMIC);
    b.v = body_linvel[i].xyz;
    b.w = body_angvel[i].xyz;
    b.pv = body_push[2u * i].xyz;
    b.pw = body_push[2u * i + 1u].xyz;
    b.inv_mass = b.dynamic ? body_pos[i].w : 0.0;
    b.rot = quat_to_mat3(body_rot[i]);
    b.inv_inertia = b.dynamic ? body_inv_inertia[i].xyz : vec3(0.0);
    return b;
}

// World inverse inertia times x: R diag(I^-1) R^T x.
vec3 solver_inv_inertia(solver_body b, vec3 x)
{
    return b.rot * (b.inv_inertia * (x * b.rot));
}

// 1 / (J M^-1 J^T) for a unit direction d acting at ra on a and rb on b; 0 when neither moves.
float solver_effective_mass(solver_body a, solver_body b, vec3 ra, vec3 rb, vec3 d)
{
    vec3 ca = cross(ra, d), cb = cross(rb, d);
    float k = a.inv_mass + b.inv_mass + dot(ca, solver_inv_inertia(a, ca)) +
              dot(cb, solver_inv_inertia(b, cb));
    return k > 0.0 ? 1.0 / k : 0.0;
}

void solver_body_store(uint i, solver_body b)
{
    if (!b.dynamic) return;
    body_linvel[i].xyz = b.v;
    body_angvel[i].xyz = b.w;
    body_push[2u * i] = vec4(b.pv, 0.0);
    body_push[2u * i + 1u] = vec4(b.pw, 0.0);
}

// Deterministic friction basis from the normal alone: t1 is perpendicular to n, built from
// the two components of n that are not both small, t2 = n x t1.
void tangent_basis(vec3 n, out vec3 t1, out vec3 t2)
{
    if (abs(n.x) >= 0.57735027)
        t1 = normalize(vec3(n.y, -n.x, 0.0));
    else
        t1 = normalize(vec3(0.0, n.z, -n.y));
    t2 = cross(n, t1);
}

#endif
