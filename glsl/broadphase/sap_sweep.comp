#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
// The sweep, run twice with the same traversal (pairs.glsl): count each finder's pairs,
// then write them. The invocation of sorted position s is the finder of body i = the
// slot there: it walks t = s + 1, s + 2, ... while the box at t can still reach i's box
// on the axis (minima only grow along the order), and reports the pairs whose boxes
// touch as (lower slot, higher slot). A dynamic body then tests the large static bodies.
//
// Three gears, each taking the candidates in order from where the last one stopped, so the
// pairs of a finder come in candidate order whichever gear found them:
// 1. tiles: the workgroup loads the next run of sorted boxes into shared memory together
//    and every finder still sweeping tests them there (all lanes read the same box at
//    once), while at least a quarter of the workgroup is sweeping;
// 2. side by side: each lane reads its own next candidate, while at least a quarter of
//    its subgroup is sweeping;
// 3. together: the few long sweeps left go one at a time through the whole subgroup, a
//    candidate per lane, ballots keeping the order, so one long body (a large dynamic one
//    among small ones) does not hold its subgroup for its whole span.
#include "world.glsl"
#include "sap.glsl"

const uint TILE = gl_WorkGroupSize.x;

shared vec4 s_min[TILE];
shared vec4 s_max[TILE];
shared uint s_sweeping[TILE];   // per subgroup (there are at most TILE of them)

uint axis;
uint n;           // sorted entries that are swept (the large and dead ones follow)
SapVec4s box_min;
SapVec4s box_max;

// This invocation's finder: sorted position s, body i, box, flags; `open` while its
// sweep goes on, `next` its next candidate.
uint s;
uint i;
vec4 fmin;
vec4 fmax;
uint fflags;
bool open;
uint next;

// Whether the box (tmin, tmax) at a candidate pairs with the finder (fmin, fmax, fflags):
// swept, not both static, touching.
bool pairs_with(vec4 amin, vec4 amax, uint aflags, vec4 tmin, vec4 tmax)
{
    uint tflags = floatBitsToUint(tmax.w);
    if ((tflags & TB_SAP_BOX_OUT) != 0u) return false;
    if (((aflags | tflags) & TB_SAP_BOX_DYNAMIC) == 0u) return false;
    return sap_boxes_touch(amin.xyz, amax.xyz, tmin.xyz, tmax.xyz);
}

// Whether a box of minimum `tmin` (or any later one) is beyond the reach of a finder with
// maximum `amax`. The expression is aabbs_touch's, so no touching box is left out.
bool beyond(vec4 tmin, vec4 amax)
{
    return tmin[axis] - params.contact.x > amax[axis];
}

// One candidate of this invocation's own sweep: closes the sweep past its reach.
void take(uint t, vec4 tmin, vec4 tmax)
{
    if (t >= n || beyond(tmin, fmax)) {
        open = false;
        return;
    }
    if (pairs_with(fmin, fmax, fflags, tmin, tmax)) {
        uint j = floatBitsToUint(tmin.w);
        bp_report(min(i, j), max(i, j));
    }
    next = t + 1u;
}

// Finders of the workgroup still sweeping. Workgroup-uniform control flow.
uint workgroup_sweeping()
{
    uint mine = subgroupBallotBitCount(subgroupBallot(open));
    if (subgroupElect()) s_sweeping[gl_SubgroupID] = mine;
    barrier();
    uint total = 0u;
    for (uint g = 0u; g < gl_NumSubgroups; g++) total += s_sweeping[g];
    barrier();   // s_sweeping may be written again after this
    return total;
}

// Gear 1. Workgroup-uniform control flow.
void sweep_tiles(uint first)
{
    for (uint tile = first + 1u; workgroup_sweeping() * 4u > TILE; tile += TILE) {
        uint t = tile + gl_LocalInvocationIndex;
        if (t < n) {
            s_min[gl_LocalInvocationIndex] = box_min.v[t];
            s_max[gl_LocalInvocationIndex] = box_max.v[t];
        }
        barrier();
        // Lanes skip the candidates before the subgroup's first position together.
        uint k = min(max(subgroupMin(open ? next : 0xffffffffu), tile) - tile, TILE);
        for (; k < TILE && subgroupAny(open); k++) {
            uint c = tile + k;
            if (open && c >= next) take(c, s_min[k], s_max[k]);
        }
        barrier();   // the tile may be loaded again after this
    }
}

// Gear 2. Subgroup-uniform control flow.
void sweep_side_by_side()
{
    while (subgroupBallotBitCount(subgroupBallot(open)) * 4u > gl_SubgroupSize) {
        if (open) {
            vec4 tmin = vec4(0.0), tmax = vec4(0.0);
            if (next < n) {   // never a load past n, even a speculated one
                tmin = box_min.v[next];
                tmax = box_max.v[next];
            }
            take(next, tmin, tmax);
        }
    }
}

// Gear 3. Subgroup-uniform control flow.
void sweep_together()
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
            if (inside) tmin = box_min.v[t];
            inside = inside && !beyond(tmin, lmax);
            bool hit = inside && pairs_with(lmin, lmax, lflags, tmin, box_max.v[t]);
            uvec4 hits = subgroupBallot(hit);
            if (hit && bp_writing())
                pairs[pair_half_base() + base + found + subgroupBallotExclusiveBitCount(hits)] =
                    uvec4(min(floatBitsToUint(lmin.w), floatBitsToUint(tmin.w)),
                          max(floatBitsToUint(lmin.w), floatBitsToUint(tmin.w)),
                          TB_NO_COLOUR, 0u);
            found += subgroupBallotBitCount(hits);
            if (!subgroupAll(inside)) break;
        }
        if (gl_SubgroupInvocationID == lane) {
            bp_found = found;
            open = false;
        }
    }
}

// The large static bodies, in the sorted order after the swept ones.
void search_large()
{
    uint end = sap_header().h.state.z;
    for (uint t = n; t < end; t++) {   // the same t in every lane: one read for them all
        vec4 tmin = box_min.v[t];
        if (sap_boxes_touch(fmin.xyz, fmax.xyz, tmin.xyz, box_max.v[t].xyz)) {
            uint j = floatBitsToUint(tmin.w);
            bp_report(min(i, j), max(i, j));
        }
    }
}

void main()
{
    if (step_aborted()) return;   // the whole workgroup returns together
    uvec4 header = sap_header().h.state;
    axis = header.x;
    n = header.y;
    box_min = sap_vec4s(TB_SAP_BOX_MIN);
    box_max = sap_vec4s(TB_SAP_BOX_MAX);
    uint first = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * TILE;
    s = first + gl_LocalInvocationIndex;
    bool valid = s < counters.grid.z;   // others still take part in the shared work
    fmin = vec4(0.0);
    fmax = vec4(0.0);
    fflags = TB_SAP_BOX_OUT;
    if (valid) {
        fmin = box_min.v[s];
        fmax = box_max.v[s];
        fflags = floatBitsToUint(fmax.w);
    }
    i = floatBitsToUint(fmin.w);
    bp_found = 0u;
    bp_base = 0u;
    if (valid) bp_begin(i);
    open = (fflags & TB_SAP_BOX_OUT) == 0u;
    next = s + 1u;
    sweep_tiles(first);
    sweep_side_by_side();
    sweep_together();
    if ((fflags & (TB_SAP_BOX_OUT | TB_SAP_BOX_DYNAMIC)) == TB_SAP_BOX_DYNAMIC) search_large();
    if (valid) bp_end(i);
}
