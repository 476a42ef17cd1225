#version 450
#extension GL_GOOGLE_include_directive : require
// Per pair, after each sweep of the block solver over the colours: the multipliers take the
// forces the rows now have (lambda <- f), and a point still in contact stiffens by
// params.block.y (per metre of its normal error, in units of its effective mass over dt^2)
// up to params.block.z; the pair's stiffest point is kept for the next step (axis.w). The
// impulses' w is the step's normal impulse so far (f_n dt). After the last sweep
// (push.args.x = 1) each point keeps, for the next step, its tangential slip while it sticks
// (none once it slides: it sticks anew wherever it stops).
#include "block.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void main()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || step_aborted()) return;
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
        if (push.args.x != 0u) slip[k] = on.y ? C.yz : vec2(0.0);
    }
    if (push.args.x != 0u) {
        manifolds[p].slip[0] = vec4(slip[0], slip[1]);
        manifolds[p].slip[1] = vec4(slip[2], slip[3]);
    }
    manifolds[p].axis.w = floatBitsToUint(stiffest);
}
