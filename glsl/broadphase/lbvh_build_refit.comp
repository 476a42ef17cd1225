#version 450
#extension GL_GOOGLE_include_directive : require
// Boxes and escapes of a linear BVH whose hierarchy lbvh_build_hierarchy just wrote. Thread
// k is leaf k: it copies its item's box into the leaf, then walks up. At each parent the
// first child to arrive stops (an atomic count per node) and the second, which finds its
// sibling's box written, takes the union and goes on, so every node is done exactly once,
// after both its children, in one pass.
//
// A node's escape is the node starting right after its range's last leaf (the right child
// of the node split there, links' START section), or the end after the last leaf.
#include "lbvh_build.glsl"

// The boxes of this pass are read by other workgroups while it runs: past L1.
layout(buffer_reference, std430, buffer_reference_align = 16) coherent buffer SharedNodes {
    tb_gpu_lbvh_node node[];
};

uint g_leaves;
shared uint s_climbing[3];

uint escape_after(uint last)
{
    LbvhUints links = LbvhUints(push.tree.zw);
    return last + 1u < g_leaves ? links.v[build_link_index(TB_LBVH_LINK_START, last + 1u)]
                                : TB_LBVH_END;
}

void store_node(uint slot, vec3 lo, vec3 hi, uint lo_w, uint hi_w)
{
    SharedNodes nodes = SharedNodes(push.tree.xy);
    nodes.node[slot].lo = uvec4(floatBitsToUint(lo), lo_w);
    nodes.node[slot].hi = uvec4(floatBitsToUint(hi), hi_w);
}

// One step up for a thread whose child is done: count the arrival at the parent; the
// second to arrive makes the parent's box and escape. Returns the next parent, or the end.
uint climb(inout uint child, uint parent, inout vec3 lo, inout vec3 hi)
{
    LbvhUints links = LbvhUints(push.tree.zw);
    SharedNodes nodes = SharedNodes(push.tree.xy);
    uint capacity = build_capacity();
    uint arrived = atomicAdd(links.v[build_link_index(TB_LBVH_LINK_ARRIVALS, parent)], 1u);
    if (arrived == 0u) return TB_LBVH_END;   // the sibling is not done yet: it goes on
    memoryBarrierBuffer();
    uint left = nodes.node[parent].lo.w;
    uint last = nodes.node[parent].hi.w;
    uint right = links.v[build_link_index(TB_LBVH_LINK_START, (left & ~TB_LBVH_LEAF) + 1u)];
    tb_gpu_lbvh_node sibling = nodes.node[lbvh_slot(child == left ? right : left, capacity)];
    lo = min(lo, lbvh_min(sibling));
    hi = max(hi, lbvh_max(sibling));
    store_node(parent, lo, hi, left, escape_after(last));
    child = parent;
    return links.v[build_link_index(TB_LBVH_LINK_PARENT, parent)];
}

void main()
{
    uint k = lbvh_thread_index();
    if (build_skipped()) return;
    uint capacity = build_capacity();
    LbvhUints links = LbvhUints(push.tree.zw);
    g_leaves = links.v[lbvh_leaf_count_index(capacity)];
    uint parent = TB_LBVH_END;
    uint child = TB_LBVH_LEAF | k;
    vec3 lo = vec3(0.0), hi = vec3(0.0);
    if (k < build_key_count() && k < g_leaves) {
        uint item = LbvhUints(push.keys.zw).v[k];
        lo = LbvhVec4s(push.boxes.xy).v[item].xyz;
        hi = LbvhVec4s(push.boxes.zw).v[item].xyz;
        store_node(capacity + k, lo, hi, item, escape_after(k));
        if (g_leaves > 1u) parent = links.v[build_link_index(TB_LBVH_LINK_LEAF_PARENT, k)];
    }
    // The climb runs in steps the whole workgroup takes together (a barrier each, and a
    // flag per step saying whether anyone still climbs), so the fences sit in uniform
    // flow: some implementations mishandle them once invocations have left a loop.
    // Three flags in turn let one barrier a step separate each flag's use from its reset.
    if (gl_LocalInvocationIndex < 3u) s_climbing[gl_LocalInvocationIndex] = 0u;
    barrier();
    for (uint step = 0u;; step++) {
        if (parent != TB_LBVH_END) s_climbing[step % 3u] = 1u;
        barrier();
        bool anyone = s_climbing[step % 3u] != 0u;
        if (gl_LocalInvocationIndex == 0u) s_climbing[(step + 2u) % 3u] = 0u;
        if (!anyone) break;
        memoryBarrierBuffer();   // the box just written, before the arrival that shares it
        if (parent != TB_LBVH_END) parent = climb(child, parent, lo, hi);
    }
}
