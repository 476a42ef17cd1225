// Joints in the block solver (layout.h's tb_gpu_joint, src/joints/): a joint is a list
// entry of each of its dynamic bodies, beside their contact points, and adds its rows to
// the body's Newton step as a contact does (solve.glsl). Its rows are hard constraints
// reached by the augmented Lagrangian of the contacts: a force per row
//     f = lambda - k C      (clamped to [lo, hi]: limits push one way, motors up to a torque),
// the multiplier lambda taking f after each sweep and the stiffness k growing with the
// error, both carried to the next step (tb_gpu_joint_state). Unlike a contact's rows,
// which are linear in the step's motion, a joint's are taken where the sweep has both
// bodies now (their turn too), with the Jacobian there: a pendulum turns through large
// angles, and a constraint linearised at the step's start would let it drift off its circle.
//
// Rows, with d = the anchor of b minus the anchor of a, and A, B the joint's frames on a
// and b (the body's rotation times tb_gpu_joint.frame_*), x their first axis:
//   point (ball, hinge, fixed):  d along the world axes
//   angular (fixed, slider):     the rotation vector of B A^-1, world axes
//   aligned axes (hinge):        x_A cross x_B, world axes (two of the three count)
//   slider's point rows:         d along A's y and z axes
//   limit:                       hinge: the twist of B about A's x axis; slider: d along x;
//                                distance: |d|; one side at a time, pushing one way
//   motor:                       the rate of that twist (or slide) over the step, against
//                                the target speed, with the force bounded
//   distance:                    |d| - length (a rod), or a spring to it
// Shared by block/solve (its sweeps), block/joint_count and block/joint_fill.
#ifndef TB_BLOCK_JOINT_GLSL
#define TB_BLOCK_JOINT_GLSL

#include "block.glsl"

uint joint_kind(tb_gpu_joint jt)
{
    return jt.info.z & 0xffu;
}

bool joint_has(tb_gpu_joint jt, uint flag)
{
    return (jt.info.z & flag) != 0u;
}

// The stiffness units of a joint's rows (N/m and N m/rad): its bodies' (ab: a and b, as
// tb_gpu_joint.info.xy) effective mass and moment over dt^2, as a contact's
// (block_stiffness_unit).
vec2 joint_units(uvec2 ab)
{
    float h = block_h();
    uint a = ab.x, b = ab.y;
    float ma = block_dynamic(a) ? body_pos[a].w : 0.0;   // inverse masses
    float mb = block_dynamic(b) ? body_pos[b].w : 0.0;
    vec3 ia = block_dynamic(a) ? body_inv_inertia[a].xyz : vec3(0.0);
    vec3 ib = block_dynamic(b) ? body_inv_inertia[b].xyz : vec3(0.0);
    float turn = max(ia.x, max(ia.y, ia.z)) + max(ib.x, max(ib.y, ib.z));
    return vec2(1.0 / max(ma + mb, 1e-30), 1.0 / max(turn, 1e-30)) / (h * h);
}

// Where the sweep has a joint's two bodies: poses, lever arms of the anchors, the frames.
struct joint_pose {
    vec3 xa, xb;   // centres of mass
    vec3 ra, rb;   // anchors from them
    vec4 fa, fb;   // the joint's frames A and B (world)
    vec3 d;        // anchor b - anchor a
    vec3 va, vb;   // how far each has turned since the step began (rotation vectors)
    vec3 dpa, dpb; // and moved
};

joint_pose joint_pose_of(tb_gpu_joint jt, uvec2 ab, vec3 dpa, vec3 va, vec3 dpb, vec3 vb)
{
    joint_pose p;
    uint a = ab.x, b = ab.y;
    vec4 qa = normalize(quat_mul(quat_of_rotation_vector(va), body_rot[a]));
    vec4 qb = normalize(quat_mul(quat_of_rotation_vector(vb), body_rot[b]));
    p.xa = body_pos[a].xyz + dpa;
    p.xb = body_pos[b].xyz + dpb;
    p.ra = quat_rotate(qa, jt.anchor_a.xyz);
    p.rb = quat_rotate(qb, jt.anchor_b.xyz);
    p.fa = quat_mul(qa, jt.frame_a);
    p.fb = quat_mul(qb, jt.frame_b);
    p.d = (p.xb + p.rb) - (p.xa + p.ra);
    p.va = va;
    p.vb = vb;
    p.dpa = dpa;
    p.dpb = dpb;
    return p;
}

