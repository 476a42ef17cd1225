// The block solver's sweep over the bodies of one colour (push.args.x = c; push.args.y what
// the sweep is, sweep_set; push.args.z the over-relaxation, see over_relaxation):
// body block_list[colour[c].y + b].x, b < counters.colour[c].x, moves by one Newton step on
//     E(x) = |x - y|^2_M / (2 dt^2) + sum over its contacts of the rows' energies,
// y the inertial pose (where its velocity after gravity would take it), with the other
// bodies held where they are. Gradient and Hessian are 6x6 (position, rotation vector),
// solved by block elimination. The Hessian keeps a row's stiffness even while its force is
// clamped (a contact apart, a point sliding): without it, a contact whose force has just
// dropped to zero lets the Newton step jump through it, and a body landing on the floor
// sinks into it with the multiplier swinging between nothing and many times its weight.
//
// BLOCK_LANES neighbouring invocations of a subgroup share a body: lane j takes the contact
// points j, j + BLOCK_LANES, ... of the body's list (an entry per point) and sums their
// rows, and the lanes add up their sums by a butterfly of shuffles, so every lane ends with
// the same totals, bit for bit, in an order fixed by the list (runs stay repeatable).
// A body's points are spread over many threads instead of one thread walking them all: a
// colour of 10,000 bodies keeps 80,000 threads busy, each with a short chain of loads.
// push.args.x = TB_MAX_COLOURS: the tail, the bodies left over once every colour is taken:
// on a GPU block/solve_tail's (solve_tail below), on a CPU device solve_tail_narrow's.
//
// The sweep's shaders (block/solve, block/solve_16, block/solve_32) are this file with
// BLOCK_LANES lanes a body (TB_BLOCK_LANES, block.glsl); block/solve_fused (TB_BLOCK_FUSED)
// runs every sweep of a small world's step in one workgroup (its main, at the end). Needs
// GL_KHR_shader_subgroup_basic and _shuffle, which they enable.
#ifndef TB_BLOCK_SOLVE_GLSL
#define TB_BLOCK_SOLVE_GLSL

#include "listed.glsl"
#ifdef TB_BLOCK_JOINTS
#include "joint.glsl"
#endif
#include "../integrate/motion.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

// What this sweep is (TB_BLOCK_SWEEP_*): each main sets it from push.args.y, the fused solve
// from its count of the sweeps. In a world with joints the step's first sweeps (15, at most
// half of them: src/solver/block.c) hold each joint's hard rows at the error the step
// began with (joint_hold): the bodies find the motion that keeps the joints as they were,
// and the multipliers the load, before the later sweeps close the error. Sweeps that all
// close it (as the contacts' do) blew up structures too deep for the sweeps to reach across
// (a 1,000-link chain, a 100 x 100 net): where the error cannot be closed in a step, each
// sweep added k C to the multipliers and grew the stiffness, and both, carried to the next
// step, pulled harder than the load (docs/joints.md).
bool sweep_is_last = false;
bool sweep_holds = false;

void sweep_set(uint bits)
{
    sweep_is_last = (bits & TB_BLOCK_SWEEP_LAST) != 0u;
    sweep_holds = (bits & TB_BLOCK_SWEEP_HOLDS) != 0u;
}

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

newton no_newton()
{
    newton e;
    e.A = mat3(0.0);
    e.B = mat3(0.0);
    e.D = mat3(0.0);
    e.gl = vec3(0.0);
    e.ga = vec3(0.0);
    return e;
}

