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

vec3 relative_velocity(solver_body a, solver_body b, vec3 ra, vec3 rb)
{
    return b.v + cross(b.w, rb) - a.v - cross(a.w, ra);
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

// Whether both bodies' state is finite: a pair with a body whose state stopped being finite
// is passed by, so its NaN reaches no neighbour; integrate then isolates that body.
bool contact_finite(contact_view v)
{
    return finite_all(v.a.v) && finite_all(v.a.w) && finite_all(v.a.dp) &&
           finite_all(v.b.v) && finite_all(v.b.w) && finite_all(v.b.dp);
}

void contact_store(contact_view v)
{
    solver_body_store(v.bodies.x, v.a);
    solver_body_store(v.bodies.y, v.b);
}

// Warm start of pair p in every substep: apply the impulses its points hold (last step's,
// copied by the narrowphase, on the first substep; the previous substep's after). Every
// constraint is warm-started in a sweep of its own before any is solved: a constraint solved
// while a neighbour's warm start is still missing sees that neighbour falling, and a stack
// then sinks at a steady speed. The first substep also starts the step's impulse total.
void warm_start_contact(uint p, uint substep)
{
    contact_view v = contact_load(p);
    if (!contact_finite(v)) return;
    for (uint k = 0u; k < v.count; k++) {
        vec4 impulse = manifolds[p].impulse[k];
        vec3 j = v.n * impulse.x + v.c.tangent1.xyz * impulse.y + v.c.tangent2.xyz * impulse.z;
        apply_impulse(v.a, v.b, v.c.p[k].ra.xyz, v.c.p[k].rb.xyz, j);
        if (substep == 0u) manifolds[p].impulse[k].w = 0.0;
    }
    contact_store(v);
}

// Separation of point k now: the prepared separation plus how far the substeps have moved
// the two ends of its lever arms apart along the normal (rotations turn the arms).
float current_separation(contact_view v, uint k)
{
    vec3 ra = v.c.p[k].ra.xyz, rb = v.c.p[k].rb.xyz;
    vec3 d = (v.b.dp - v.a.dp) + (quat_rotate(v.b.dq, rb) - quat_rotate(v.a.dq, ra));
    return dot(d, v.n) + v.c.p[k].rb.w;
}

// The normal impulse of point k towards a relative normal velocity vn with the soft step's
// rules (Box2D v3): a speculative point (apart) may close its gap within the substep; a
// touching one is pushed out as a damped spring (params.soft: bias rate, mass scale, impulse
// scale) no faster than params.contact.z, or, when relaxing, only kept from approaching.
float normal_increment(contact_view v, uint k, float vn, float accumulated, bool relax)
{
    float s = current_separation(v, k), mass = v.c.p[k].ra.w;
    float bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (s > 0.0) {
        bias = s / params.soft.w;
    } else if (!relax) {
        vec4 soft = v.a.inv_mass == 0.0 || v.b.inv_mass == 0.0 ? params.soft_static : params.soft;
        bias = max(soft.x * s, -params.contact.z);
        mass_scale = soft.y;
        impulse_scale = soft.z;
    }
    return -mass * mass_scale * (vn + bias) - impulse_scale * accumulated;
}

// One projected Gauss-Seidel pass over pair p: normal impulses (accumulated, >= 0), then
// friction clamped to a circular cone of mu times the normal impulse. A relax pass ends the
// substep and adds its impulses to the step's total (impulse.w).
void solve_contact(uint p, bool relax)
{
    contact_view v = contact_load(p);
    if (!contact_finite(v)) return;
    vec3 t1 = v.c.tangent1.xyz, t2 = v.c.tangent2.xyz;
    float friction = v.c.tangent1.w;
    vec4 impulse[TB_MAX_MANIFOLD_POINTS];
    for (uint k = 0u; k < v.count; k++) impulse[k] = manifolds[p].impulse[k];
    for (uint k = 0u; k < v.count; k++) {
        vec3 ra = v.c.p[k].ra.xyz, rb = v.c.p[k].rb.xyz;
        float vn = dot(relative_velocity(v.a, v.b, ra, rb), v.n);
        // The fastest approach, for restitution: a body that lands within the step has
        // gained speed since the step began.
        if (vn < v.c.p[k].mass.w) constraints[p].p[k].mass.w = vn;
        float total = max(impulse[k].x + normal_increment(v, k, vn, impulse[k].x, relax), 0.0);
        apply_impulse(v.a, v.b, ra, rb, v.n * (total - impulse[k].x));
        impulse[k].x = total;
    }
    for (uint k = 0u; k < v.count; k++) {
        vec3 ra = v.c.p[k].ra.xyz, rb = v.c.p[k].rb.xyz;
        vec3 dv = relative_velocity(v.a, v.b, ra, rb);
        vec2 old = impulse[k].yz;
        vec2 total = old - vec2(v.c.p[k].mass.x * dot(dv, t1), v.c.p[k].mass.y * dot(dv, t2));
        // Circular cone: the tangent impulse may not exceed mu times the normal impulse.
        float limit = friction * impulse[k].x, size = length(total);
        if (size > limit) total *= size > 0.0 ? limit / size : 0.0;
        vec2 d = total - old;
        apply_impulse(v.a, v.b, ra, rb, t1 * d.x + t2 * d.y);
        impulse[k].yz = total;
        if (relax) impulse[k].w += impulse[k].x;
    }
    for (uint k = 0u; k < v.count; k++) manifolds[p].impulse[k] = impulse[k];
    contact_store(v);
}

// After the substeps: a point that approached faster than the restitution threshold (the
// fastest relative normal velocity the solve saw, or the one before the step) and took load
// leaves at e times that speed.
void restitution_contact(uint p)
{
    // Most contacts do not bounce: their material says so before anything else is read.
    float e = constraints[p].tangent2.w;
    if (e == 0.0) return;
    contact_view v = contact_load(p);
    if (!contact_finite(v)) return;
    for (uint k = 0u; k < v.count; k++) {
        float before = min(v.c.p[k].mass.z, v.c.p[k].mass.w);
        vec4 impulse = manifolds[p].impulse[k];
        if (before > -params.contact.y || impulse.w == 0.0) continue;
        vec3 ra = v.c.p[k].ra.xyz, rb = v.c.p[k].rb.xyz;
        float vn = dot(relative_velocity(v.a, v.b, ra, rb), v.n);
        float total = max(impulse.x - v.c.p[k].ra.w * (vn + e * before), 0.0);
        apply_impulse(v.a, v.b, ra, rb, v.n * (total - impulse.x));
        manifolds[p].impulse[k].x = total;
        manifolds[p].impulse[k].w = impulse.w + (total - impulse.x);
    }
    contact_store(v);
}

// What a sweep (TB_SOLVE_*, `mode`) does to pair p in `substep`; solve.comp and solve_tail
// both go through here.
void contact_sweep(uint p, uint mode, uint substep)
{
    if (mode == TB_SOLVE_WARM) warm_start_contact(p, substep);
    else if (mode == TB_SOLVE_RESTITUTION) restitution_contact(p);
    else solve_contact(p, mode == TB_SOLVE_RELAX);
}

#endif