// One row: its Jacobian on a (linear la, angular aa) and on b (lb, ab), its value C, and a
// bound on how much its Jacobian turns as each body turns (bend: the size of C's second
// derivative in the body's turn, a lever arm's length for a point row).
struct joint_row {
    vec3 la, aa, lb, ab;
    float C;
    vec2 bend;
};

joint_row joint_row_of(vec3 la, vec3 aa, vec3 lb, vec3 ab, float C)
{
    joint_row r;
    r.la = la;
    r.aa = aa;
    r.lb = lb;
    r.ab = ab;
    r.C = C;
    r.bend = vec2(0.0);
    return r;
}

// A row along direction u through the anchors: b's anchor moves with b, a's with a.
joint_row joint_point_row(joint_pose p, vec3 u, float C)
{
    joint_row r = joint_row_of(-u, -cross(p.ra, u), u, cross(p.rb, u), C);
    r.bend = vec2(length(p.ra), length(p.rb));
    return r;
}

// A row along a direction u fixed in a's frame A: it turns with a, so a's turn moves the
// row's value through the direction too (u x d) besides through a's anchor.
joint_row joint_frame_row(joint_pose p, vec3 u, float C)
{
    vec3 reach = p.xb + p.rb - p.xa;
    joint_row r = joint_row_of(-u, cross(u, reach), u, cross(p.rb, u), C);
    r.bend = vec2(length(reach), length(p.rb));
    return r;
}

// A row of turn about u.
joint_row joint_turn_row(vec3 u, float C)
{
    return joint_row_of(vec3(0.0), -u, vec3(0.0), u, C);
}

// What the sweep does with a joint's rows: add them to one body's Newton step (primal),
// or update their multipliers and stiffnesses once both bodies have moved (dual).
struct joint_work {
    bool dual;       // else primal
    bool is_b;       // primal: the body moving is b
    bool last;       // dual: the step's last sweep
    float growth;    // dual: the stiffness's growth per unit of error, in units
    // primal: the Newton blocks of the body (as solve.glsl's newton)
    mat3 A, B, D;
    vec3 gl, ga;
    // dual: the force and torque on b, about b's anchor, summed over the rows
    vec3 force, torque;
    // a soft joint's frequency (0: rigid) and damping ratio, and how far its bodies have
    // moved and turned since the step began (a held row's rate)
    float soft_hertz, soft_damping;
    vec3 dpa, va, dpb, vb;
    // the joint, and its hard equality rows taken so far (joint_hold counts them); `record`:
    // only write their values, as the error the step begins with (block/joint_start);
    // `hold_start`: hold them at that error (the step's first sweeps, solve.glsl)
    uint joint, holds;
    bool record, hold_start;
};

// Row r with multiplier lambda and stiffness k (unit: its stiffness unit), its force
// clamped to [lo, hi]; `hessian` false leaves its stiffness out of the Newton step (a limit
// not reached). Dual: lambda takes the force; k grows while the row holds (the force
// within its bounds) by growth * unit * |C|, up to the largest stiffness.
void joint_apply(inout joint_work w, joint_row r, inout float lambda, inout float k, float unit,
                 float lo, float hi, bool hessian, vec3 rb)
{
    float f = clamp(lambda - k * r.C, lo, hi);
    if (w.dual) {
        if (f > lo && f < hi)
            k = min(k + w.growth * unit * abs(r.C), params.block_joints.x * unit);
        lambda = f;
        w.force += f * r.lb;
        w.torque += f * (r.ab - cross(rb, r.lb));
        return;
    }
    vec3 jl = w.is_b ? r.lb : r.la, ja = w.is_b ? r.ab : r.aa;
    w.gl -= f * jl;
    w.ga -= f * ja;
    // The force times C's second derivative belongs in the Hessian too; its bound on the
    // diagonal (as the AVBD paper does) keeps the step from overshooting where the force
    // is large against the body's inertia: a light link of a chain with a 10 times heavier
    // end, swinging through the bottom, turned too far and the chain blew up.
    w.D += abs(f) * (w.is_b ? r.bend.y : r.bend.x) * mat3(1.0);
    if (!hessian) return;
    w.A += k * outerProduct(jl, jl);
    w.B += k * outerProduct(jl, ja);
    w.D += k * outerProduct(ja, ja);
}

