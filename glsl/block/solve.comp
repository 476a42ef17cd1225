#version 450
#extension GL_GOOGLE_include_directive : require
// The block solver's sweep over the bodies of one colour (push.args.x = c; push.args.y = 1
// in the last sweep of the step): thread t <
// counters.colour[c].x moves body block_list[colour[c].y + t] by one Newton step on
//     E(x) = |x - y|^2_M / (2 dt^2) + sum over its contacts of the rows' energies,
// y the inertial pose (where its velocity after gravity would take it), with the other
// bodies held where they are. Gradient and Hessian are 6x6 (position, rotation vector),
// solved by block elimination. The Hessian keeps a row's stiffness even while its force is
// clamped (a contact apart, a point sliding): without it, a contact whose force has just
// dropped to zero lets the Newton step jump through it, and a body landing on the floor
// sinks into it with the multiplier swinging between nothing and many times its weight.
#include "block.glsl"
#include "../integrate/motion.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

struct newton {
    mat3 A, B, D;   // Hessian blocks: position-position, position-rotation, rotation-rotation
    vec3 gl, ga;    // gradient: position, rotation
};

// World inertia of body i (infinite moments made very large).
mat3 world_inertia(uint i)
{
    mat3 r = quat_to_mat3(body_rot[i]);
    vec3 inv = body_inv_inertia[i].xyz;
    vec3 d = vec3(inv.x > 0.0 ? 1.0 / inv.x : 1e20, inv.y > 0.0 ? 1.0 / inv.y : 1e20,
                  inv.z > 0.0 ? 1.0 / inv.z : 1e20);
    return r * mat3(d.x, 0.0, 0.0, 0.0, d.y, 0.0, 0.0, 0.0, d.z) * transpose(r);
}

newton inertial_part(uint i, tb_gpu_solver_body s, float h)
{
    newton e;
    float m = 1.0 / s.linear.w, scale = 1.0 / (h * h);
    e.A = mat3(m * scale);
    e.B = mat3(0.0);
    e.D = world_inertia(i) * scale;
    e.gl = m * scale * (s.delta_position.xyz - h * s.linear.xyz);
    vec4 target = rotation_of(s.angular.xyz, h, params.limits.x);
    vec4 off = quat_mul(s.delta_rotation, vec4(-target.xyz, target.w));
    e.ga = e.D * rotation_vector(off);
    return e;
}

// Row u of a point at lever arm r (at the step's start), sign +1 on body b and -1 on body a:
// the rows are linear in the motion (block_rows), so this Jacobian is exact and the Hessian
// needs no geometric stiffness.
void add_row(inout newton e, vec3 u, vec3 r, float sign, float f, float k)
{
    vec3 jl = sign * u, ja = sign * cross(r, u);
    e.gl -= f * jl;
    e.ga -= f * ja;
    e.A += k * outerProduct(jl, jl);
    e.B += k * outerProduct(jl, ja);
    e.D += k * outerProduct(ja, ja);
}

void add_contact(inout newton e, uint entry, tb_gpu_solver_body me)
{
    uint p = entry & ~TB_BLOCK_SIDE_B;
    bool is_b = (entry & TB_BLOCK_SIDE_B) != 0u;
    tb_gpu_solver_body other = solver_bodies[block_other(entry)];
    tb_gpu_constraint c = constraints[p];
    vec3 n = manifolds[p].normal.xyz;
    uint count = min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS));
    float h = block_h(), sign = is_b ? 1.0 : -1.0;
    vec3 dpa = is_b ? other.delta_position.xyz : me.delta_position.xyz;
    vec3 dpb = is_b ? me.delta_position.xyz : other.delta_position.xyz;
    vec4 dqa = is_b ? other.delta_rotation : me.delta_rotation;
    vec4 dqb = is_b ? me.delta_rotation : other.delta_rotation;
    for (uint k = 0u; k < count; k++) {
        vec3 C = block_rows(c, n, p, k, dpa, dqa, dpb, dqb);
        float stiffness = c.p[k].mass.w;
        bvec3 on;
        vec3 f = block_forces(manifolds[p].impulse[k].xyz / h, stiffness, C, c.tangent1.w, on);
        vec3 r = is_b ? c.p[k].rb.xyz : c.p[k].ra.xyz;
        add_row(e, n, r, sign, f.x, stiffness);
        add_row(e, c.tangent1.xyz, r, sign, f.y, stiffness);
        add_row(e, c.tangent2.xyz, r, sign, f.z, stiffness);
    }
}

void main()
{
    if (step_aborted()) return;
    uint colour = push.args.x;
    uint t = pair_thread_index();
    if (colour >= TB_MAX_COLOURS || t >= counters.colour[colour].x) return;
    uint i = block_list[counters.colour[colour].y + t];
    tb_gpu_solver_body me = solver_bodies[i];
    newton e = inertial_part(i, me, block_h());
    uint first = block_start[i], n = block_fill[i];
    for (uint k = 0u; k < n; k++) add_contact(e, block_entries[first + k], me);
    // [A B; B^T D] [x; y] = [gl; ga] by the Schur complement of A.
    mat3 Ai = inverse(e.A), Bt = transpose(e.B);
    mat3 S = e.D - Bt * Ai * e.B;
    vec3 y = inverse(S) * (e.ga - Bt * (Ai * e.gl));
    vec3 x = Ai * (e.gl - e.B * y);
    solver_bodies[i].delta_position.xyz = me.delta_position.xyz - x;
    solver_bodies[i].delta_rotation = normalize(quat_mul(quat_of_rotation_vector(-y),
                                                         me.delta_rotation));
    // The multipliers of the contacts whose other body has already moved in this sweep (a
    // static one, or one of an earlier colour) are updated here, by the last of their bodies
    // to move: both are where the sweep leaves them, so this is the update a pass of its own
    // after the sweep would make (bit for bit), without that pass's dispatch and reads.
    for (uint k = 0u; k < n; k++) {
        uint entry = block_entries[first + k];
        uint word = body_colour[block_other(entry)];
        if (word == TB_BLOCK_NOT_SOLVED || (word & 0xffu) < colour)
            block_dual(entry & ~TB_BLOCK_SIDE_B, push.args.y != 0u);
    }
}