// The inertia's rows of body i (state s). Its turn beyond the free turn (block_target),
// theta, changes its spin by theta / h, and a spinning body answers a change of spin with the
// gyroscopic term: Euler's equations I dw/dt + w x I w = torque, the turn's part of them
// linearised about the free spin w, ask
//     (I + h (skew(w) I - skew(I w))) theta / h^2 = torque   (skew: integrate/motion.glsl)
// (one Newton step on the body's angular momentum equation). Without the gyroscopic part a
// fast top took the torque of its tip as a plain push and fell over instead of precessing
// (test_integrate, 40 rad/s at 60 Hz: -0.19 rad/s of precession instead of 1.22, the tilt
// off by 13 degrees; with it 1.18 rad/s and 1.5 degrees; the soft step's substeps hand the
// torque to the spin in four pieces, the block solver in one). For a sphere, or a body at
// rest, it is the inertia alone. The matrix is not symmetric; the block elimination in
// solve_body does not need it to be.
void add_inertia(inout newton e, uint i, tb_gpu_solver_body s, float h)
{
    float m = 1.0 / s.linear.w, scale = 1.0 / (h * h);
    mat3 I = world_inertia(i);
    vec3 w = s.angular.xyz;
    mat3 D = (I + h * (skew(w) * I - skew(I * w))) * scale;
    e.A += mat3(m * scale);
    e.D += D;
    e.gl += m * scale * (s.delta_position.xyz - block_target[2u * i].xyz);
    vec4 target = block_target[2u * i + 1u];
    vec4 off = quat_mul(s.delta_rotation, vec4(-target.xyz, target.w));
    e.ga += D * rotation_vector(off);
}

// What a body's contact points add to its Newton step, summed. A point's three rows (the
// normal and the friction directions, orthonormal) share its stiffness k and its lever arm r
// (at the step's start; sign +1 on body b, -1 on body a), and the rows are linear in the
// motion (block_rows), so their Jacobian is exact and their Hessian sums in closed form:
//     sum_u k u u^T = k I,   sum_u k u (r x u)^T = -k skew(r),
//     sum_u k (r x u)(r x u)^T = k (|r|^2 I - r r^T)
// (the sign is squared away), and the gradient is the point's force F and its moment r x F.
// So the points of a body sum 16 numbers, not the 33 of three outer products a row: the
// stiffness (A = k I), the stiffness-weighted lever arm (B = -skew(kr)), the rotation
// block's diagonal and off-diagonal, and the gradient.
struct point_sums {
    float k;
    vec3 kr;
    vec3 d_diagonal;   // D[0][0], D[1][1], D[2][2]
    vec3 d_off;        // D[1][2], D[0][2], D[0][1]
    vec3 gl, ga;
};

point_sums no_point_sums()
{
    return point_sums(0.0, vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
}

void add_rows(inout point_sums s, vec3 r, float k, vec3 F)
{
    vec3 r2 = r * r;
    s.k += k;
    s.kr += k * r;
    s.d_diagonal += k * (r2.yzx + r2.zxy);
    s.d_off -= k * (r.yxx * r.zzy);
    s.gl -= F;
    s.ga -= cross(r, F);
}

newton newton_of(point_sums s)
{
    newton e;
    e.A = mat3(s.k);
    e.B = -skew(s.kr);
    vec3 d = s.d_diagonal, o = s.d_off;
    e.D = mat3(d.x, o.z, o.y, o.z, d.y, o.x, o.y, o.x, d.z);
    e.gl = s.gl;
    e.ga = s.ga;
    return e;
}

newton newton_of(newton e)
{
    return e;
}

// In a sweep with joints the points add to the joints' general blocks (a joint's rows do
// not share one stiffness and lever arm); without, to the sums above.
void add_rows(inout newton e, vec3 r, float k, vec3 F)
{
    point_sums s = no_point_sums();
    add_rows(s, r, k, F);
    newton p = newton_of(s);
    e.A += p.A;
    e.B += p.B;
    e.D += p.D;
    e.gl += p.gl;
    e.ga += p.ga;
}

#ifdef TB_BLOCK_JOINTS
#define body_sums newton
#define no_body_sums no_newton
#else
#define body_sums point_sums
#define no_body_sums no_point_sums
#endif

void add_point(inout body_sums e, block_point q, bool is_b, vec3 dpa, vec3 va, vec3 dpb,
               vec3 vb)
{
    vec3 C = block_rows(q, dpa, va, dpb, vb);
    bvec3 on;
    vec3 f = block_forces(q.lambda, q.stiffness, C, q.friction, on);
    vec3 r = is_b ? q.rb : q.ra;
    float sign = is_b ? 1.0 : -1.0;
    add_rows(e, r, q.stiffness, sign * (f.x * q.n + f.y * q.t1 + f.z * q.t2));
}

// The sums over groups of `lanes` neighbouring lanes (a power of two), by a butterfly of
// shuffles: every lane of a group ends with the same sum, bit for bit.
vec3 butterfly_sum(vec3 v, uint lanes)
{
    for (uint m = lanes >> 1; m > 0u; m >>= 1) v += subgroupShuffleXor(v, m);
    return v;
}

mat3 butterfly_sum(mat3 a, uint lanes)
{
    return mat3(butterfly_sum(a[0], lanes), butterfly_sum(a[1], lanes), butterfly_sum(a[2], lanes));
}

newton butterfly_sum(newton e, uint lanes)
{
    e.A = butterfly_sum(e.A, lanes);
    e.B = butterfly_sum(e.B, lanes);
    e.D = butterfly_sum(e.D, lanes);
    e.gl = butterfly_sum(e.gl, lanes);
    e.ga = butterfly_sum(e.ga, lanes);
    return e;
}

// The point sums over the TB_BLOCK_LANES lanes of a body without a butterfly of each of
// the 16 numbers: a reduce-scatter and then an allgather. At each level of the
// reduce-scatter a lane sends its partner the half of its numbers the partner keeps and
// adds the partner's to the half it keeps; after log2(16) levels each number's total is on
// one lane (on 32 lanes, on a pair that add theirs alike), and the allgather hands the
// totals back, so every lane holds the same totals, bit for bit. 8 lanes shuffle 28
// numbers instead of 48 (the butterfly of each). The levels use literal indices, so the
// numbers stay in registers: the same sums through loops over an array indexed by a
// level's count went to local memory and made the deep pile's solve five times slower.
#define SUM_WORDS 16u
#define KEEP1(k, h, m) { float mine = upper ? v[(k) + (h)] : v[k];                     \
    float theirs = subgroupShuffleXor(upper ? v[k] : v[(k) + (h)], m); v[k] = mine + theirs; }
