#version 450
#extension GL_GOOGLE_include_directive : require
// Pair finding in the linear BVH, run twice with the same walk (pairs.glsl): count, then
// write. Thread s takes the s-th sorted entry. A leaf walks the tree from its own escape,
// which visits only the leaves after it in the sorted order, so each pair of tree bodies is
// found once, by its earlier leaf, and the walk needs no stack; a dynamic body then tests
// every large static body (the run of TB_LBVH_KEY_LARGE keys after the leaves). Pairs are
// stored as (lower slot, higher slot) whoever finds them. Large and dead entries find none.
// The count pass keeps the first TB_LBVH_CACHED_PAIRS partners of each entry; the write
// pass writes an entry that found no more from them instead of walking again (the walk is
// most of the search). A pair with a mesh or compound body is one record here too; the
// midphase split divides it later.
// The count pass also clears the scene bounds for the next step.
#include "world.glsl"
#include "pairs.glsl"
#include "lbvh_bodies.glsl"

uint entry;      // this thread's sorted entry
uint partners;   // partners the count pass met so far (past TB_LBVH_CACHED_PAIRS: caches none)

void report(uint i, uint j)
{
    // A jointed pair that does not collide is never met, so the cache holds only what the
    // count counted (cached and then dropped by bp_report, it left a pair unwritten: a body
    // paired with itself).
    if (joint_keeps_apart(i, j)) return;
    if (!bp_writing() && partners < TB_LBVH_CACHED_PAIRS) {
        lbvh_cache().v[partners * lbvh_capacity() + entry] = j;
        partners++;
    }
    bp_report(min(i, j), max(i, j));
}

// Pairs body i found in the counting pass: its offset to the next slot's after the scan.
uint pairs_counted(uint i, uint slots)
{
    uint next = i + 1u < slots ? body_pair_count[i + 1u] : counters.state.z;
    return next - body_pair_count[i];
}

// The write pass of an entry that found few pairs: from the cache, in the walk's order.
bool write_cached(uint i, uint slots)
{
    uint found = pairs_counted(i, slots);
    if (found > TB_LBVH_CACHED_PAIRS) return false;
    for (uint k = 0u; k < found; k++) {
        uint j = lbvh_cache().v[k * lbvh_capacity() + entry];
        bp_report(min(i, j), max(i, j));
    }
    return true;
}

void search_tree(uint i, bool i_dynamic, tb_gpu_lbvh_node own, float margin)
{
    LbvhNodes nodes = lbvh_nodes();
    uint capacity = lbvh_capacity();
    vec3 lo = lbvh_min(own), hi = lbvh_max(own);
    uint ref = own.hi.w;
    while (ref != TB_LBVH_END) {
        tb_gpu_lbvh_node n = nodes.node[lbvh_slot(ref, capacity)];
        bool hit = lbvh_touches(lo, hi, margin, n);
        if (hit && lbvh_is_leaf(ref)) {
            uint j = n.lo.w;
            if (i_dynamic || body_is(j, TB_BODY_FLAG_DYNAMIC)) report(i, j);
        }
        ref = hit && !lbvh_is_leaf(ref) ? n.lo.w : n.hi.w;
    }
}

void search_large(uint i, uint first, uint count)
{
    LbvhUints keys = lbvh_keys();
    LbvhUints values = lbvh_values();
    for (uint s = first; s < count && keys.v[s] == TB_LBVH_KEY_LARGE; s++) {
        uint j = values.v[s];
        if (aabbs_touch(i, j)) report(i, j);
    }
}

void clear_bounds()
{
    lbvh_bounds().b = tb_gpu_lbvh_bounds(uvec4(0u), uvec4(0u));
}

void main()
{
    uint s = body_thread_index();
    uint count = counters.grid.z;
    if (s >= count || lbvh_skipped()) return;
    if (s == 0u && !bp_writing()) clear_bounds();
    uint leaves = lbvh_links().v[lbvh_leaf_count_index(lbvh_capacity())];
    uint i = lbvh_values().v[s];
    entry = s;
    partners = 0u;
    bp_begin(i);
    if (s < leaves && !(bp_writing() && write_cached(i, count))) {
        bool dynamic = body_is(i, TB_BODY_FLAG_DYNAMIC);
        tb_gpu_lbvh_node own = lbvh_nodes().node[lbvh_capacity() + s];
        search_tree(i, dynamic, own, params.contact.x);
        if (dynamic) search_large(i, leaves, count);
    }
    bp_end(i);
}