// A spring of frequency `hertz` and damping ratio `damping` on the bodies' effective mass
// (or moment, unit h^2): its stiffness k and damping c.
vec2 joint_spring_gains(float unit, float hertz, float damping)
{
    float h = block_h(), omega = 6.2831853 * hertz;
    float mass = unit * h * h;
    return vec2(mass * omega * omega, 2.0 * mass * damping * omega);
}

// That spring along a row whose value C is the coordinate's distance from where the spring
// pulls to and `moved` its change over the step so far; stepped implicitly, its stiffness
// and damping over the step act as k + c / dt: a row of multiplier `lambda` at C = 0 with
// that `stiffness`.
void joint_spring(float C, float moved, float unit, float hertz, float damping,
                  out float lambda, out float stiffness)
{
    float h = block_h();
    vec2 kc = joint_spring_gains(unit, hertz, damping);
    lambda = -(kc.x * C + kc.y * moved / h);
    stiffness = kc.x + kc.y / h;
}

void joint_spring_row(inout joint_work w, joint_row r, float moved, float unit, float hertz,
                      float damping, vec3 rb)
{
    float lambda, stiffness;
    joint_spring(r.C, moved, unit, hertz, damping, lambda, stiffness);
    r.C = 0.0;
    joint_apply(w, r, lambda, stiffness, unit, -1e30, 1e30, true, rb);
}

// The hard equality rows a joint's start_error holds (two vec4s; a kind has at most seven).
const uint JOINT_START_ROWS = 8u;

// The error hard equality row n of joint j began the step with (tb_gpu_joint_state.start_error).
float joint_start_error(uint j, uint n)
{
    return n < JOINT_START_ROWS ? joint_states[j].start_error[n >> 2][n & 3u] : 0.0;
}

// Keep C as that error (block/joint_start, joint_record_start).
void joint_record_start_error(uint j, uint n, float C)
{
    if (n < JOINT_START_ROWS) joint_states[j].start_error[n >> 2][n & 3u] = C;
}

// An equality row: hard (its multiplier and stiffness), or in a soft joint a spring to 0.
// In the step's first sweeps a hard row holds the error its step began with (sweep_set,
// solve.glsl); the later sweeps close it.
void joint_hold(inout joint_work w, joint_row r, inout float lambda, inout float k, float unit,
                vec3 rb)
{
    uint n = w.holds++;
    if (w.record) {
        joint_record_start_error(w.joint, n, r.C);
        return;
    }
    // One joint_apply for both ways, so each row of a kind is one copy of it in the sweep.
    bool soft = w.soft_hertz > 0.0;
    float l = lambda, stiffness = k;
    if (soft) {
        float moved = dot(r.la, w.dpa) + dot(r.aa, w.va) + dot(r.lb, w.dpb) + dot(r.ab, w.vb);
        joint_spring(r.C, moved, unit, w.soft_hertz, w.soft_damping, l, stiffness);
        r.C = 0.0;
    } else if (w.hold_start) {
        r.C -= joint_start_error(w.joint, n);
    }
    joint_apply(w, r, l, stiffness, unit, -1e30, 1e30, true, rb);
    if (soft) return;
    lambda = l;
    k = stiffness;
}

