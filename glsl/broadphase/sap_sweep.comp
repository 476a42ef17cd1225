#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The sweep, run twice with the same traversal (pairs.glsl): count each finder's pairs,
// then write them. The invocation of sorted position s is the finder of body i = the
// slot there: it walks t = s + 1, s + 2, ... while the box at t can still reach i's box
// on the axis (minima only grow along the order), and reports the pairs whose boxes
// touch as (lower slot, higher slot). A dynamic body then tests the large static bodies.
//
// Load balance: the lanes of a subgroup sweep side by side, one candidate each per round,
// while at least a quarter of them are still sweeping (reads of neighbouring lanes are
// neighbouring addresses). The few long sweeps left then go one at a time through the
// whole subgroup, a candidate per lane, so one long body does not hold its subgroup for
// its whole span; ballots keep its pairs in candidate order, as a lone sweep would.
#include "world.glsl"
#include "sap.glsl"

uint axis;
SapVec4s box_min;
SapVec4s box_max;

// Whether the box at sorted position t (its min already read) pairs with a finder that
// has box (fmin, fmax) and flags `fflags`: touching, not both static, t swept.
bool pairs_with(vec4 fmin, vec4 fmax, uint fflags, vec4 tmin, uint t)
{
    vec4 tmax = box_max.v[t];
    uint tflags = floatBitsToUint(tmax.w);
    if ((tflags & TB_SAP_BOX_OUT) != 0u) return false;
    if (((fflags | tflags) & TB_SAP_BOX_DYNAMIC) == 0u) return false;
    return sap_boxes_touch(fmin.xyz, fmax.xyz, tmin.xyz, tmax.xyz);
}

// Whether a box of minimum `tmin` (or any later one) is beyond the finder's reach. The
// expression is aabbs_touch's, so the sweep stops at no box that would touch.
bool beyond(vec4 tmin, vec4 fmax)
{
    return tmin[axis] - params.contact.x > fmax[axis];
}

uvec4 ordered_pair(uint i, uint j)
{
    return uvec4(min(i, j), max(i, j), TB_NO_COLOUR, 0u);
}

// The long sweeps left to the lanes flagged in `open`, each shared by the whole subgroup
// from its next candidate `next`. Subgroup-uniform control flow.
void sweep_together(bool open, uint next, vec4 fmin, vec4 fmax, uint fflags, uint n)
{
    uvec4 left = subgroupBallot(open);
    while (left != uvec4(0u)) {
        uint lane = subgroupBallotFindLSB(left);
        left[lane / 32u] &= ~(1u << (lane % 32u));
        uint start = subgroupShuffle(next, lane);
        vec4 lmin = subgroupShuffle(fmin, lane);
        vec4 lmax = subgroupShuffle(fmax, lane);
        uint lflags = subgroupShuffle(fflags, lane);
        uint base = subgroupShuffle(bp_base, lane);
        uint found = subgroupShuffle(bp_found, lane);
        for (uint c = start;; c += gl_SubgroupSize) {
            uint t = c + gl_SubgroupInvocationID;
            bool inside = t < n;
            vec4 tmin = vec4(0.0);
            if (inside) tmin = box_min.v[t];   // never a load past n, even a speculated one
            inside = inside && !beyond(tmin, lmax);
            bool hit = inside && pairs_with(lmin, lmax, lflags, tmin, t);
            uvec4 hits = subgroupBallot(hit);
            if (hit && bp_writing())
                pairs[pair_half_base() + base + found + subgroupBallotExclusiveBitCount(hits)] =
                    ordered_pair(floatBitsToUint(lmin.w), floatBitsToUint(tmin.w));
            found += subgroupBallotBitCount(hits);
            if (!subgroupAll(inside)) break;
        }
        if (gl_SubgroupInvocationID == lane) bp_found = found;
    }
}

// One round of a lone sweep: the candidate at `next`, reported when it pairs. Returns
// whether the sweep goes on.
bool sweep_step(uint i, vec4 fmin, vec4 fmax, uint fflags, uint n, inout uint next)
{
    if (next >= n) return false;
    vec4 tmin = box_min.v[next];
    if (beyond(tmin, fmax)) return false;
    if (pairs_with(fmin, fmax, fflags, tmin, next)) {
        uint j = floatBitsToUint(tmin.w);
        bp_report(min(i, j), max(i, j));
    }
    next++;
    return true;
}

void search_large(uint i, vec4 fmin, vec4 fmax)
{
    SapUints list = sap_uints(TB_SAP_LARGE_LIST);
    uint count = sap_header().h.state.y;
    for (uint l = 0u; l < count; l++) {
        uint j = list.v[l];
        if (sap_boxes_touch(fmin.xyz, fmax.xyz, body_aabb_min[j].xyz, body_aabb_max[j].xyz))
            bp_report(min(i, j), max(i, j));
    }
}

void main()
{
    if (step_aborted()) return;
    uint s = body_thread_index();
    uint n = counters.grid.z;
    axis = sap_header().h.state.x;
    box_min = sap_vec4s(TB_SAP_BOX_MIN);
    box_max = sap_vec4s(TB_SAP_BOX_MAX);
    bool valid = s < n;   // invalid invocations still take part in the subgroup's work
    vec4 fmin = vec4(0.0), fmax = vec4(0.0);
    uint fflags = TB_SAP_BOX_OUT;
    if (valid) {
        fmin = box_min.v[s];
        fmax = box_max.v[s];
        fflags = floatBitsToUint(fmax.w);
    }
    uint i = floatBitsToUint(fmin.w);
    if (valid) bp_begin(i);
    bool open = (fflags & TB_SAP_BOX_OUT) == 0u;
    uint next = s + 1u;
    while (subgroupBallotBitCount(subgroupBallot(open)) * 4u > gl_SubgroupSize) {
        if (open) open = sweep_step(i, fmin, fmax, fflags, n, next);
    }
    sweep_together(open, next, fmin, fmax, fflags, n);
    if ((fflags & (TB_SAP_BOX_OUT | TB_SAP_BOX_DYNAMIC)) == TB_SAP_BOX_DYNAMIC)
        search_large(i, fmin, fmax);
    if (valid) bp_end(i);
}
