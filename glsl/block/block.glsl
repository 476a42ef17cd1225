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
// with lambda the multipliers (kept as impulses lambda * dt in manifolds[p].impulse.xyz) and
// k the point's stiffness (N/m; during the sweeps in manifolds[p].impulse.w, beside the
// multipliers, so a sweep reads both in one load: H100, spheres 100k 6.87 -> 6.57 ms a step,
// hulls 100k 16.6 -> 16.2, boxes 1M 47.2 -> 46.0, against keeping it in the constraint's
// mass.w; the last sweep puts the step's normal impulse there). Positions are the substep
// records' delta_position and delta_rotation: how far each body has moved since the step
// began.
#ifndef TB_BLOCK_GLSL
#define TB_BLOCK_GLSL

#include "world.glsl"
#include "quat.glsl"

// Invocations that share a body in a sweep: on a GPU `wanted`, or the subgroup when it is
// narrower; on a CPU device 1, as its lanes are SIMD lanes of one core that each pay for the
// whole 6x6 solve (lavapipe, deep pile of 4,000: solve 356 ms a step with 8 lanes a body,
// 217 with 4 or 2, 168 with 1). The sweep comes in 8, 16 and 32 lanes (block/solve,
// block/solve_16, block/solve_32; the host picks one, tb_block_lanes_for): more lanes a
// body shorten each lane's chain of loads, which pays while a colour's bodies are fewer
// than the GPU's threads and each has many points.
#define BLOCK_LANES_OF(wanted) (CPU_DEVICE != 0u ? 1u : SUBGROUP_SIZE < (wanted) ? SUBGROUP_SIZE : (wanted))

// The lanes of this shader's sweep (TB_BLOCK_LANES, defined before this file by the sweeps
// that want more than 8; block/bounce keeps 8 and runs on the sweeps' dispatch sizes, its
// extra lanes idle). A plain number, so the preprocessor can test it (solve.glsl's sums).
#ifndef TB_BLOCK_LANES
#define TB_BLOCK_LANES 8
#endif
const uint BLOCK_LANES = BLOCK_LANES_OF(uint(TB_BLOCK_LANES));

bool block_dynamic(uint i)
{
    return body_is(i, TB_BODY_FLAG_ALIVE | TB_BODY_FLAG_DYNAMIC);
}

// A dynamic body's place in a sweep, from its body_colour word: its colour, or for a body
// the colouring left to the tail (more than TB_MAX_COLOURS were needed), TB_MAX_COLOURS +
// its place in the tail, which is solved one body at a time after the colours.
uint block_order(uint word)
{
    uint c = word & 0xffu;
    return c < uint(TB_MAX_COLOURS) ? c : uint(TB_MAX_COLOURS) + (word >> 8);
}

// Whether the body whose body_colour word is `word` has already moved in a sweep when the
// body of place `order` moves: a static or kinematic body never moves.
bool block_moved_before(uint word, uint order)
{
    return word == TB_BLOCK_NOT_SOLVED || block_order(word) < order;
}

// Where the tail's bodies start in block_list: after every colour's.
uint block_tail_start()
{
    uint last = uint(TB_MAX_COLOURS) - 1u;
    return counters.colour[last].y + counters.colour[last].x;
}

// An entry of a body's contact list is one contact point: its pair, its point, and which
// end of the pair the body is.
uint block_entry(uint p, uint k, bool is_b)
{
    return (p << 2) | k | (is_b ? TB_BLOCK_SIDE_B : 0u);
}

uint block_pair(uint e)
{
    return (e & ~TB_BLOCK_SIDE_B) >> 2;
}

uint block_point_of(uint e)
{
    return e & 3u;
}

bool block_is_b(uint e)
{
    return (e & TB_BLOCK_SIDE_B) != 0u;
}

// A joint's entry: its slot | TB_BLOCK_JOINT, and the side as a contact's.
bool block_is_joint(uint entry)
{
    return (entry & TB_BLOCK_JOINT) != 0u;
}