#define KEEP2(k, h, m) KEEP1(k, h, m) KEEP1((k) + 1, h, m)
#define KEEP4(k, h, m) KEEP2(k, h, m) KEEP2((k) + 2, h, m)
#define KEEP8(k, h, m) KEEP4(k, h, m) KEEP4((k) + 4, h, m)
#define BACK1(k, h, m) { float theirs = subgroupShuffleXor(v[k], m);                   \
    v[(k) + (h)] = upper ? v[k] : theirs; v[k] = upper ? theirs : v[k]; }
#define BACK2(k, h, m) BACK1(k, h, m) BACK1((k) + 1, h, m)
#define BACK4(k, h, m) BACK2(k, h, m) BACK2((k) + 2, h, m)
#define BACK8(k, h, m) BACK4(k, h, m) BACK4((k) + 4, h, m)
#define LEVEL(step, m) { bool upper = (gl_SubgroupInvocationID & (m)) != 0u; step; }

void scatter_gather_sum(inout float v[SUM_WORDS])
{
    const uint L = uint(TB_BLOCK_LANES);
    LEVEL(KEEP8(0, 8, L / 2u), L / 2u)
    LEVEL(KEEP4(0, 4, L / 4u), L / 4u)
    LEVEL(KEEP2(0, 2, L / 8u), L / 8u)
#if TB_BLOCK_LANES >= 16
    LEVEL(KEEP1(0, 1, L / 16u), L / 16u)
#endif
#if TB_BLOCK_LANES >= 32
    v[0] += subgroupShuffleXor(v[0], L / 32u);
#endif
#if TB_BLOCK_LANES >= 16
    LEVEL(BACK1(0, 1, L / 16u), L / 16u)
#endif
    LEVEL(BACK2(0, 2, L / 8u), L / 8u)
    LEVEL(BACK4(0, 4, L / 4u), L / 4u)
    LEVEL(BACK8(0, 8, L / 2u), L / 2u)
}