// Three hard equality rows along the world axes with one stiffness (state.w) and their
// multipliers in state.xyz, of value C: the anchors' offset (`turn` false: the point rows,
// the anchors meet) or the turn from A to B (`turn`: a weld's angular rows). Their Jacobians
// are the axes, so they sum in closed form as a contact point's rows do (solve.glsl,
// add_rows): sum_u k u u^T = k I, sum_u k u (r x u)^T = -k skew(r),
// sum_u k (r x u)(r x u)^T = k (|r|^2 I - r r^T), the gradient the force f and its moment
// r x f, where the row by row sums (joint_hold, joint_apply) took three outer products a
// row. The same rows, values and updates as those, summed in another order.
void joint_axes_rows(inout joint_work w, joint_pose p, vec3 C, bool turn, inout vec4 state,
                     float unit)
{
    uint n = w.holds;
    w.holds += 3u;
    if (w.record) {
        for (uint i = 0u; i < 3u; i++) joint_record_start_error(w.joint, n + i, C[i]);
        return;
    }
    vec3 lambda = state.xyz;
    float k = state.w;
    bool soft = w.soft_hertz > 0.0;
    if (soft) {
        // The rows' change over the step so far, and the spring's multipliers and stiffness.
        vec3 moved = turn ? w.vb - w.va
                          : (w.dpb + cross(w.vb, p.rb)) - (w.dpa + cross(w.va, p.ra));
        float h = block_h();
        vec2 kc = joint_spring_gains(unit, w.soft_hertz, w.soft_damping);
        lambda = -(kc.x * C + kc.y * moved / h);
        k = kc.x + kc.y / h;
        C = vec3(0.0);
    } else if (w.hold_start) {
        C -= vec3(joint_start_error(w.joint, n), joint_start_error(w.joint, n + 1u),
                  joint_start_error(w.joint, n + 2u));
    }
    vec3 f = lambda - k * C;
    if (w.dual) {
        if (turn) w.torque += f;
        else w.force += f;   // the point rows' moment about b's anchor is none
        if (soft) return;
        float c = max(abs(C.x), max(abs(C.y), abs(C.z)));
        state = vec4(f, max(k, min(k + w.growth * unit * c, params.block_joints.x * unit)));
        return;
    }
    float sign = w.is_b ? 1.0 : -1.0;
    float pushed = abs(f.x) + abs(f.y) + abs(f.z);
    if (turn) {
        w.ga -= sign * f;
        w.D += (k + 0.5 * pushed) * mat3(1.0);   // joint_lock_rows's bend, 0.5
        return;
    }
    vec3 r = w.is_b ? p.rb : p.ra;
    vec3 r2 = r * r;
    w.gl -= sign * f;
    w.ga -= sign * cross(r, f);
    w.A += k * mat3(1.0);
    vec3 kr = k * r;
    w.B -= mat3(0.0, kr.z, -kr.y, -kr.z, 0.0, kr.x, kr.y, -kr.x, 0.0);   // skew(kr)
    w.D += mat3(k * (r2.y + r2.z), -k * r.x * r.y, -k * r.x * r.z,
                -k * r.x * r.y, k * (r2.x + r2.z), -k * r.y * r.z,
                -k * r.x * r.z, -k * r.y * r.z, k * (r2.x + r2.y));
    w.D += pushed * length(r) * mat3(1.0);   // a point row's bend: its lever arm
}

// The three point rows: the anchors meet.
void joint_point_rows(inout joint_work w, joint_pose p, inout tb_gpu_joint_state s, float unit)
{
    joint_axes_rows(w, p, p.d, false, s.linear, unit);
}

// The three angular rows of a weld: B A^-1 is no turn.
void joint_lock_rows(inout joint_work w, joint_pose p, inout tb_gpu_joint_state s, float unit)
{
    vec3 theta = rotation_vector(quat_mul(p.fb, vec4(-p.fa.xyz, p.fa.w)));
    joint_axes_rows(w, p, theta, true, s.angular, unit);
}

// A hinge's axes stay aligned: c = x_A cross x_B is zero. Its change with b's turn t is
// ((x_A . x_B) I - x_B x_A^T) t, with a's turn the same with A and B swapped, negated.
void joint_align_rows(inout joint_work w, joint_pose p, inout tb_gpu_joint_state s, float unit)
{
    vec3 xa = quat_rotate(p.fa, vec3(1.0, 0.0, 0.0)), xb = quat_rotate(p.fb, vec3(1.0, 0.0, 0.0));
    vec3 c = cross(xa, xb);
    float cosine = dot(xa, xb);
    float k = s.angular.w;
    for (int i = 0; i < 3; i++) {
        vec3 u = mat3(1.0)[i];   // world axis i
        vec3 ab = cosine * u - xb[i] * xa, aa = -(cosine * u - xa[i] * xb);
        float lambda = s.angular[i];
        float ki = k;
        joint_row r = joint_row_of(vec3(0.0), aa, vec3(0.0), ab, c[i]);
        r.bend = vec2(1.0);
        joint_hold(w, r, lambda, ki, unit, p.rb);
        s.angular[i] = lambda;
        s.angular.w = max(s.angular.w, ki);
    }
}

