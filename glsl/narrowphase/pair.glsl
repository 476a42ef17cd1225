// A pair as both narrowphase passes see it (contacts.comp, hull_points.comp): its bodies in
// one canonical order (by shape type, then body index), so points and feature keys depend
// only on the unordered pair and swapping a and b only negates the normal; its speculative
// reach; last step's manifold of it; and how its manifold is finished.
#ifndef TB_NP_PAIR_GLSL
#define TB_NP_PAIR_GLSL

// Speculative reach of a pair: the contact margin plus how far the two may close in within
// the step. Points up to that far apart are kept (speculative, separation > 0); the solver
// lets a gap close no faster than it would within a substep, so a fast body lands on a
// surface instead of passing through it (while its path within the step is straight).
float pair_margin(uint a, uint b)
{
    float reach_a = body_step_turn(a) * length(shapes[body_info[a].x].aabb_half.xyz);
    float reach_b = body_step_turn(b) * length(shapes[body_info[b].x].aabb_half.xyz);
    return params.contact.x + length(body_step_motion(a) - body_step_motion(b)) + reach_a +
           reach_b;
}

struct np_pair {
    uint a, b;
    uint sub;                 // which parts of a and b (pairs[].w; layout.h)
    uint triangle;            // a mesh pair's triangle
    np_body body_a, body_b;
    np_body first, second;    // the canonical order
    bool swapped;             // first is b
    np_target t;
    float margin;
};

// Which compound children of a and b a pair is of: above the triangle beside a mesh, else
// a's in the low half of w and b's in the high half.
uvec2 np_pair_children(uvec4 pair)
{
    bool mesh = pair_has_mesh(pair);
    uint child_a = mesh ? pair.w >> TB_PAIR_TRIANGLE_BITS : pair.w & 0xffffu;
    return uvec2(child_a, mesh ? child_a : pair.w >> 16);
}

// Pair p's bodies, order and margin; its target has no last step's manifold (np_pair_load
// finds that).
np_pair np_pair_bodies(uint p)
{
    np_pair q;
    uvec4 pair = pairs[pair_half_base() + p];
    q.a = pair.x;
    q.b = pair.y;
    q.sub = pair.w;
    uvec2 child = np_pair_children(pair);
    q.triangle = (pair.w & TB_PAIR_TRIANGLE_MASK) - 1u;
    q.body_a = np_load_part(q.a, child.x);
    q.body_b = np_load_part(q.b, child.y);
    q.swapped = q.body_a.type > q.body_b.type || (q.body_a.type == q.body_b.type && q.a > q.b);
    q.t = np_target(p, NP_NONE, 0u, uvec4(0u));
    // Selected operands (not one call per order): both orders run the very same
    // instructions, so their points agree to the bit.
    q.first = q.swapped ? q.body_b : q.body_a;
    q.second = q.swapped ? q.body_a : q.body_b;
    q.margin = pair_margin(q.a, q.b);
    return q;
}

// Pair p with last step's manifold of the same pair (found in last step's pairs).
np_pair np_pair_load(uint p)
{
    np_pair q = np_pair_bodies(p);
    q.t = np_target_make(p, q.a, q.b, q.sub, current_half() ^ 1u);
    return q;
}

// The manifold's cached axis cleared, but for the block solver's stiffness of the pair (w),
// which carries over from last step's manifold; every pass that writes a manifold starts so.
void np_pair_start(np_pair q)
{
    uint stiffness = q.t.prev != NP_NONE ? prev_manifolds[q.t.prev].axis.w : 0u;
    manifolds[q.t.slot].axis = uvec4(0u, 0u, 0u, stiffness);
}

// Normal (from first to second) back to a to b, and the pair's combined materials.
void np_pair_finish(np_pair q, uint count, vec3 normal)
{
    np_finish(q.t, count, q.swapped ? -normal : normal, q.a, q.b,
              sqrt(q.body_a.material.x * q.body_b.material.x),
              max(q.body_a.material.y, q.body_b.material.y));
}

// The shape type of part c of body i (a compound's child c; any other body itself).
uint np_part_type(uint i, uint c)
{
    uint s = body_info[i].x;
    if (shapes[s].info.x != TB_GPU_SHAPE_COMPOUND) return shapes[s].info.x;
    return shapes[floatBitsToUint(compound_of_shape(s).child[c].position.w)].info.x;
}

// The kind of pair p (layout.h): a round kind for round_points when it has a capsule,
// cylinder or cone (its first bucket: round_cull adds the pair's); TB_PAIR_KIND_HULL or
// TB_PAIR_KIND_CONVEX for contacts.comp (a compound pair whose parts are all apart too);
// TB_ROUND_KINDS for a pair of a body and a mesh triangle without a round shape
// (mesh_points'). The round types come last in the canonical order, so the round shape is
// the larger type, and a hull the larger of the other convex shapes.
uint np_pair_kind(uint p)
{
    uvec4 pair = pairs[pair_half_base() + p];
    if (pair.w == TB_PAIR_UNSPLIT) return TB_PAIR_KIND_CONVEX;
    uvec2 child = np_pair_children(pair);
    uint ta = np_part_type(pair.x, child.x), tb = np_part_type(pair.y, child.y);
    uint first = min(ta, tb), second = max(ta, tb);
    uint round_kind = first * 3u + second - TB_GPU_SHAPE_CAPSULE;
    if (np_is_round(second)) return round_kind * TB_GJK_BUCKETS;
    if (second == TB_GPU_SHAPE_MESH || second == TB_GPU_SHAPE_HEIGHTFIELD) return TB_ROUND_KINDS;
    return second == TB_GPU_SHAPE_HULL ? TB_PAIR_KIND_HULL : TB_PAIR_KIND_CONVEX;
}

// Pairs of kinds first..last (contiguous) as round_order listed them in colour_work's first
// list: x where they start, y how many.
uvec2 np_kind_run(uint first, uint last)
{
    uint count = 0u;
    for (uint k = first; k <= last; k++) count += counters.round_kinds[k].x;
    return uvec2(counters.round_kinds[first].z, count);
}

// Threads a pass over listed pairs spreads them across when they are few: packed into full
// warps, a few thousand pairs would leave most of a GPU idle while each warp runs its
// lanes' long routines; spread, more warps wait on memory at once.
#define NP_SPREAD_THREADS 65536u

// The listed pair (of the run np_kind_run gave) of thread t of a pass dispatched over
// every pair, or NP_NONE: threads take every spread-th one, spread a power of two up to
// 32, so that a run of few pairs still reaches about NP_SPREAD_THREADS threads.
uint np_listed_pair(uint t, uvec2 run)
{
    uint room = counters.state.z / max(run.y, 1u);
    uint spread = 1u << findMSB(clamp(min(NP_SPREAD_THREADS / max(run.y, 1u), room), 1u, 32u));
    if ((t & (spread - 1u)) != 0u || t / spread >= run.y) return NP_NONE;
    return colour_work[run.x + t / spread];
}

// Contact points for the stats: one atomic per subgroup.
void np_count_points(uint count)
{
    uint total = subgroupAdd(count);
    if (subgroupElect() && total != 0u) atomicAdd(counters.solver.w, total);
}

#endif
