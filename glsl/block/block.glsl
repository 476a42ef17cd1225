// The block solver (augmented vertex block descent, Giles, Diaz and Yuksel 2025): each
// dynamic body in turn moves to the pose that minimises its inertia's energy plus that of
// its contacts, one 6x6 Newton step on the body alone; bodies of one colour share no
// contact and move in parallel. A contact is a hard constraint reached by an augmented
// Lagrangian: a stiffness that grows while the contact is violated, and a force (the
// multiplier) that keeps what the stiffness found, carried from step to step, so a deep pile
// holds its load without sinking. Shared by glsl/block/*.comp.
//
// A contact point has three rows, C = (separation, and the displacements of b against a
// along the two friction directions since the step began). Its forces are
//     f_n = max(0, lambda_n - k C_n),   f_t = lambda_t - k C_t inside the cone |f_t| <= mu f_n,
// with lambda the multipliers (kept as impulses lambda * dt in manifolds[p].impulse) and k the
// point's stiffness (constraints[p].p[k].mass.w, N/m). Positions are the substep records'
// delta_position and delta_rotation: how far each body has moved since the step began.
#ifndef TB_BLOCK_GLSL
#define TB_BLOCK_GLSL

#include "world.glsl"
#include "quat.glsl"

bool block_dynamic(uint i)
{
    return body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC);
}

// The body at the other end of entry e of a contact list.
uint block_other(uint e)
{
    uvec2 ab = pairs[pair_half_base() + (e & ~TB_BLOCK_SIDE_B)].xy;
    return (e & TB_BLOCK_SIDE_B) != 0u ? ab.x : ab.y;
}

// The angle times the axis of unit quaternion q (q and -q alike).
vec3 rotation_vector(vec4 q)
{
    if (q.w < 0.0) q = -q;
    float s = length(q.xyz);
    if (s < 1e-7) return 2.0 * q.xyz;
    return (2.0 * atan(s, q.w) / s) * q.xyz;
}

// The unit quaternion turning by angle |v| about v.
vec4 quat_of_rotation_vector(vec3 v)
{
    float angle = length(v);
    if (angle < 1e-7) return normalize(vec4(0.5 * v, 1.0));
    return vec4(v * (sin(0.5 * angle) / angle), cos(0.5 * angle));
}

// How far the point at lever arm r (world, at the step's start) has moved with its body,
// to first order in the turn: the rows are linear in the motion, with the Jacobian the solve
// uses. (The exact turn, quat_rotate(dq, r) - r, bends the normal row by |r| (1 - cos angle):
// a sphere spinning 18 rad/s then seems to leave its neighbour by 2 cm a step and sinks into
// it, though a sphere's surface does not move as it spins.)
vec3 moved_by(vec3 dp, vec4 dq, vec3 r)
{
    return dp + cross(rotation_vector(dq), r);
}

// Point k's static friction slip, carried from step to step (tb_gpu_manifold.slip).
vec2 block_slip(uint p, uint k)
{
    vec4 s = manifolds[p].slip[k >> 1];
    return (k & 1u) == 0u ? s.xy : s.zw;
}

// The rows of point k of pair p whose bodies moved by (dpa, dqa) and (dpb, dqb). A
// penetration the step began with counts only in part (params.block_more.x of it is left
// to later steps), so deep contacts are pushed apart gently. The friction rows count from
// where the point began to stick, so a load on a slope cannot creep a little every step.
vec3 block_rows(tb_gpu_constraint c, vec3 n, uint p, uint k, vec3 dpa, vec4 dqa, vec3 dpb,
                vec4 dqb)
{
    vec3 ra = c.p[k].ra.xyz, rb = c.p[k].rb.xyz;
    vec3 d = moved_by(dpb, dqb, rb) - moved_by(dpa, dqa, ra);
    float s = c.p[k].rb.w + dot(rb - ra, n);
    if (s < 0.0) s *= 1.0 - params.block_more.x;
    vec2 slip = block_slip(p, k) * params.block_more.y;
    return vec3(s + dot(d, n), slip.x + dot(d, c.tangent1.xyz), slip.y + dot(d, c.tangent2.xyz));
}


// The forces of a point with multipliers lambda and stiffness k at rows C; `on` says
// which rows are on their constraint (not apart, not sliding): only those grow stiffer.
vec3 block_forces(vec3 lambda, float k, vec3 C, float friction, out bvec3 on)
{
    float fn = max(lambda.x - k * C.x, 0.0);
    vec2 ft = lambda.yz - k * C.yz;
    float limit = friction * fn, size = length(ft);
    bool sliding = size > limit;
    if (sliding) ft *= size > 0.0 ? limit / size : 0.0;
    on = bvec3(fn > 0.0, !sliding && fn > 0.0, !sliding && fn > 0.0);
    return vec3(fn, ft);
}

// Step length, and effective mass over dt^2: the stiffness unit of a contact.
float block_h()
{
    return params.soft.w;
}

float block_stiffness_unit(tb_gpu_constraint c, uint k)
{
    float h = block_h();
    return c.p[k].ra.w / (h * h);
}

// The multipliers' update of pair p from where its bodies are now, once a sweep has moved
// both (solve.comp runs it from the later of the two): the multipliers take the forces the
// rows now have (lambda <- f), and a point still in contact stiffens by params.block.y (per
// metre of its normal error, in units of its effective mass over dt^2) up to params.block.z;
// the pair's stiffest point is kept for the next step (axis.w). The impulses' w is the
// step's normal impulse so far (f_n dt). After the last sweep (`last`) each point keeps, for
// the next step, its tangential slip while it sticks (none once it slides).
void block_dual(uint p, bool last)
{
    uint count = min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS));
    if (count == 0u) return;
    uvec2 ab = pairs[pair_half_base() + p].xy;
    tb_gpu_solver_body a = solver_bodies[ab.x], b = solver_bodies[ab.y];
    tb_gpu_constraint c = constraints[p];
    vec3 n = manifolds[p].normal.xyz;
    float h = block_h(), stiffest = 0.0;
    vec2 slip[TB_MAX_MANIFOLD_POINTS];
    for (uint k = 0u; k < uint(TB_MAX_MANIFOLD_POINTS); k++) slip[k] = vec2(0.0);
    for (uint k = 0u; k < count; k++) {
        vec3 C = block_rows(c, n, p, k, a.delta_position.xyz, a.delta_rotation,
                            b.delta_position.xyz, b.delta_rotation);
        float stiffness = c.p[k].mass.w;
        bvec3 on;
        vec3 f = block_forces(manifolds[p].impulse[k].xyz / h, stiffness, C, c.tangent1.w, on);
        manifolds[p].impulse[k] = vec4(f * h, f.x * h);
        float unit = block_stiffness_unit(c, k);
        if (on.x) {
            stiffness = min(stiffness + params.block.y * unit * abs(C.x), params.block.z * unit);
            constraints[p].p[k].mass.w = stiffness;
        }
        if (unit > 0.0) stiffest = max(stiffest, stiffness / unit);
        if (last) slip[k] = on.y ? C.yz : vec2(0.0);
    }
    if (last) {
        manifolds[p].slip[0] = vec4(slip[0], slip[1]);
        manifolds[p].slip[1] = vec4(slip[2], slip[3]);
    }
    manifolds[p].axis.w = floatBitsToUint(stiffest);
}

#endif
