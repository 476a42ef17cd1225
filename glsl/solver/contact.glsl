// One projected Gauss-Seidel pass over one contact constraint (see solve.comp for the rules).
// Shared by solve.comp (a colour at a time) and solve_tail.comp (leftovers, in pair order).
#ifndef TB_SOLVER_CONTACT_GLSL
#define TB_SOLVER_CONTACT_GLSL

#include "colouring.glsl"
#include "bodies.glsl"

// Impulse j applied at ra on a (negative) and rb on b (positive), real velocities.
void apply_impulse(inout solver_body a, inout solver_body b, vec3 ra, vec3 rb, vec3 j)
{
    a.v -= a.inv_mass * j;
    a.w -= solver_inv_inertia(a, cross(ra, j));
    b.v += b.inv_mass * j;
    b.w += solver_inv_inertia(b, cross(rb, j));
}

// The same on the split-impulse pseudo velocities.
void apply_push(inout solver_body a, inout solver_body b, vec3 ra, vec3 rb, vec3 j)
{
    a.pv -= a.inv_mass * j;
    a.pw -= solver_inv_inertia(a, cross(ra, j));
    b.pv += b.inv_mass * j;
    b.pw += solver_inv_inertia(b, cross(rb, j));
}

vec3 relative_velocity(solver_body a, solver_body b, vec3 ra, vec3 rb)
{
    return b.v + cross(b.w, rb) - a.v - cross(a.w, ra);
}

vec3 relative_push(solver_body a, solver_body b, vec3 ra, vec3 rb)
{
    return b.pv + cross(b.pw, rb) - a.pv - cross(a.pw, ra);
}

// A constraint as a pass works on it: its pair's bodies (loaded), points, normal and data.
struct contact_view {
    uvec2 bodies;
    uint count;
    vec3 n;
    tb_gpu_constraint c;
    solver_body a, b;
};

contact_view contact_load(uint p)
{
    contact_view v;
    v.bodies = pairs[pair_half_base() + p].xy;
    v.count = min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS));
    v.n = manifolds[p].normal.xyz;
    v.c = constraints[p];
    v.a = solver_body_load(v.bodies.x);
    v.b = solver_body_load(v.bodies.y);
    return v;
}

void contact_store(contact_view v)
{
    solver_body_store(v.bodies.x, v.a);
    solver_body_store(v.bodies.y, v.b);
}

// Warm start of pair p: apply the impulses its points ended the last step with (the
// narrowphase copied them into this step's manifold). Every constraint is warm-started in a
// sweep of its own before any is solved: a constraint solved while a neighbour's warm start
// is still missing sees that neighbour falling, and a stack then sinks at a steady speed.
// The split impulse starts from zero every step.
void warm_start_contact(uint p)
{
    contact_view v = contact_load(p);
    for (uint k = 0u; k < v.count; k++) {
        vec4 impulse = manifolds[p].impulse[k];
        vec3 j = v.n * impulse.x + v.c.tangent1.xyz * impulse.y + v.c.tangent2.xyz * impulse.z;
        apply_impulse(v.a, v.b, v.c.p[k].ra.xyz, v.c.p[k].rb.xyz, j);
        manifolds[p].impulse[k].w = 0.0;
    }
    contact_store(v);
}

// One projected Gauss-Seidel pass over pair p of this step's half.
void solve_contact(uint p)
{
    contact_view v = contact_load(p);
    uint count = v.count;
    vec3 n = v.n;
    tb_gpu_constraint c = v.c;
    vec3 t1 = c.tangent1.xyz, t2 = c.tangent2.xyz;
    float friction = c.tangent1.w;
    solver_body a = v.a, b = v.b;
    vec4 impulse[TB_MAX_MANIFOLD_POINTS];
    for (uint k = 0u; k < count; k++) impulse[k] = manifolds[p].impulse[k];
    for (uint k = 0u; k < count; k++) {
        vec3 ra = c.p[k].ra.xyz, rb = c.p[k].rb.xyz;
        float mass = c.p[k].ra.w;
        // Real velocity: non-penetration (accumulated impulse >= 0) against the target.
        float vn = dot(relative_velocity(a, b, ra, rb), n);
        float total = max(impulse[k].x + mass * (c.p[k].rb.w - vn), 0.0);
        apply_impulse(a, b, ra, rb, n * (total - impulse[k].x));
        impulse[k].x = total;
        // Pseudo velocity: penetration recovery, never seen by the real velocities.
        float pn = dot(relative_push(a, b, ra, rb), n);
        float split = max(impulse[k].w + mass * (c.p[k].mass.z - pn), 0.0);
        apply_push(a, b, ra, rb, n * (split - impulse[k].w));
        impulse[k].w = split;
    }
    for (uint k = 0u; k < count; k++) {
        vec3 ra = c.p[k].ra.xyz, rb = c.p[k].rb.xyz;
        vec3 dv = relative_velocity(a, b, ra, rb);
        vec2 old = impulse[k].yz;
        vec2 total = old - vec2(c.p[k].mass.x * dot(dv, t1), c.p[k].mass.y * dot(dv, t2));
        // Circular cone: the tangent impulse may not exceed mu times the normal impulse.
        float limit = friction * impulse[k].x, size = length(total);
        if (size > limit) total *= size > 0.0 ? limit / size : 0.0;
        vec2 d = total - old;
        apply_impulse(a, b, ra, rb, t1 * d.x + t2 * d.y);
        impulse[k].yz = total;
    }
    for (uint k = 0u; k < count; k++) manifolds[p].impulse[k] = impulse[k];
    v.a = a;
    v.b = b;
    contact_store(v);
}

#endif