// A limit on a coordinate q (the row r's value is q): lower <= q <= upper, one side at a
// time (the nearer), its multiplier lambda signed along r. Equal bounds lock the
// coordinate. Its stiffness stays in the Newton step while the limit is engaged (bit `bit`
// of `engaged`: it pushed last step, or has pushed in this one), even in a sweep where its
// force drops to nothing, as a contact's does: without it a rope pulled taut went slack in
// one sweep, fell freely in the next, came back taut with a larger error, and blew up.
void joint_limit_row(inout joint_work w, joint_row r, float lower, float upper,
                     inout float lambda, inout float k, inout uint engaged, uint bit,
                     float unit, vec3 rb)
{
    float q = r.C;
    bool held = (engaged & bit) != 0u;
    if (upper - lower < 1e-6) {
        r.C = q - lower;
        joint_hold(w, r, lambda, k, unit, rb);
    } else {
        // The nearer side: from below it pushes q up (a force >= 0 along r), from above down.
        bool below = q - lower < upper - q;
        r.C = below ? q - lower : q - upper;
        lambda = below ? max(lambda, 0.0) : min(lambda, 0.0);
        bool pressed = below ? r.C < 0.0 : r.C > 0.0;
        joint_apply(w, r, lambda, k, unit, below ? 0.0 : -1e30, below ? 1e30 : 0.0,
                    held || pressed, rb);
    }
    if (w.dual && lambda != 0.0) engaged |= bit;
}

// The limit of axial.xy (a hinge's, slider's or distance joint's; a cone's twist).
void joint_axial_limit_row(inout joint_work w, joint_row r, float lower, float upper,
                           inout tb_gpu_joint_state s, float unit, vec3 rb)
{
    joint_limit_row(w, r, lower, upper, s.axial.x, s.axial.y, s.info.z, 1u, unit, rb);
}

// A motor: the coordinate's change over the step (r's value) against speed * dt, with a
// force of at most `most` either way.
void joint_motor_row(inout joint_work w, joint_row r, float speed, float most,
                     inout tb_gpu_joint_state s, float unit, vec3 rb)
{
    r.C -= speed * block_h();
    float lambda = s.axial.z, k = s.axial.w;
    joint_apply(w, r, lambda, k, unit, -most, most, true, rb);
    s.axial.z = lambda;
    s.axial.w = k;
}

// The twist of B about A's x axis, in (-pi, pi].
float joint_twist(joint_pose p)
{
    vec4 rel = quat_mul(vec4(-p.fa.xyz, p.fa.w), p.fb);
    return 2.0 * atan(rel.x, rel.w);
}

void joint_hinge_rows(inout joint_work w, tb_gpu_joint jt, joint_pose p,
                      inout tb_gpu_joint_state s, vec2 unit)
{
    joint_point_rows(w, p, s, unit.x);
    joint_align_rows(w, p, s, unit.y);
    vec3 x = quat_rotate(p.fa, vec3(1.0, 0.0, 0.0));
    float angle = joint_twist(p), turned = dot(p.vb - p.va, x);
    if (joint_has(jt, TB_GPU_JOINT_LIMIT))
        joint_axial_limit_row(w, joint_turn_row(x, angle), jt.limit.x, jt.limit.y, s, unit.y,
                              p.rb);
    if (joint_has(jt, TB_GPU_JOINT_MOTOR))
        joint_motor_row(w, joint_turn_row(x, turned), jt.motor.x, jt.motor.y, s, unit.y, p.rb);
    if (joint_has(jt, TB_GPU_JOINT_SPRING)) {
        float off = angle - jt.anchor_a.w;
        off -= 6.2831853 * round(off / 6.2831853);   // the near way round
        joint_spring_row(w, joint_turn_row(x, off), turned, unit.y, jt.anchor_b.w, jt.limit.z,
                         p.rb);
    }
}

