#version 450
#extension GL_GOOGLE_include_directive : require
// The hierarchy of a linear BVH from sorted keys, every internal node at once (Karras 2012,
// "Maximizing parallelism in the construction of BVHs, octrees and k-d trees"). Thread i
// is internal node i: the sign of delta(i, i + 1) - delta(i, i - 1) says which way its
// range grows, an exponential then a binary search find the range's other end, and another
// binary search the split: the last index that shares more leading bits with i than the
// range's ends do. delta is the count of leading bits two keys share, equal keys compared by
// their indices, so duplicates make a balanced subtree instead of a broken one.
//
// Keys at or above TB_LBVH_KEY_END are no leaves (they sort last): the leaves are the
// sorted keys before them, and the last leaf's thread writes their count into the links.
// Each node records its children and its range's last leaf; each child its parent; the
// right child of a node split after leaf s is "the node starting at s + 1", from which the
// refit derives every escape. Boxes come in the refit (lbvh_build_refit).
#include "lbvh_build.glsl"

LbvhUints g_keys;
uint g_count;

bool is_leaf_key(int j)
{
    return j >= 0 && uint(j) < g_count && g_keys.v[j] < TB_LBVH_KEY_END;
}

// Leading bits shared by the keys at i and j (index bits after 32 when the keys are equal);
// -1 outside the leaves.
int delta(int i, int j)
{
    if (!is_leaf_key(j)) return -1;
    uint x = g_keys.v[i] ^ g_keys.v[j];
    if (x != 0u) return 31 - findMSB(x);
    return 32 + 31 - findMSB(uint(i ^ j));
}

// The other end of node i's range, walking in direction d.
int range_end(int i, int d)
{
    int floor_delta = delta(i, i - d);
    int reach = 2;
    while (delta(i, i + reach * d) > floor_delta) reach *= 2;
    int length = 0;
    for (int step = reach / 2; step > 0; step /= 2)
        if (delta(i, i + (length + step) * d) > floor_delta) length += step;
    return i + length * d;
}

// The last leaf of the left child: the farthest index from i that shares more than the
// range's common prefix with i.
int split_of(int i, int j, int d)
{
    int node_delta = delta(i, j);
    int length = abs(j - i);
    int split = 0;
    int step = length;
    do {
        step = (step + 1) / 2;
        if (delta(i, i + (split + step) * d) > node_delta) split += step;
    } while (step > 1);
    return i + split * d + min(d, 0);
}

void set_parent(uint child, uint parent)
{
    LbvhUints links = LbvhUints(push.tree.zw);
    uint section = lbvh_is_leaf(child) ? TB_LBVH_LINK_LEAF_PARENT : TB_LBVH_LINK_PARENT;
    links.v[build_link_index(section, child & ~TB_LBVH_LEAF)] = parent;
}

void build_node(int i)
{
    int d = delta(i, i + 1) > delta(i, i - 1) ? 1 : -1;
    int j = range_end(i, d);
    int split = split_of(i, j, d);
    int first = min(i, j), last = max(i, j);
    uint left = first == split ? TB_LBVH_LEAF | uint(split) : uint(split);
    uint right = last == split + 1 ? TB_LBVH_LEAF | uint(split + 1) : uint(split + 1);
    LbvhNodes nodes = LbvhNodes(push.tree.xy);
    nodes.node[i].lo = uvec4(0u, 0u, 0u, left);
    nodes.node[i].hi = uvec4(0u, 0u, 0u, uint(last));
    set_parent(left, uint(i));
    set_parent(right, uint(i));
    LbvhUints links = LbvhUints(push.tree.zw);
    links.v[build_link_index(TB_LBVH_LINK_START, uint(split + 1))] = right;
    links.v[build_link_index(TB_LBVH_LINK_ARRIVALS, uint(i))] = 0u;
    if (i == 0) links.v[build_link_index(TB_LBVH_LINK_PARENT, 0u)] = TB_LBVH_END;
}

void main()
{
    uint t = lbvh_thread_index();
    g_count = build_key_count();
    if (t >= g_count || build_skipped()) return;
    g_keys = LbvhUints(push.keys.xy);
    int i = int(t);
    LbvhUints links = LbvhUints(push.tree.zw);
    uint leaf_count = lbvh_leaf_count_index(build_capacity());
    if (!is_leaf_key(i)) {
        if (i == 0) links.v[leaf_count] = 0u;
        return;
    }
    if (!is_leaf_key(i + 1)) {   // the last leaf: n - 1 internal nodes come before it
        links.v[leaf_count] = t + 1u;
        if (i == 0) links.v[build_link_index(TB_LBVH_LINK_LEAF_PARENT, 0u)] = TB_LBVH_END;
        return;
    }
    build_node(i);
}
