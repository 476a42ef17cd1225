#version 450
#extension GL_GOOGLE_include_directive : require
// Contact events for plugins' host callbacks, after the solver (impulses final) and before
// narrowphase/keep makes this step's manifolds last step's. A pair is in contact when its
// manifold has points.
//   TB_EVENTS_BEGIN, per pair of this step: a pair with points whose last-step manifold
//     (found as the warm start finds it) had none, or which is new, began; every pair with
//     points marks its last-step manifold as continued.
//   TB_EVENTS_END, per pair of last step (a grid-stride loop): one with points that no pair
//     of this step continued ended.
// Events are appended in any order (the host sorts them); one beyond the capacity abandons
// the step, which runs again once the host grew the buffer.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "../solver/bodies.glsl"

layout(push_constant) uniform Push { tb_gpu_events_push push; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer EventArray { tb_gpu_contact_event v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer MarkArray { uint v[]; };

void emit(uint kind, tb_gpu_manifold m)
{
    uint index = atomicAdd(counters.events.x, 1u);
    if (index >= push.args.y) {
        atomicOr(counters.state.x, TB_ABORT_EVENTS);
        return;
    }
    uint points = min(m.info.x, uint(TB_MAX_MANIFOLD_POINTS));
    vec3 t1, t2;
    tangent_basis(m.normal.xyz, t1, t2);
    float normal_impulse = 0.0;
    vec2 friction = vec2(0.0);
    for (uint k = 0u; k < points; k++) {
        normal_impulse += m.impulse[k].w;
        friction += m.impulse[k].yz;
    }
    // Friction is the last substep's times the substeps, as tb_world_read_contacts gives it.
    vec3 friction_world = float(params.counts.z) * (friction.x * t1 + friction.y * t2);
    tb_gpu_contact_event e;
    e.info = uvec4(kind, m.info.y, m.info.z, counters.state.y);
    e.point = vec4(m.point[0].xyz, float(points));
    e.normal = vec4(m.normal.xyz, normal_impulse);
    e.friction = vec4(friction_world, 0.0);
    EventArray(push.address.xy).v[index] = e;
}

void begins()
{
    uint p = pair_thread_index();
    if (p >= counters.state.z || manifolds[p].info.x == 0u) return;
    uint a = manifolds[p].info.y, b = manifolds[p].info.z;
    uint previous = np_find_previous(a, b, pairs[pair_half_base() + p].w, current_half() ^ 1u);
    if (previous != NP_NONE) {
        MarkArray(push.address.zw).v[previous] = counters.state.y + 1u;
        if (prev_manifolds[previous].info.x != 0u) return;
    }
    emit(TB_EVENT_BEGIN, manifolds[p]);
}

void ends()
{
    uint count = counters.events.z;
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint q = gl_GlobalInvocationID.x; q < count; q += stride) {
        if (prev_manifolds[q].info.x == 0u) continue;
        if (MarkArray(push.address.zw).v[q] == counters.state.y + 1u) continue;
        emit(TB_EVENT_END, prev_manifolds[q]);
    }
}

void main()
{
    if (step_aborted()) return;
    if (push.args.x == TB_EVENTS_BEGIN) begins();
    else ends();
}