point_sums scatter_gather_sum(point_sums s)
{
    float v[SUM_WORDS];
    v[0] = s.k;
    v[1] = s.kr.x; v[2] = s.kr.y; v[3] = s.kr.z;
    v[4] = s.d_diagonal.x; v[5] = s.d_diagonal.y; v[6] = s.d_diagonal.z;
    v[7] = s.d_off.x; v[8] = s.d_off.y; v[9] = s.d_off.z;
    v[10] = s.gl.x; v[11] = s.gl.y; v[12] = s.gl.z;
    v[13] = s.ga.x; v[14] = s.ga.y; v[15] = s.ga.z;
    scatter_gather_sum(v);
    return point_sums(v[0], vec3(v[1], v[2], v[3]), vec3(v[4], v[5], v[6]),
                      vec3(v[7], v[8], v[9]), vec3(v[10], v[11], v[12]),
                      vec3(v[13], v[14], v[15]));
}

// The sums over the BLOCK_LANES lanes of a body; a sweep's subgroup narrower than the
// shader's lanes (or a CPU device's one lane a body) adds them by the butterfly.
newton lanes_sum(point_sums s)
{
    if (BLOCK_LANES != uint(TB_BLOCK_LANES)) return butterfly_sum(newton_of(s), BLOCK_LANES);
    return newton_of(scatter_gather_sum(s));
}

// The Newton blocks' sums over the BLOCK_LANES lanes of a body (a sweep with joints). Their
// A and D blocks are symmetric until the inertia joins them (newton_step): a contact's and
// a joint row's k u u^T are, to the bit. So 27 numbers, padded to 32, go through the
// reduce-scatter and allgather above: 56 shuffles, where a butterfly of each block's 33
// took 99.
#define KEEP16(k, h, m) KEEP8(k, h, m) KEEP8((k) + 8, h, m)
#define BACK16(k, h, m) BACK8(k, h, m) BACK8((k) + 8, h, m)

void scatter_gather_sum_32(inout float v[32])
{
    const uint L = uint(TB_BLOCK_LANES);   // 8 (lanes_sum)
    LEVEL(KEEP16(0, 16, L / 2u), L / 2u)
    LEVEL(KEEP8(0, 8, L / 4u), L / 4u)
    LEVEL(KEEP4(0, 4, L / 8u), L / 8u)
    LEVEL(BACK4(0, 4, L / 8u), L / 8u)
    LEVEL(BACK8(0, 8, L / 4u), L / 4u)
    LEVEL(BACK16(0, 16, L / 2u), L / 2u)
}

mat3 symmetric(float xx, float yy, float zz, float xy, float xz, float yz)
{
    return mat3(xx, xy, xz, xy, yy, yz, xz, yz, zz);
}

newton lanes_sum(newton e)
{
    if (TB_BLOCK_LANES != 8 || BLOCK_LANES != uint(TB_BLOCK_LANES))
        return butterfly_sum(e, BLOCK_LANES);
    float v[32];
    v[0] = e.A[0][0]; v[1] = e.A[1][1]; v[2] = e.A[2][2];
    v[3] = e.A[1][0]; v[4] = e.A[2][0]; v[5] = e.A[2][1];
    v[6] = e.D[0][0]; v[7] = e.D[1][1]; v[8] = e.D[2][2];
    v[9] = e.D[1][0]; v[10] = e.D[2][0]; v[11] = e.D[2][1];
    v[12] = e.B[0].x; v[13] = e.B[0].y; v[14] = e.B[0].z;
    v[15] = e.B[1].x; v[16] = e.B[1].y; v[17] = e.B[1].z;
    v[18] = e.B[2].x; v[19] = e.B[2].y; v[20] = e.B[2].z;
    v[21] = e.gl.x; v[22] = e.gl.y; v[23] = e.gl.z;
    v[24] = e.ga.x; v[25] = e.ga.y; v[26] = e.ga.z;
    v[27] = 0.0; v[28] = 0.0; v[29] = 0.0; v[30] = 0.0; v[31] = 0.0;
    scatter_gather_sum_32(v);
    newton t;
    t.A = symmetric(v[0], v[1], v[2], v[3], v[4], v[5]);
    t.D = symmetric(v[6], v[7], v[8], v[9], v[10], v[11]);
    t.B = mat3(v[12], v[13], v[14], v[15], v[16], v[17], v[18], v[19], v[20]);
    t.gl = vec3(v[21], v[22], v[23]);
    t.ga = vec3(v[24], v[25], v[26]);
    return t;
}

