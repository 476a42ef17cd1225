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
// touch as (lower slot, higher slot). A dynamic body first tests the large static bodies.
// Writing, a finder knows how many pairs the count found, and stops at the last one.
// Writing, workgroup 0 then chooses the next step's axis: the write runs only in a step
// that is kept, so a step redone after an overflow sweeps along the same axis as before.
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
#include "sap_axis.glsl"

const uint TILE = gl_WorkGroupSize.x;

shared uvec4 s_min[TILE];
shared uvec4 s_max[TILE];
shared uint s_sweeping[TILE];   // per subgroup (there are at most TILE of them)

uint n;           // sorted entries that are swept
uint large_end;   // the large bodies follow, up to here (then the dead slots)
SapBoxes box_min;
SapBoxes box_max;

// This invocation's finder: sorted position s, body i, box, flags; `open` while its
// sweep goes on, `next` its next candidate, `expected` its pairs (when writing).
uint s;
uint i;
uvec4 fmin;
uvec4 fmax;
uint fflags;
bool open;
uint next;
uint expected;

// Whether the box (tmin, tmax) at a candidate pairs with the finder's (amin, amax, with
// flags aflags): swept, not both static, touching.
bool pairs_with(uvec4 amin, uvec4 amax, uint aflags, uvec4 tmin, uvec4 tmax)
{
    uint tflags = tmax.w;
    if ((tflags & TB_SAP_BOX_OUT) != 0u) return false;
    if (((aflags | tflags) & TB_SAP_BOX_DYNAMIC) == 0u) return false;
    // Jointed bodies that do not collide (pairs.glsl's bp_report says the same; the
    // subgroup's sweep below writes its pairs itself).
    return sap_boxes_touch(amin, amax, tmin, tmax) && !joint_keeps_apart(amin.w, tmin.w);
}

// Whether a box of minimum `tmin` (or any later one) is beyond the reach of a finder with
// maximum `amax` on the sweep axis (x of the sorted boxes). The expression is
// aabbs_touch's, so no touching box is left out.
bool beyond(uvec4 tmin, uvec4 amax)
{
    return uintBitsToFloat(tmin.x) - params.contact.x > uintBitsToFloat(amax.x);
}

// One candidate of this invocation's own sweep: closes the sweep past its reach.
void take(uint t, uvec4 tmin, uvec4 tmax)
{
    if (t >= n || beyond(tmin, fmax)) {
        open = false;
        return;
    }
    if (pairs_with(fmin, fmax, fflags, tmin, tmax)) {
        uint j = tmin.w;
        bp_report(min(i, j), max(i, j));
        open = bp_found < expected;
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
            uvec4 tmin = uvec4(0u), tmax = uvec4(0u);
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
        uvec4 lmin = subgroupShuffle(fmin, lane);
        uvec4 lmax = subgroupShuffle(fmax, lane);
        uint lflags = subgroupShuffle(fflags, lane);
        uint base = subgroupShuffle(bp_base, lane);
        uint found = subgroupShuffle(bp_found, lane);
        uint wanted = subgroupShuffle(expected, lane);
        for (uint c = start;; c += gl_SubgroupSize) {
            uint t = c + gl_SubgroupInvocationID;
            bool inside = t < n;
            uvec4 tmin = uvec4(0u);
            if (inside) tmin = box_min.v[t];
            inside = inside && !beyond(tmin, lmax);
            uvec4 tmax = uvec4(0u);
            if (inside) tmax = box_max.v[t];
            bool hit = inside && pairs_with(lmin, lmax, lflags, tmin, tmax);
            // A compound's body pair is one record for the midphase to split (split.glsl).
            // (Mesh bodies are large: never swept.)
            uint a = min(lmin.w, tmin.w), b = max(lmin.w, tmin.w);
            bool split = ((lflags | tmax.w) & TB_SAP_BOX_SPLIT) != 0u;
            uint count = hit ? 1u : 0u;
            uint at = base + found + subgroupExclusiveAdd(count);
            if (hit && bp_writing())
                pairs[pair_half_base() + at] = uvec4(a, b, TB_NO_COLOUR, split ? TB_PAIR_UNSPLIT : 0u);
            found += subgroupAdd(count);
            if (!subgroupAll(inside) || found == wanted) break;
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
    for (uint t = n; t < large_end; t++) {   // the same t in every lane: one read for them all
        uvec4 tmin = box_min.v[t];
        if (sap_boxes_touch(fmin, fmax, tmin, box_max.v[t])) {
            uint j = tmin.w;
            bp_report(min(i, j), max(i, j));
        }
    }
}

// Writing: the pairs the count found for this finder, from the scanned counts (the
// offsets of slot i and of the next slot, or the total after the last).
uint finder_pairs()
{
    uint end = i + 1u < counters.grid.z ? body_pair_count[i + 1u] : counters.state.z;
    return end - bp_base;
}

void main()
{
    if (step_aborted()) return;   // the whole workgroup returns together
    uvec2 ends = sap_header().h.state.yz;   // x, the axis, is being chosen (sap_axis.glsl)
    n = ends.x;
    large_end = ends.y;
    box_min = sap_boxes(TB_SAP_BOX_MIN);
    box_max = sap_boxes(TB_SAP_BOX_MAX);
    uint first = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * TILE;
    s = first + gl_LocalInvocationIndex;
    bool valid = s < counters.grid.z;   // others still take part in the shared work
    fmin = uvec4(0u);
    fmax = uvec4(0u);
    fflags = TB_SAP_BOX_OUT;
    if (valid) {
        fmin = box_min.v[s];
        fmax = box_max.v[s];
        fflags = fmax.w;
    }
    i = fmin.w;
    bp_found = 0u;
    bp_base = 0u;
    expected = 0xffffffffu;
    if (valid) {
        bp_begin(i);
        if (bp_writing()) expected = finder_pairs();
    }
    if ((fflags & (TB_SAP_BOX_OUT | TB_SAP_BOX_DYNAMIC)) == TB_SAP_BOX_DYNAMIC) search_large();
    open = (fflags & TB_SAP_BOX_OUT) == 0u && bp_found < expected;
    next = s + 1u;
    sweep_tiles(first);
    sweep_side_by_side();
    sweep_together();
    if (valid) bp_end(i);
    uint slots = counters.grid.z;
    if (bp_writing() && first == 0u) sap_axis_choose((slots + TILE - 1u) / TILE);
}
