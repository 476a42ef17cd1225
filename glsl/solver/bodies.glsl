// A body as the contact solver sees it: velocities, split-impulse pseudo velocities and
// inverse mass properties in world space, kept in solver_bodies (tb_gpu_solver_body) for the
// step. Static bodies (and anything not dynamic) have zero inverse mass and inertia, so
// impulses leave them as they are, and they are never written.
#ifndef TB_SOLVER_BODIES_GLSL
#define TB_SOLVER_BODIES_GLSL

#include "world.glsl"
#include "quat.glsl"

struct solver_body {
    vec3 v, w;          // linear and angular velocity
    vec3 pv, pw;        // split-impulse pseudo velocities
    float inv_mass;
    mat3 inv_inertia;   // world space
};

// The world inverse inertia R diag(I^-1) R^T of a dynamic body; zero for any other.
mat3 solver_world_inv_inertia(uint i)
{
    if (!body_is(i, TB_BODY_FLAG_DYNAMIC)) return mat3(0.0);
    mat3 r = quat_to_mat3(body_rot[i]);
    vec3 d = body_inv_inertia[i].xyz;
    return r * mat3(d.x, 0.0, 0.0, 0.0, d.y, 0.0, 0.0, 0.0, d.z) * transpose(r);
}

// A body from the body arrays, before the step's forces (solver/prepare), no push yet.
solver_body solver_body_from_arrays(uint i)
{
    solver_body b;
    bool dynamic = body_is(i, TB_BODY_FLAG_DYNAMIC);
    b.v = body_linvel[i].xyz;
    b.w = body_angvel[i].xyz;
    b.pv = vec3(0.0);
    b.pw = vec3(0.0);
    b.inv_mass = dynamic ? body_pos[i].w : 0.0;
    b.inv_inertia = solver_world_inv_inertia(i);
    return b;
}

// The record apply_forces wrote, as the solve passes update it.
solver_body solver_body_load(uint i)
{
    tb_gpu_solver_body r = solver_bodies[i];
    solver_body b;
    b.v = r.linear.xyz;
    b.w = r.angular.xyz;
    b.pv = r.push_linear.xyz;
    b.pw = r.push_angular.xyz;
    b.inv_mass = r.linear.w;
    vec3 d = r.inv_inertia_diag.xyz, o = r.inv_inertia_off.xyz;
    b.inv_inertia = mat3(d.x, o.x, o.y, o.x, d.y, o.z, o.y, o.z, d.z);
    return b;
}

// The whole record of body i with velocities v, w and no push (apply_forces).
void solver_body_begin(uint i, vec3 v, vec3 w, float inv_mass, mat3 inv_inertia)
{
    tb_gpu_solver_body r;
    r.linear = vec4(v, inv_mass);
    r.angular = vec4(w, 0.0);
    r.push_linear = vec4(0.0);
    r.push_angular = vec4(0.0);
    r.inv_inertia_diag = vec4(inv_inertia[0][0], inv_inertia[1][1], inv_inertia[2][2], 0.0);
    r.inv_inertia_off = vec4(inv_inertia[0][1], inv_inertia[0][2], inv_inertia[1][2], 0.0);
    solver_bodies[i] = r;
}

// World inverse inertia times x.
vec3 solver_inv_inertia(solver_body b, vec3 x)
{
    return b.inv_inertia * x;
}

// 1 / (J M^-1 J^T) for a unit direction d acting at ra on a and rb on b; 0 when neither moves.
float solver_effective_mass(solver_body a, solver_body b, vec3 ra, vec3 rb, vec3 d)
{
    vec3 ca = cross(ra, d), cb = cross(rb, d);
    float k = a.inv_mass + b.inv_mass + dot(ca, solver_inv_inertia(a, ca)) +
              dot(cb, solver_inv_inertia(b, cb));
    return k > 0.0 ? 1.0 / k : 0.0;
}

// Writes back what the solve changes; bodies with no inverse mass (static) are never
// written, so many constraints of one colour may share one.
void solver_body_store(uint i, solver_body b)
{
    if (b.inv_mass == 0.0) return;
    solver_bodies[i].linear.xyz = b.v;
    solver_bodies[i].angular.xyz = b.w;
    solver_bodies[i].push_linear.xyz = b.pv;
    solver_bodies[i].push_angular.xyz = b.pw;
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