// How far a body moves along its Newton step (push.args.z, in thousandths; 0: the whole
// step). A little beyond it (1.2) the sweeps converge faster on stacks: a column's bodies,
// each stopped short by its neighbours' old positions, move together sooner. Measured on an
// H100 (docs/performance.md): the columns scene 88 -> 100 % at rest, the deep pile of
// 4,000 90.6 -> 99.6 %, the base-100 pyramid's drift 4.1 -> 4.0 cm, at the same cost;
// at 1.3 a hull stopped by a wall without gravity crept away from it (3.7 cm/s), and at
// 1.6 the columns fell.
float over_relaxation()
{
    return push.args.z == 0u ? 1.0 : float(push.args.z) / 1000.0;
}

// The motion (displacement, rotation vector) of body o since the step began.
void motion_of(uint o, out vec3 dp, out vec3 v)
{
    dp = solver_bodies[o].delta_position.xyz;
    v = rotation_vector(solver_bodies[o].delta_rotation);
}

// Entry `entry` of the body's list as the sweep sees it: the point, the other body and
// how far that one has moved (it is of another colour, or static: it stays put during the
// dispatch).
struct item {
    uint entry, p, k, other;
    uint other_colour; // body_colour of the other body
    block_point q;
    vec3 dp, v;
};

// A joint's entry (the sweeps made with TB_BLOCK_JOINTS, block/solve_joints: a world with
// joints): p is the joint's slot and q is not loaded. The joints' code is left out of the
// sweeps of worlds without joints: in them it took registers from the contacts' and
// slowed the sweep of 100k boxes 2.3 times (H200: the deep pile's solve 4.9 -> 11.3 ms).
bool item_is_joint(uint entry)
{
#ifdef TB_BLOCK_JOINTS
    return block_is_joint(entry);
#else
    return false;
#endif
}

item item_of(uvec2 entry)
{
    item it;
    it.entry = entry.x;
    bool joint = item_is_joint(entry.x);
    it.p = joint ? block_joint_of(entry.x) : block_pair(entry.x);
    it.k = joint ? 0u : block_point_of(entry.x);
    it.other = entry.y;
    it.other_colour = body_colour[it.other];
    if (!joint) it.q = block_load(it.p, it.k);
    motion_of(it.other, it.dp, it.v);
    return it;
}

#ifndef TB_BLOCK_JOINTS
void add_item(inout body_sums e, item it, vec3 my_dp, vec3 my_v)
{
    if (block_is_b(it.entry)) {
        add_point(e, it.q, true, it.dp, it.v, my_dp, my_v);
    } else {
        add_point(e, it.q, false, my_dp, my_v, it.dp, it.v);
    }
}

// The multipliers' update of the item's point if its other body has already moved in this
// sweep (a static one, or one of an earlier place, block_order): both are where the sweep
// leaves them.
void update_item(item it, uint order, vec3 my_dp, vec3 my_v, bool last)
{
    if (!block_moved_before(it.other_colour, order)) return;
    if (block_is_b(it.entry)) block_dual(it.p, it.k, it.q, it.dp, it.v, my_dp, my_v, last);
    else block_dual(it.p, it.k, it.q, my_dp, my_v, it.dp, it.v, last);
}
#else
// A joint's rows, of its body b (is_b) or a and the other at dpa, va, dpb, vb: in the
// primal added to the body's Newton step e, in the dual (once both bodies have moved)
// their multipliers updated.
void joint_item(inout newton e, uint j, uvec2 ab, bool is_b, bool dual, vec3 dpa, vec3 va,
                vec3 dpb, vec3 vb)
{
    joint_work w = joint_work_of(dual, is_b, e.A, e.B, e.D, e.gl, e.ga, sweep_is_last,
                                 sweep_holds);
    tb_gpu_joint_state s = joint_states[j];
    joint_rows(w, j, ab, s, dpa, va, dpb, vb);
    if (dual) {
        joint_store(j, s, w);
        return;
    }
    e.A = w.A;
    e.B = w.B;
    e.D = w.D;
    e.gl = w.gl;
    e.ga = w.ga;
}

