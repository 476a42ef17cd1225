#version 450
#extension GL_GOOGLE_include_directive : require
// Solver data of every constraint of the step (pairs with points), from its manifold and
// the velocities before the step's forces. Per pair, dispatched with counters.pair_dispatch;
// writes constraints[p]: friction basis, lever arms, effective masses, the adjusted
// separation the substeps track (see contact.glsl) and the relative normal velocity before
// the step, which restitution answers.
#include "colouring.glsl"
#include "bodies.glsl"

vec3 point_velocity(solver_body b, vec3 r)
{
    return b.v + cross(b.w, r);
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
        c.p[k].ra = vec4(ra, solver_effective_mass(a, b, ra, rb, n));
        c.p[k].rb = vec4(rb, s - dot(rb - ra, n));
        c.p[k].mass = vec4(solver_effective_mass(a, b, ra, rb, t1),
                           solver_effective_mass(a, b, ra, rb, t2), vn, vn);
    }
    constraints[p] = c;
}