uint block_joint_of(uint entry)
{
    return entry & ~(TB_BLOCK_JOINT | TB_BLOCK_SIDE_B);
}

uint block_joint_entry(uint j, bool is_b)
{
    return j | TB_BLOCK_JOINT | (is_b ? TB_BLOCK_SIDE_B : 0u);
}

// Points of pair p.
uint block_points(uint p)
{
    return min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS));
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

// One contact point as a sweep sees it: what the rows and forces of glsl/block/ need of
// the manifold (normal, multipliers, slip) and of the constraint solver/prepare wrote (lever
// arms, friction directions, effective mass), loaded field by field so a sweep reads no more
// of the 224-byte constraint than the point's share.
struct block_point {
    vec3 n, t1, t2;   // the normal (a to b) and the friction directions
    vec3 ra, rb;      // lever arms on a and b at the step's start
    float separation; // adjusted separation (constraint rb.w)
    float friction;
    float stiffness;  // N/m (the impulse's w during the sweeps)
    float unit;       // effective mass over dt^2: the stiffness unit
    vec3 lambda;      // multipliers: the forces the point holds (N)
    vec2 slip;        // static friction's slip since the point began to stick (m)
};

// The block solver's step: the whole time step (it has no substeps).
float block_h()
{
    return params.gravity.w;
}

// The force body i's contacts hold it with (N): the sum of the multipliers of its list, as
// the manifolds' impulses hold them (last step's at the step's start, this step's after the
// sweeps).
vec3 block_contact_force(uint i)
{
    float h = block_h();
    vec3 force = vec3(0.0);
    uint first = block_start[i], n = block_fill[i];
    for (uint e = 0u; e < n; e++) {
        uint entry = block_entries[first + e].x;
        if (block_is_joint(entry)) continue;   // joints: block/guess
        uint p = block_pair(entry), k = block_point_of(entry);
        vec3 l = manifolds[p].impulse[k].xyz / h;
        vec3 f = manifolds[p].normal.xyz * l.x + constraints[p].tangent1.xyz * l.y
               + constraints[p].tangent2.xyz * l.z;
        force += block_is_b(entry) ? f : -f;
    }
    return force;
}

// A body's free motion over the step is predicted in params.block_more.z pieces (the
// substeps), each adding a piece's share of the acceleration a to the velocity and then
// moving: over the step the velocity grows by a h, the displacement by a h^2 (N + 1) / (2 N).
// These are the two shares.
float block_fall_share()
{
    float n = max(params.block_more.z, 1.0);
    return (n + 1.0) / (2.0 * n);
}

// Point k's static friction slip, carried from step to step (tb_gpu_manifold.slip); read
// only while anchored friction is on.
vec2 block_slip(uint p, uint k)
{
    if (params.block_more.y == 0.0) return vec2(0.0);
    return slip_of_point(manifolds[p].slip[k >> 1], k);
}

// Effective mass over dt^2: the stiffness unit of point k of pair p. (Read as the whole
// vec4: reading ra.w alone through the address gave NaN bodies on lavapipe, Mesa 22.3,
// though the SPIR-V's load is the same component at alignment 4; not yet understood.)
float block_stiffness_unit(uint p, uint k)
{
    float h = block_h();
    vec4 ra = constraints[p].p[k].ra;
    return ra.w / (h * h);
}

block_point block_load(uint p, uint k)
{
    block_point q;
    float h = block_h();
    q.n = manifolds[p].normal.xyz;
    vec4 t1 = constraints[p].tangent1;
    q.t1 = t1.xyz;
    q.friction = t1.w;
    q.t2 = cross(q.n, q.t1);   // as solver/prepare made it (tangent_basis): one load less
    vec4 ra = constraints[p].p[k].ra, rb = constraints[p].p[k].rb;
    q.ra = ra.xyz;
    q.rb = rb.xyz;
    q.unit = block_stiffness_unit(p, k);
    q.separation = rb.w;
    vec4 impulse = manifolds[p].impulse[k];
    q.stiffness = impulse.w;
    q.lambda = impulse.xyz / h;
    q.slip = block_slip(p, k);
    return q;
}