// List entry `entry` of body i (my_dp, my_v) at place `order` in the sweep: in the primal
// (dual false) its rows go into the body's Newton step e; in the dual, if its other body
// has already moved in this sweep (a static one, or one of an earlier place, block_order),
// its multipliers are updated with both where the sweep leaves them.
void sweep_item(inout newton e, uvec2 entry, uint i, uint order, bool dual, vec3 my_dp,
                vec3 my_v)
{
    if (dual && !block_moved_before(body_colour[entry.y], order)) return;
    item it = item_of(entry);
    bool is_b = block_is_b(it.entry);
    vec3 dpa = is_b ? it.dp : my_dp, va = is_b ? it.v : my_v;
    vec3 dpb = is_b ? my_dp : it.dp, vb = is_b ? my_v : it.v;
    if (item_is_joint(it.entry))
        joint_item(e, it.p, is_b ? uvec2(it.other, i) : uvec2(i, it.other), is_b, dual, dpa,
                   va, dpb, vb);
    else if (dual)
        block_dual(it.p, it.k, it.q, dpa, va, dpb, vb, sweep_is_last);
    else
        add_point(e, it.q, is_b, dpa, va, dpb, vb);
}
#endif

// Body i (state me) moves by the Newton step of its contacts' summed rows e and its
// inertia: its displacement and turn since the step began, in my_dp and my_dq.
void newton_step(newton e, uint i, tb_gpu_solver_body me, out vec3 my_dp, out vec4 my_dq)
{
    add_inertia(e, i, me, block_h());
    // [A B; B^T D] [x; y] = [gl; ga] by the Schur complement of A.
#ifdef TB_BLOCK_JOINTS
    mat3 Ai = inverse(e.A);
#else
    mat3 Ai = mat3(1.0 / e.A[0][0]);   // contacts and inertia alone: A = a I (point_sums)
#endif
    mat3 Bt = transpose(e.B);
    mat3 S = e.D - Bt * Ai * e.B;
    vec3 y = inverse(S) * (e.ga - Bt * (Ai * e.gl));
    vec3 x = Ai * (e.gl - e.B * y);
    // A step that is not finite (a neighbour's state, or the body's own, stopped being
    // finite) is not taken: the body stays where it is, and integrate isolates whichever
    // body is not finite at the end of the step.
    bool finite = finite_all(x) && finite_all(y);
    float relax = over_relaxation();
    my_dp = finite ? me.delta_position.xyz - relax * x : me.delta_position.xyz;
    vec4 turn = finite ? quat_of_rotation_vector(-relax * y) : vec4(0.0, 0.0, 0.0, 1.0);
    my_dq = normalize(quat_mul(turn, me.delta_rotation));
}

// Body i takes its Newton step (lane 0 of those sharing it stores it); every lane gets
// its new displacement and rotation vector.
void move_body(newton e, uint i, tb_gpu_solver_body me, uint lane, out vec3 my_dp,
               out vec3 my_v)
{
    vec4 my_dq;
    newton_step(e, i, me, my_dp, my_dq);
    if (lane == 0u) {
        solver_bodies[i].delta_position.xyz = my_dp;
        solver_bodies[i].delta_rotation = my_dq;
    }
    my_v = rotation_vector(my_dq);
}