void joint_slider_rows(inout joint_work w, tb_gpu_joint jt, joint_pose p,
                       inout tb_gpu_joint_state s, vec2 unit)
{
    vec3 x = quat_rotate(p.fa, vec3(1.0, 0.0, 0.0));
    vec3 y = quat_rotate(p.fa, vec3(0.0, 1.0, 0.0)), z = quat_rotate(p.fa, vec3(0.0, 0.0, 1.0));
    float k = s.linear.w;
    float ly = s.linear.x, lz = s.linear.y, ky = k, kz = k;
    joint_hold(w, joint_frame_row(p, y, dot(y, p.d)), ly, ky, unit.x, p.rb);
    joint_hold(w, joint_frame_row(p, z, dot(z, p.d)), lz, kz, unit.x, p.rb);
    s.linear.xy = vec2(ly, lz);
    s.linear.w = max(ky, kz);
    joint_lock_rows(w, p, s, unit.y);
    float offset = dot(x, p.d), moved = dot(x, p.dpb - p.dpa);
    if (joint_has(jt, TB_GPU_JOINT_LIMIT))
        joint_axial_limit_row(w, joint_frame_row(p, x, offset), jt.limit.x, jt.limit.y, s,
                              unit.x, p.rb);
    if (joint_has(jt, TB_GPU_JOINT_MOTOR))
        joint_motor_row(w, joint_frame_row(p, x, moved), jt.motor.x, jt.motor.y, s, unit.x,
                        p.rb);
    if (joint_has(jt, TB_GPU_JOINT_SPRING))
        joint_spring_row(w, joint_frame_row(p, x, offset - jt.anchor_a.w), moved, unit.x,
                         jt.anchor_b.w, jt.limit.z, p.rb);
}

// A cone-twist joint: the anchors meet (the point rows), B's x axis stays within the cone
// of half angle limit.w about A's (the swing: the angle between them, a turn about their
// cross product), and, with the limit on, the twist of B about its x axis stays within the
// limit (its rate is taken about the two axes' mean).
void joint_cone_rows(inout joint_work w, tb_gpu_joint jt, joint_pose p,
                     inout tb_gpu_joint_state s, vec2 unit)
{
    joint_point_rows(w, p, s, unit.x);
    vec3 xa = quat_rotate(p.fa, vec3(1.0, 0.0, 0.0)), xb = quat_rotate(p.fb, vec3(1.0, 0.0, 0.0));
    vec3 n = cross(xa, xb);
    float sine = length(n), swing = atan(sine, dot(xa, xb));
    if (sine > 1e-6) {
        // lower -4: below any swing by more than the cone is above it, so the limit's upper
        // side is always the nearer one.
        joint_row r = joint_turn_row(n / sine, swing);
        r.bend = vec2(1.0);
        joint_limit_row(w, r, -4.0, jt.limit.w, s.axial.z, s.axial.w, s.info.z, 2u, unit.y, p.rb);
    }
    if (!joint_has(jt, TB_GPU_JOINT_LIMIT)) return;
    vec3 mean = xa + xb;
    vec3 axis = dot(mean, mean) > 1e-6 ? normalize(mean) : xb;
    joint_axial_limit_row(w, joint_turn_row(axis, joint_twist(p)), jt.limit.x, jt.limit.y, s,
                          unit.y, p.rb);
}

// What a 6-dof joint does with its axis i (0-2 offsets, 3-5 turns).
uint joint_axis_mode(tb_gpu_joint jt, int i)
{
    return (jt.info.z >> (TB_GPU_JOINT_AXIS_SHIFT + 2 * i)) & 3u;
}

// One axis of a 6-dof joint: row r held at 0 (locked) or within [lower, upper] (limited),
// its multiplier lambda, its stiffness taken from and raised into k, its engaged flag bit
// `bit` of the state's info.z.
void joint_axis_row(inout joint_work w, joint_row r, uint mode, float lower, float upper,
                    inout float lambda, inout float k, inout uint engaged, uint bit,
                    float unit, vec3 rb)
{
    float ki = k;
    if (mode == TB_GPU_JOINT_AXIS_LOCKED)
        joint_hold(w, r, lambda, ki, unit, rb);
    else if (mode == TB_GPU_JOINT_AXIS_LIMITED)
        joint_limit_row(w, r, lower, upper, lambda, ki, engaged, bit, unit, rb);
    k = max(k, ki);
}

// A 6-dof joint: the offset d along A's axes, and the turn from A to B as the rotation
// vector of A^-1 B (A's axes), each axis free, limited or locked.
void joint_six_dof_rows(inout joint_work w, tb_gpu_joint jt, joint_pose p,
                        inout tb_gpu_joint_state s, vec2 unit)
{
    vec3 theta = rotation_vector(quat_mul(vec4(-p.fa.xyz, p.fa.w), p.fb));
    float kl = s.linear.w, ka = s.angular.w;
    for (int i = 0; i < 3; i++) {
        vec3 u = quat_rotate(p.fa, mat3(1.0)[i]);   // A's axis i
        joint_axis_row(w, joint_frame_row(p, u, dot(u, p.d)), joint_axis_mode(jt, i),
                       jt.lower[i], jt.upper[i], s.linear[i], kl, s.info.z, 1u << i, unit.x,
                       p.rb);
        joint_row r = joint_turn_row(u, theta[i]);
        r.bend = vec2(0.5);
        joint_axis_row(w, r, joint_axis_mode(jt, i + 3), jt.turn_lower[i], jt.turn_upper[i],
                       s.angular[i], ka, s.info.z, 8u << i, unit.y, p.rb);
    }
    s.linear.w = kl;
    s.angular.w = ka;
}