// The rows of point q whose bodies moved by (dpa, turn va) and (dpb, vb), turns as rotation
// vectors. The rows are linear in the motion (the turn enters to first order, with the
// Jacobian the solve uses). (The exact turn, quat_rotate(dq, r) - r, bends the normal row by
// |r| (1 - cos angle): a sphere spinning 18 rad/s then seems to leave its neighbour by 2 cm a
// step and sinks into it, though a sphere's surface does not move as it spins.) A
// penetration the step began with counts only in part (params.block_more.x of it is left to
// later steps), so deep contacts are pushed apart gently. The friction rows count from where
// the point began to stick while anchored friction is on.
vec3 block_rows(block_point q, vec3 dpa, vec3 va, vec3 dpb, vec3 vb)
{
    vec3 d = (dpb + cross(vb, q.rb)) - (dpa + cross(va, q.ra));
    float s = q.separation + dot(q.rb - q.ra, q.n);
    if (s < 0.0) s *= 1.0 - params.block_more.x;
    vec2 slip = q.slip * params.block_more.y;
    return vec3(s + dot(d, q.n), slip.x + dot(d, q.t1), slip.y + dot(d, q.t2));
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

// Whether point k stopped an impact: it approached (the relative normal velocity before the
// step, constraint mass.z) faster than the restitution threshold. The multiplier of a
// contact that stopped a body holds the impact's impulse as well as the load, and carried
// to the next step it pushed the body out again (a hull stopped by a wall at 100 m/s left it
// at 30 m/s the step after, a ball bounced 7 % too high). The next step starts without any
// force at such a point: what is left once the impact's share is taken off is the
// estimate's error more than the load, and with the stiffness the impact grew, carried too,
// it kicked a box stopped on a wall without gravity off it at 5 mm/s (the sweeps find a
// load again within the step). Slower approaches are a pile settling: all of their force is
// load (without the threshold a column of 20 sank twice as far at first).
bool stopped_impact(uint p, uint k, block_point q)
{
    return q.unit > 0.0 && -constraints[p].p[k].mass.z > params.contact.y;
}

// The multipliers' update of point k of pair p (q, loaded before the sweep moved its
// bodies) from where its bodies are now, once a sweep has moved both (solve.glsl runs it
// from the later of the two): the multipliers take the forces the rows now have (lambda <-
// f), and a point still in contact stiffens by params.block.y (per metre of its normal
// error, in units of its effective mass over dt^2) up to params.block.z, kept in the
// impulses' w for the next sweep; the last sweep writes the step's normal impulse there
// instead (f_n dt). After the last sweep (`last`) the point keeps, for the
// next step, its normal force (none after an impact, stopped_impact) and its tangential slip
// while it sticks (none once it slides), and the pair keeps its stiffest point's stiffness,
// in its unit, for the next step (axis.w, which start.comp zeroed: the last sweep updates
// every point once, and stiffnesses only grow in a step).
void block_dual(uint p, uint k, block_point q, vec3 dpa, vec3 va, vec3 dpb, vec3 vb, bool last)
{
    float h = block_h();
    vec3 C = block_rows(q, dpa, va, dpb, vb);
    bvec3 on;
    vec3 f = block_forces(q.lambda, q.stiffness, C, q.friction, on);
    float stiffness = q.stiffness;
    if (on.x)
        stiffness = min(stiffness + params.block.y * q.unit * abs(C.x), params.block.z * q.unit);
    vec4 impulse = vec4(f * h, last ? f.x * h : stiffness);
    if (!finite_all(impulse)) return;   // a body's state stopped being finite: keep the last
    if (last && stopped_impact(p, k, q)) impulse.x = 0.0;
    manifolds[p].impulse[k] = impulse;
    if (last) {
        set_manifold_slip(p, k, on.y ? C.yz : vec2(0.0));
        if (q.unit > 0.0) atomicMax(manifolds[p].axis.w, floatBitsToUint(stiffness / q.unit));
    }
}

#endif