#ifndef TB_BLOCK_JOINTS
// Body listed.x (its list: listed.y, listed.z entries), at place `order` in the sweep
// (block_order), moves by one Newton step; the BLOCK_LANES lanes that share it call this
// together, `valid` false on lanes without a body (beyond the colour's bodies).
void solve_body(uvec4 listed, uint lane, bool valid, uint order)
{
    uint i = listed.x, first = listed.y, items = listed.z;
    tb_gpu_solver_body me = solver_bodies[i];
    vec3 my_dp = me.delta_position.xyz, my_v = rotation_vector(me.delta_rotation);
    // The first pass's points stay in registers for the multipliers' update below.
    body_sums e = no_body_sums();
    item kept;
    bool has_kept = lane < items;
    if (has_kept) {
        kept = item_of(block_entries[first + lane]);
        add_item(e, kept, my_dp, my_v);
    }
    for (uint at = BLOCK_LANES + lane; at < items; at += BLOCK_LANES)
        add_item(e, item_of(block_entries[first + at]), my_dp, my_v);
    newton sums = lanes_sum(e);
    if (!valid) return;
    move_body(sums, i, me, lane, my_dp, my_v);
    // The multipliers of the contacts whose other body has already moved are updated here,
    // by the last of their bodies to move, so no pass of its own after the sweep needs a
    // dispatch and a read of every contact.
    bool last = sweep_is_last;
    if (has_kept) update_item(kept, order, my_dp, my_v, last);
    for (uint at = BLOCK_LANES + lane; at < items; at += BLOCK_LANES)
        update_item(item_of(block_entries[first + at]), order, my_dp, my_v, last);
}
#else
// Body listed.x as above, in a sweep with joints: a primal pass over its entries adds them
// up, a dual pass updates their multipliers, and each is one call of sweep_item, so the
// joints' rows are in the kernel twice, each copy specialised to its pass. No entry is kept
// in registers across the body's step, whose state is read again for it. H200, the 100 x
// 100 net of ball joints (joint_grid 10000): the sweeps took 1.10 ms a step with a call a
// pass for the kept entry and another for the rest (four copies of the rows: 255
// registers, 3 KB of spills a thread, a 920 KB kernel), 0.78 ms so (168 registers, no
// spills, 394 KB), and 1.63 ms with a single call, the pass a variable (223 registers,
// 305 KB: the rows no longer specialised); lavapipe compiles it in a quarter of the time.
void solve_body(uvec4 listed, uint lane, bool valid, uint order)
{
    uint i = listed.x, first = listed.y, items = listed.z;
    vec3 my_dp = solver_bodies[i].delta_position.xyz;
    vec3 my_v = rotation_vector(solver_bodies[i].delta_rotation);
    newton e = no_newton();
    for (uint at = lane; at < items; at += BLOCK_LANES)
        sweep_item(e, block_entries[first + at], i, order, false, my_dp, my_v);
    newton sums = lanes_sum(e);
    if (!valid) return;
    move_body(sums, i, solver_bodies[i], lane, my_dp, my_v);
    for (uint at = lane; at < items; at += BLOCK_LANES)
        sweep_item(e, block_entries[first + at], i, order, true, my_dp, my_v);
}
#endif

#ifdef TB_BLOCK_TAIL
// The tail (block/solve_tail, one workgroup of TB_BLOCK_TAIL_WORKGROUP_SIZE): the bodies
// the colouring left over, one after the other in their order in the tail; each body sees
// the moves and multipliers of the ones before it, so it is still Gauss-Seidel and
// repeatable. Only crowds have a tail (more than 64 bodies all touching one another), and
// there each body has as many points as the crowd has bodies: every invocation of the
// workgroup takes every W-th point of the body, the subgroups add theirs by the butterfly
// (every lane the same sum, bit for bit) and the workgroup adds the subgroups' sums in
// their order. One subgroup's 8 lanes a body took 24 s a step for 2,000 spheres in one
// place on an H100. The usual step has no tail and returns at once.
#define TAIL_PARTS 64u   // the most subgroups of the workgroup (4 lanes each)

struct newton_part { mat3 A, B, D; vec3 gl, ga; };
shared newton_part tail_part[TAIL_PARTS];

newton workgroup_sum(newton e)
{
    newton s = butterfly_sum(e, gl_SubgroupSize);
    newton_part p = newton_part(s.A, s.B, s.D, s.gl, s.ga);
    if (gl_SubgroupInvocationID == 0u && gl_SubgroupID < TAIL_PARTS) tail_part[gl_SubgroupID] = p;
    memoryBarrierShared();
    barrier();
    newton t = no_newton();
    for (uint k = 0u; k < min(gl_NumSubgroups, TAIL_PARTS); k++) {
        newton_part q = tail_part[k];
        t.A += q.A;
        t.B += q.B;
        t.D += q.D;
        t.gl += q.gl;
        t.ga += q.ga;
    }
    barrier();   // every invocation has read the parts before the next body writes them
    return t;
}