// A distance joint's row along the line between the anchors.
void joint_distance_rows(inout joint_work w, tb_gpu_joint jt, joint_pose p,
                         inout tb_gpu_joint_state s, vec2 unit)
{
    float len = length(p.d);
    vec3 n = len > 1e-6 ? p.d / len : vec3(0.0, 1.0, 0.0);
    joint_row r = joint_point_row(p, n, len);
    float rest = jt.anchor_a.w;
    if (joint_has(jt, TB_GPU_JOINT_SPRING)) {
        float moved = dot(n, (p.dpb + cross(p.vb, p.rb)) - (p.dpa + cross(p.va, p.ra)));
        r.C = len - rest;
        joint_spring_row(w, r, moved, unit.x, jt.anchor_b.w, jt.limit.z, p.rb);
        if (joint_has(jt, TB_GPU_JOINT_LIMIT)) {
            r.C = len;
            joint_axial_limit_row(w, r, jt.limit.x, jt.limit.y, s, unit.x, p.rb);
        }
        return;
    }
    if (joint_has(jt, TB_GPU_JOINT_LIMIT)) {
        joint_axial_limit_row(w, r, jt.limit.x, jt.limit.y, s, unit.x, p.rb);
        return;
    }
    r.C = len - rest;
    float lambda = s.axial.x, k = s.axial.y;
    joint_hold(w, r, lambda, k, unit.x, p.rb);
    s.axial.xy = vec2(lambda, k);
}

// Joint j's rows as the sweep has its bodies ab (its info.xy: the sweep knows them from
// the list entry, so their poses need not wait for the joint's load; a moved by dpa and
// turned by va since the step began, b by dpb, vb): work w's mode says what to do with
// them; s is the joint's state, updated in the dual.
void joint_rows(inout joint_work w, uint j, uvec2 ab, inout tb_gpu_joint_state s, vec3 dpa,
                vec3 va, vec3 dpb, vec3 vb)
{
    tb_gpu_joint jt = joints[j];
    joint_pose p = joint_pose_of(jt, ab, dpa, va, dpb, vb);
    vec2 unit = joint_units(ab);
    uint kind = joint_kind(jt);
    w.soft_hertz = joint_has(jt, TB_GPU_JOINT_SOFT) ? jt.lower.w : 0.0;
    w.soft_damping = jt.upper.w;
    w.joint = j;
    w.holds = 0u;
    w.dpa = dpa;
    w.va = va;
    w.dpb = dpb;
    w.vb = vb;
    if (kind == TB_GPU_JOINT_BALL) {
        joint_point_rows(w, p, s, unit.x);
    } else if (kind == TB_GPU_JOINT_FIXED) {
        joint_point_rows(w, p, s, unit.x);
        joint_lock_rows(w, p, s, unit.y);
    } else if (kind == TB_GPU_JOINT_HINGE) {
        joint_hinge_rows(w, jt, p, s, unit);
    } else if (kind == TB_GPU_JOINT_SLIDER) {
        joint_slider_rows(w, jt, p, s, unit);
    } else if (kind == TB_GPU_JOINT_DISTANCE) {
        joint_distance_rows(w, jt, p, s, unit);
    } else if (kind == TB_GPU_JOINT_CONE) {
        joint_cone_rows(w, jt, p, s, unit);
    } else if (kind == TB_GPU_JOINT_SIX_DOF) {
        joint_six_dof_rows(w, jt, p, s, unit);
    }
}

// Whether joint j holds in this step: a joint in the slot, not broken (a state of another
// generation is a joint that was in the slot before: block/joint_start starts it anew).
bool joint_holds(uint j)
{
    uvec4 info = joints[j].info;
    uvec4 state = joint_states[j].info;
    return (info.z & 0xffu) != TB_GPU_JOINT_NONE && (state.y == 0u || state.x != info.w);
}

