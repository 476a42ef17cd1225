#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Narrowphase: the separating axis test (hull_sat.glsl; hull_hull.glsl steps 2 and 3) of
// the hull pairs narrowphase/contacts listed (counters.hull_sat.x of them, in colour_work's
// second list): those whose last axis neither still separates nor is kept. A subgroup takes
// a pair at a time, its lanes sharing A's faces, then B's, then A's edges (each lane walks
// B's Gauss map for its own edges of A), and the best of each search is the subgroup's
// maximum, ties to the lowest index as one thread's loop finds them. With a thread per
// pair, the few pairs of a step that needed the whole test ran its hundreds of faces times
// vertices alone while the rest of their warps waited, and the pass took as long as its
// slowest pair. The touching pairs are marked for hull_points.comp as contacts.comp marks
// those it keeps. Dispatched indirectly over counters.wide_pair_dispatch (a subgroup for
// every 32 pairs or so; each takes every so-many-th listed pair), in workgroups of
// TB_WIDE_WORKGROUP_SIZE.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "box_box.glsl"
#include "hull.glsl"
#include "hull_sat.glsl"
#include "hull_clip.glsl"
#include "hull_hull.glsl"
#include "pair.glsl"

#define NO_INDEX 0xffffffffu

// The subgroup's best (largest) separation and, of the lanes that found it, the lowest
// index (NO_INDEX from a lane that found none).
float best_of_subgroup(float separation, uint index, out uint best_index)
{
    float top = subgroupMax(separation);
    best_index = subgroupMin(separation == top ? index : NO_INDEX);
    return top;
}

// As np_best_face, the faces of r shared among the lanes.
float best_face(np_hull r, np_hull o, np_frame o_in_r, float margin, out uint face)
{
    float best = -NP_BIG;
    uint mine = NO_INDEX;
    for (uint f = gl_SubgroupInvocationID; f < r.faces; f += gl_SubgroupSize) {
        float s = np_face_separation(r, f, o, o_in_r);
        if (s > best) {
            best = s;
            mine = f;
            if (s >= margin) break;
        }
    }
    float top = best_of_subgroup(best, mine, face);
    face = face == NO_INDEX ? 0u : face;
    return top;
}

// As np_best_edges, the edges of a shared among the lanes.
float best_edges(np_hull a, np_hull b, np_frame a_in_b, float margin, out uint edge_a,
                 out uint edge_b)
{
    float best = -NP_BIG;
    uint best_a = 0u, best_b = 0u, start = 0u;
    for (uint i = gl_SubgroupInvocationID; i < a.edges; i += gl_SubgroupSize) {
        np_edge edge = np_load_edge_a(a, i, a_in_b);
        np_walk_edges(edge, i, b, a_in_b.pos, edge.u, edge.v, margin, start, best, best_a,
                      best_b);
        if (best >= margin) break;
    }
    uint packed;
    float top = best_of_subgroup(best, best > -NP_BIG ? (best_a << 15u) | best_b : NO_INDEX,
                                 packed);
    edge_a = packed == NO_INDEX ? 0u : packed >> 15u;
    edge_b = packed == NO_INDEX ? 0u : packed & 0x7fffu;
    return top;
}

// The test of pair p, by the whole subgroup (p uniform): its cached axis, and the touching
// pair's mark for hull_points.comp.
void separating_axis_test(uint p)
{
    np_pair q = np_pair_bodies(p);
    np_body a = q.first, b = q.second;
    np_hull ha = np_hull_of(a), hb = np_hull_of(b);
    np_frame b_in_a = np_frame_between(a, b), a_in_b = np_frame_between(b, a);
    uint face_a, face_b = 0u, edge_a = 0u, edge_b = 0u;
    float sep_b = -NP_BIG, sep_e = -NP_BIG;
    // The first search to find an axis beyond the margin ends the test: the pair is apart.
    uint apart = 0u;
    float apart_by = 0.0;
    float sep_a = best_face(ha, hb, b_in_a, q.margin, face_a);
    if (sep_a >= q.margin) {
        apart = np_axis_code(NP_AXIS_FACE_A, 0u, face_a);
        apart_by = sep_a;
    }
    if (apart == 0u) {
        sep_b = best_face(hb, ha, a_in_b, q.margin, face_b);
        if (sep_b >= q.margin) {
            apart = np_axis_code(NP_AXIS_FACE_B, 0u, face_b);
            apart_by = sep_b;
        }
    }
    if (apart == 0u) {
        sep_e = best_edges(ha, hb, a_in_b, q.margin, edge_a, edge_b);
        if (sep_e >= q.margin) {
            apart = np_axis_code(NP_AXIS_EDGES, edge_a, edge_b);
            apart_by = sep_e;
        }
    }
    if (!subgroupElect()) return;
    if (apart != 0u)
        np_set_axis(q.t, apart, apart_by);
    else
        manifolds[p].axis.z = np_hull_hull_choose(q.t, sep_a, face_a, sep_b, face_b, sep_e,
                                                  edge_a, edge_b);
}

void main()
{
    if (counters.state.x != 0u) return;
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint subgroups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumSubgroups;
    uint count = counters.hull_sat.x;
    for (uint k = group * gl_NumSubgroups + gl_SubgroupID; k < count; k += subgroups)
        separating_axis_test(colour_work[params.capacity.x + k]);
}