void solve_tail()
{
    uint count = counters.colouring.z;
    if (count == 0u) return;
    uint lane = gl_LocalInvocationIndex, lanes = gl_WorkGroupSize.x;
    uint start = block_tail_start();
    bool last = sweep_is_last;
    for (uint t = 0u; t < count; t++) {
        uvec4 listed = block_list[start + t];
        uint i = listed.x, first = listed.y, items = listed.z;
        tb_gpu_solver_body me = solver_bodies[i];
        vec3 my_dp = me.delta_position.xyz, my_v = rotation_vector(me.delta_rotation);
        uint order = uint(TB_MAX_COLOURS) + t;
#ifndef TB_BLOCK_JOINTS
        body_sums e = no_body_sums();
        for (uint at = lane; at < items; at += lanes)
            add_item(e, item_of(block_entries[first + at]), my_dp, my_v);
        move_body(workgroup_sum(newton_of(e)), i, me, lane, my_dp, my_v);
        for (uint at = lane; at < items; at += lanes)
            update_item(item_of(block_entries[first + at]), order, my_dp, my_v, last);
#else
        newton e = no_newton();
        for (uint at = lane; at < items; at += lanes)
            sweep_item(e, block_entries[first + at], i, order, false, my_dp, my_v);
        move_body(workgroup_sum(e), i, me, lane, my_dp, my_v);
        for (uint at = lane; at < items; at += lanes)
            sweep_item(e, block_entries[first + at], i, order, true, my_dp, my_v);
#endif
        memoryBarrierBuffer();
        barrier();
    }
}

void main()
{
    if (step_aborted()) return;
    sweep_set(push.args.y);
    solve_tail();
}
#elif defined(TB_BLOCK_FUSED)
// The whole solve of a small world's step in one workgroup (block/solve_fused; push.args.x
// the colours recorded, y the sweeps, z the over-relaxation): every sweep over the colours
// in order, a colour's bodies BLOCK_LANES lanes each and as many at once as the workgroup
// holds, the workgroup's barrier between two colours in place of a dispatch and the
// barrier after it. The bodies move in the same order by the same steps as in the sweeps'
// dispatches, so the results are the same to the bit (at the same lanes a body). Recorded on
// a GPU while a world has few bodies and no tail (tb_block_fuses), where a colour's launch
// and barrier (about 2.5 us) are much of its time and a step has 30 sweeps of them; one SM
// walking a large world's colours 32 bodies at a time is slower than a dispatch each, and
// on lavapipe the workgroup's barriers cost more than the dispatches they replace.
void main()
{
    if (step_aborted()) return;
    uint lane = gl_SubgroupInvocationID % BLOCK_LANES;
    uint here = (gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID) / BLOCK_LANES;
    uint at_once = gl_WorkGroupSize.x / BLOCK_LANES;
    uint sweeps = push.args.y & 0xffffu, holds = push.args.y >> TB_BLOCK_FUSED_HOLDS_SHIFT;
    for (uint sweep = 0u; sweep < sweeps; sweep++) {
        sweep_set(TB_BLOCK_SWEEP_BITS(sweep, sweeps, holds));
        for (uint c = 0u; c < push.args.x; c++) {
            uint count = counters.colour[c].x, start = counters.colour[c].y;
            for (uint first = 0u; first < count; first += at_once) {
                uint slot = first + here;
                bool valid = slot < count;
                solve_body(valid ? block_list[start + slot] : uvec4(0u), lane, valid, c);
            }
            memoryBarrierBuffer();
            barrier();
        }
    }
}
#else
// The tail on a CPU device (push.args.x = TB_MAX_COLOURS, one workgroup), where the sweep
// has one lane a body: the bodies one after the other by the first lane.
void solve_tail_narrow()
{
    uint count = counters.colouring.z;
    uint lane = gl_SubgroupInvocationID;
    if (count == 0u || gl_SubgroupID != 0u || lane >= BLOCK_LANES) return;
    uint start = block_tail_start();
    for (uint t = 0u; t < count; t++) {
        solve_body(block_list[start + t], lane, true, uint(TB_MAX_COLOURS) + t);
        subgroupMemoryBarrierBuffer();
        subgroupBarrier();
    }
}

void main()
{
    if (step_aborted()) return;
    sweep_set(push.args.y);
    uint colour = push.args.x;
    if (colour >= TB_MAX_COLOURS) {
        solve_tail_narrow();
        return;
    }
    uvec4 listed;
    uint lane;
    bool valid = block_listed(colour, listed, lane);
    solve_body(listed, lane, valid, colour);
}
#endif

#endif
