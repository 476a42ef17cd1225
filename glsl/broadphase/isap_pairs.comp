#version 450
#extension GL_GOOGLE_include_directive : require
// The pair search of the incremental sort and sweep, run twice (count, then write:
// pairs.glsl). A body's run holds:
// - incrementally: the pairs of its run last step that are still wanted (last step's pairs
//   are last step's half of the pair array, found through last step's body_pairs), then the
//   pairs its endpoints' moves started (below), then its pairs with large static bodies;
// - from scratch (isap_decide): nothing; the LBVH's search writes the step's pairs.
// Pairs are (lower slot, higher slot), whoever finds them.
//
// Incremental scans: an endpoint e that moved from place o (last step's order) to place p
// (this step's) visits the entries between o and p in both orders, skipping in the new
// order those it met in the old. If the begin of one body and the end of another swapped
// places between the orders, one of the two meets the other this way (if e's old place is
// before f's, e's new after f's: f was in e's old range, or is in its new range, or else f
// moved back past e's old place, which puts e in f's old range). A pair whose overlap
// starts must have such a swap on some axis, so someone meets it; the first meeting in a
// fixed order (axis, then the four begin/end combinations) reports it, so it is reported
// once. Whether the overlap started is decided on the boxes of both steps, not the orders.
#include "world.glsl"
#include "isap.glsl"

uint n;

// Last step's decision for the pair, on last step's boxes and margin.
bool wanted_before(uint a, uint b)
{
    uint h = isap_old_half();
    float m = uintBitsToFloat(isap_control().c.header[h].set.w);
    return (body_is(a, TB_BODY_FLAG_DYNAMIC) || body_is(b, TB_BODY_FLAG_DYNAMIC)) &&
           !any(greaterThan(isap_min(h, a).xyz - m, isap_max(h, b).xyz)) &&
           !any(greaterThan(isap_min(h, b).xyz - m, isap_max(h, a).xyz));
}

// Places of endpoint e on axis k: last step's (x) and this step's (y).
uvec2 places(uint k, uint e)
{
    return uvec2(isap_place(isap_old_half()).v[isap_at(k, e)],
                 isap_place(isap_new_half()).v[isap_at(k, e)]);
}

bool within(uint x, uint lo, uint hi)
{
    return x >= lo && x <= hi;
}

// Does the scan of endpoint e (places `from`) meet the endpoint at places `other`?
bool meets(uvec2 from, uvec2 other)
{
    if (from.x == from.y) return false;
    uint lo = min(from.x, from.y), hi = max(from.x, from.y);
    return within(other.x, lo, hi) || within(other.y, lo, hi);
}

// Is (axis k, e meets f) the first meeting of the pair (a < b) in the fixed order?
bool first_meeting(uint k, uint e, uint f, uint a, uint b)
{
    for (uint axis = 0u; axis <= k; axis++) {
        uvec2 ba = places(axis, a), ea = places(axis, n + a);
        uvec2 bb = places(axis, b), eb = places(axis, n + b);
        bool here = axis == k;
        if (here && e == a && f == n + b) return true;
        if (meets(ba, eb)) return false;
        if (here && e == n + b && f == a) return true;
        if (meets(eb, ba)) return false;
        if (here && e == b && f == n + a) return true;
        if (meets(bb, ea)) return false;
        if (here && e == n + a && f == b) return true;
        if (meets(ea, bb)) return false;
    }
    return false;
}

// Body i's endpoint e met endpoint f on axis k: report the pair if its overlap started.
void met(uint i, uint k, uint e, uint f)
{
    if ((e < n) == (f < n)) return;              // two begins or two ends: no overlap changes
    uint j = f < n ? f : f - n;
    if (j == i || !bp_wanted(i, j) || wanted_before(i, j)) return;
    uint a = min(i, j), b = max(i, j);
    if (first_meeting(k, e, f, a, b)) bp_report(a, b);
}

void scan_moves(uint i)
{
    IsapUints old_order = isap_order(isap_old_half());
    IsapUints new_order = isap_order(isap_new_half());
    IsapUints old_place = isap_place(isap_old_half());
    for (uint k = 0u; k < 3u; k++) {
        for (uint e = i; e < 2u * n; e += n) {
            uvec2 at = places(k, e);
            if (at.x == at.y) continue;
            uint lo = min(at.x, at.y), hi = max(at.x, at.y);
            for (uint q = lo; q <= hi; q++) {
                uint f = old_order.v[isap_at(k, q)];
                if (f != e) met(i, k, e, f);
            }
            for (uint q = lo; q <= hi; q++) {
                uint f = new_order.v[isap_at(k, q)];
                if (f != e && !within(old_place.v[isap_at(k, f)], lo, hi)) met(i, k, e, f);
            }
        }
    }
}

// Last step's pairs of i's run that are still wanted (pairs with large bodies excepted:
// search_large finds those again). A body pair split by children or triangles left several
// pairs in a row: it is taken back once, at its first (reported again, it is split again).
void keep_old(uint i)
{
    uint h = isap_old_half();
    uvec4 ranges = body_pairs[i];
    uvec2 run = h == 0u ? ranges.xy : ranges.zw;
    uint base = h * params.capacity.x + run.x;
    for (uint t = 0u; t < run.y; t++) {
        uvec2 pair = pairs[base + t].xy;
        if (t > 0u && pairs[base + t - 1u].xy == pair) continue;
        uint j = pair.x == i ? pair.y : pair.x;
        if (!isap_large(j) && bp_wanted(pair.x, pair.y)) bp_report(pair.x, pair.y);
    }
}

// Large static bodies: their begins in axis 0's order, in slot order.
void search_large(uint i)
{
    uvec4 sort = isap_control().c.sort;
    uint count = (sort.z - sort.y) / 2u;
    IsapUints order = isap_order(isap_new_half());
    for (uint l = 0u; l < count; l++) {
        uint j = order.v[isap_at(0u, sort.y + l)];
        if (aabbs_touch(i, j)) bp_report(min(i, j), max(i, j));
    }
}

void main()
{
    uint i = body_thread_index();
    if (i >= counters.grid.z || step_aborted()) return;
    n = isap_slots();
    bool scratch = isap_from_scratch();
    if (i == 0u && !bp_writing()) {
        if (scratch) isap_control().c.stats.y += 1u;
        else isap_control().c.stats.x += 1u;
    }
    if (scratch) return;   /* the LBVH writes this step's pairs */
    bp_begin(i);
    if (body_is(i, TB_BODY_FLAG_ALIVE) && !isap_large(i)) {
        keep_old(i);
        scan_moves(i);
        if (body_is(i, TB_BODY_FLAG_DYNAMIC)) search_large(i);
    }
    bp_end(i);
}
