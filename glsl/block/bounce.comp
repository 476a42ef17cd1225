#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
// Restitution for the block solver, per body of colour push.args.x (TB_MAX_COLOURS: the
// tail's bodies, one after the other), after block/end has turned the solve's motion into
// velocities. A contact point that approached faster than the restitution threshold
// (approach: before the step, sped up by gravity over the gap it closed) and carried load at
// the end of the solve (impulse.w > 0) leaves at e times that speed, e the pair's
// restitution.
//
// Each body changes only its own velocities. The first of a pair's bodies to come (the one
// of the earlier place, block_order, or the only dynamic one) finds the point's impulse from
// both bodies' velocities, applies its share and keeps the impulse (constraint mass.w, free
// once the sweeps are done) for the other body, which applies the rest when its turn comes:
// the pair's momentum is kept, and for one pair the bounce is exact. A body's points are
// taken one after the other (the first of each body's lanes does it: bounces are rare).
#include "listed.glsl"
#include "../solver/bodies.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

// Gravity's acceleration of body i (none unless it is dynamic).
vec3 gravity_of(uint i)
{
    tb_gpu_solver_body s = solver_bodies[i];
    return s.linear.w > 0.0 ? params.gravity.xyz * s.angular.w : vec3(0.0);
}

// The relative normal velocity point k of pair p met its surface with (m/s, < 0 when
// approaching): the one before the step, sped up by gravity over the gap the point had
// to close (a body that lands within the step has gained speed since the step began).
float approach(uint p, uint k)
{
    float before = constraints[p].p[k].mass.z;
    vec3 n = manifolds[p].normal.xyz;
    uvec4 info = manifolds[p].info;
    float towards = -dot(gravity_of(info.z) - gravity_of(info.y), n);
    float gap = max(manifolds[p].point[k].w, 0.0);
    if (before >= 0.0 || towards <= 0.0) return before;
    return -sqrt(before * before + 2.0 * towards * gap);
}

// Whether point k of pair p bounces (e > 0, an approach faster than the threshold, load at
// the end of the solve), and at what approach speed (m/s, < 0).
bool bounces(uint p, uint k, out float e, out float before)
{
    e = uintBitsToFloat(manifolds[p].info.w);
    if (e == 0.0 || manifolds[p].impulse[k].w <= 0.0) return false;
    before = approach(p, k);
    return before < -params.contact.y;
}

// Apply impulse `size` along the normal of pair p at point k to body b (of the pair's end
// `is_b`).
void push_body(inout solver_body b, uint p, uint k, bool is_b, float size)
{
    vec3 n = manifolds[p].normal.xyz;
    vec3 r = is_b ? constraints[p].p[k].rb.xyz : constraints[p].p[k].ra.xyz;
    float sign = is_b ? 1.0 : -1.0;
    b.v += (sign * size * b.inv_mass) * n;
    b.w += solver_inv_inertia(b, cross(r, sign * size * n));
}

// The impulse that makes point k of pair p leave at -e * before, from the velocities of
// `me` and the other body; added to the step's normal impulse (impulse.w) and kept for the
// other body in mass.w. The point carries no force into the next step (impulse.xyz): it is
// leaving, and the force of its impact, carried, pushed the body out again (a ball bounced
// 7 % higher than e^2 of its drop).
float bounce_impulse(uint p, uint k, solver_body me, bool is_b, uint other, float e,
                     float before)
{
    solver_body o = solver_body_load(other);
    solver_body a = is_b ? o : me, b = is_b ? me : o;
    // Whole vec4 loads: ra.w read alone through the address reads 0 on lavapipe (see
    // block_stiffness_unit).
    vec4 ra = constraints[p].p[k].ra, rb = constraints[p].p[k].rb;
    vec3 n = manifolds[p].normal.xyz;
    float vn = dot((b.v + cross(b.w, rb.xyz)) - (a.v + cross(a.w, ra.xyz)), n);
    vec4 impulse = manifolds[p].impulse[k];
    float total = max(impulse.x - ra.w * (vn + e * before), 0.0);
    float size = total - impulse.x;
    manifolds[p].impulse[k] = vec4(0.0, 0.0, 0.0, impulse.w + size);
    constraints[p].p[k].mass.w = size;
    return size;
}

// The bounces of body listed.x, at place `order` in the sweep (block_order), by one
// invocation.
void bounce_body(uvec4 listed, uint order)
{
    uint i = listed.x;
    solver_body me = solver_body_load(i);
    bool moved = false;
    // The impulses of pairs whose other body came first, then those this body finds.
    for (uint pass = 0u; pass < 2u; pass++) {
        for (uint at = listed.y; at < listed.y + listed.z; at++) {
            uvec2 entry = block_entries[at];
            if (block_is_joint(entry.x)) continue;   // joints do not bounce
            uint p = block_pair(entry.x), k = block_point_of(entry.x);
            float e, before;
            if (!bounces(p, k, e, before)) continue;
            uint word = body_colour[entry.y];
            bool other_first = word != TB_BLOCK_NOT_SOLVED && block_moved_before(word, order);
            if (other_first != (pass == 0u)) continue;
            bool is_b = block_is_b(entry.x);
            float size = other_first ? constraints[p].p[k].mass.w
                                     : bounce_impulse(p, k, me, is_b, entry.y, e, before);
            push_body(me, p, k, is_b, size);
            moved = true;
        }
    }
    if (!moved) return;
    solver_bodies[i].linear.xyz = me.v;
    solver_bodies[i].angular.xyz = me.w;
}

void main()
{
    if (step_aborted()) return;
    uint colour = push.args.x;
    if (colour >= TB_MAX_COLOURS) {
        // The tail: its bodies one after the other, by one invocation.
        if (gl_LocalInvocationIndex != 0u) return;
        uint start = block_tail_start();
        for (uint t = 0u; t < counters.colouring.z; t++)
            bounce_body(block_list[start + t], uint(TB_MAX_COLOURS) + t);
        return;
    }
    uvec4 listed;
    uint lane;
    if (!block_listed(colour, listed, lane) || lane != 0u) return;
    bounce_body(listed, colour);
}