// Whether the kind's point rows (along the world axes) and angular rows may carry their
// force into the next step's prediction (tb_gpu_joint_state.held_force, held_torque).
bool joint_may_hold(uint kind)
{
    return kind == TB_GPU_JOINT_BALL || kind == TB_GPU_JOINT_HINGE || kind == TB_GPU_JOINT_FIXED ||
           kind == TB_GPU_JOINT_CONE;
}

// What joint j's prediction holds body i with (held_force and held_torque): the force on
// it and the torque about its centre, at the poses the step began with.
void joint_held_on(uint j, bool is_b, out vec3 force, out vec3 torque)
{
    tb_gpu_joint jt = joints[j];
    tb_gpu_joint_state s = joint_states[j];
    vec3 f = s.held_force.xyz, t = s.held_torque.xyz;
    uint body = is_b ? jt.info.y : jt.info.x;
    vec3 r = quat_rotate(body_rot[body], is_b ? jt.anchor_b.xyz : jt.anchor_a.xyz);
    force = is_b ? f : -f;
    torque = cross(r, force) + (is_b ? t : -t);
}

joint_work joint_work_primal(bool is_b)
{
    joint_work w;
    w.dual = false;
    w.is_b = is_b;
    w.last = false;
    w.growth = 0.0;
    w.A = mat3(0.0);
    w.B = mat3(0.0);
    w.D = mat3(0.0);
    w.gl = vec3(0.0);
    w.ga = vec3(0.0);
    w.force = vec3(0.0);
    w.torque = vec3(0.0);
    w.soft_hertz = 0.0;
    w.soft_damping = 0.0;
    w.dpa = vec3(0.0);
    w.va = vec3(0.0);
    w.dpb = vec3(0.0);
    w.vb = vec3(0.0);
    w.joint = 0u;
    w.holds = 0u;
    w.record = false;
    w.hold_start = false;
    return w;
}

// Joint j's hard equality rows' values with its bodies where the step begins, kept as the
// error the step's first sweeps hold (block/joint_start). Every row the sweeps read is
// written here each step, in the same order, so the rest of start_error is left as it is.
void joint_record_start(uint j, tb_gpu_joint_state s)
{
    joint_work w = joint_work_primal(false);
    w.record = true;
    joint_rows(w, j, joints[j].info.xy, s, vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
}

// What the sweep's work with a joint's rows starts from: a primal's are added to body
// (is_b) b's or a's Newton blocks e (solve.glsl's newton, passed as its parts); a dual, once
// both bodies have moved, updates the rows' multipliers and stiffnesses (joint_store).
joint_work joint_work_of(bool dual, bool is_b, mat3 A, mat3 B, mat3 D, vec3 gl, vec3 ga,
                         bool last, bool hold_start)
{
    joint_work w = joint_work_primal(is_b);
    w.dual = dual;
    w.last = last;
    w.hold_start = hold_start;
    w.growth = params.block.y;
    w.A = A;
    w.B = B;
    w.D = D;
    w.gl = gl;
    w.ga = ga;
    return w;
}

// The dual's end for joint j, its rows taken into state s by work w: the new multipliers
// and stiffnesses; after the last sweep also the force and torque it put on b, and
// whether they broke it.
void joint_store(uint j, tb_gpu_joint_state s, joint_work w)
{
    if (!finite_all(s.linear) || !finite_all(s.angular) || !finite_all(s.axial)) return;
    joint_states[j].linear = s.linear;
    joint_states[j].angular = s.angular;
    joint_states[j].axial = s.axial;
    joint_states[j].info.z = s.info.z;
    if (!w.last) return;
    joint_states[j].force = vec4(s.held_force.xyz + w.force, 0.0);
    joint_states[j].torque = vec4(s.held_torque.xyz + w.torque, 0.0);
    tb_gpu_joint jt = joints[j];
    bool breaks = joint_has(jt, TB_GPU_JOINT_BREAKABLE) &&
                  ((jt.motor.z > 0.0 && length(s.held_force.xyz + w.force) > jt.motor.z) ||
                   (jt.motor.w > 0.0 && length(s.held_torque.xyz + w.torque) > jt.motor.w));
    if (breaks) joint_states[j].info.y = 1u;
}

#endif
