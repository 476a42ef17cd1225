#version 450
#extension GL_GOOGLE_include_directive : require
// Solver data of every constraint of the step (pairs with points), from its manifold and
// the velocities after gravity: friction basis, lever arms, effective masses and the normal
// velocity targets. Per pair, dispatched with counters.pair_dispatch; writes constraints[p].
//
// Real velocity target of a point (relative normal velocity vn = (vb - va) . n after the solve):
// - touching or penetrating (s <= 0): vn >= 0, no positional bias (recovery is split, below);
// - speculative (s > 0): the gap may close within the step, vn >= -s / dt;
// - restitution: when e > 0, the approach speed before the solve exceeds params.contact.y and
//   the point reaches the surface within the step, vn >= -e * vn_before (a speculative point
//   thus bounces up to s early, at most the contact margin; with e = 0 it lands exactly).
// Split target: params.contact.w * max(-(s + slop), 0) / dt, slop = params.contact.z.
#include "colouring.glsl"
#include "bodies.glsl"

vec3 point_velocity(solver_body b, vec3 r)
{
    return b.v + cross(b.w, r);
}

float velocity_target(float s, float vn, float restitution, float dt)
{
    float target = s > 0.0 ? -s / dt : 0.0;
    bool bounces = restitution > 0.0 && -vn > params.contact.y && -vn * dt >= s;
    return bounces ? max(target, -restitution * vn) : target;
}

void main()
{
    if (step_aborted()) return;
    uint p = pair_thread_index();
    if (p >= counters.state.z) return;
    uint at = pair_half_base() + p;
    tb_gpu_manifold m = manifolds[p];
    uint count = min(m.info.x, uint(TB_MAX_MANIFOLD_POINTS));
    if (count == 0u) return;
    uvec4 pair = pairs[at];
    solver_body a = solver_body_from_arrays(pair.x), b = solver_body_from_arrays(pair.y);
    vec3 pa = body_pos[pair.x].xyz, pb = body_pos[pair.y].xyz;
    vec3 n = m.normal.xyz, t1, t2;
    tangent_basis(n, t1, t2);
    float restitution = uintBitsToFloat(m.info.w);
    float dt = params.gravity.w;
    tb_gpu_constraint c;
    c.tangent1 = vec4(t1, m.normal.w);
    c.tangent2 = vec4(t2, restitution);
    for (uint k = 0u; k < TB_MAX_MANIFOLD_POINTS; k++) {
        if (k >= count) {
            c.p[k].ra = vec4(0.0);
            c.p[k].rb = vec4(0.0);
            c.p[k].mass = vec4(0.0);
            continue;
        }
        vec3 point = m.point[k].xyz;
        float s = m.point[k].w;
        vec3 ra = point - pa, rb = point - pb;
        float vn = dot(point_velocity(b, rb) - point_velocity(a, ra), n);
        float split = params.contact.w * max(-(s + params.contact.z), 0.0) / dt;
        c.p[k].ra = vec4(ra, solver_effective_mass(a, b, ra, rb, n));
        c.p[k].rb = vec4(rb, velocity_target(s, vn, restitution, dt));
        c.p[k].mass = vec4(solver_effective_mass(a, b, ra, rb, t1),
                           solver_effective_mass(a, b, ra, rb, t2), split, 0.0);
    }
    constraints[p] = c;
}
