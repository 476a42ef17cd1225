// Hull against hull, and box against hull through the box's hull data (box against box
// keeps its own path, box_box.glsl). Needs box_box.glsl (np_clearly_better, NP_BIG,
// NP_EDGE_PARALLEL) and the hull files included before it.
//
// 1. Last step's axis (tb_gpu_manifold.axis of the pair): still separating by the margin or
//    more, the pair has no contact and nothing else is tested.
//    1b. A pair whose points last step came from that axis (their feature keys name it)
//    keeps it while the two have moved less than NP_KEEP_AXIS_MOTION against each other
//    since it was chosen (axis.y sums the pair's closing motion and turn reach step by
//    step), and goes straight to step 4: a resting pile repeats no separating axis test.
//    The points are clipped afresh every step; only the choice of axis waits.
// 2. The separating axis test (hull_sat.glsl), stopping at the first separating axis,
//    which becomes the cached axis: in a pass of its own (narrowphase/hull_sat), a
//    subgroup's lanes sharing each pair's faces and edges, where one thread a pair ran the
//    longest tests alone while its warp waited.
// 3. The reference axis: A's best face, unless B's is clearly better, unless the best edge
//    pair is clearly better than that (the tolerances of box_box.glsl): faces win ties, so
//    a resting contact keeps its axis, its reference face and its feature keys from step to
//    step. It is cached too, with its separation.
// 4. Points: clipping for a face axis, closest edge points for an edge axis (hull_clip.glsl),
//    in a pass of their own (hull_points.comp) from the axis cached in step 3; the axis of
//    largest separation when the cached one leaves none.
#ifndef TB_NP_HULL_HULL_GLSL
#define TB_NP_HULL_HULL_GLSL

// How far (m) two hulls may move against each other (their closing motion and the reach of
// their turns, summed step by step) before a touching pair's axis is chosen again.
#define NP_KEEP_AXIS_MOTION 5.0e-3

// The axis of largest separation among the three candidates, without the tie rule (faces
// of A, then of B, then edges on exact ties).
uint np_strict_axis(float sep_a, uint face_a, float sep_b, uint face_b, float sep_e,
                    uint edge_a, uint edge_b)
{
    if (sep_e > sep_a && sep_e > sep_b) return np_axis_code(NP_AXIS_EDGES, edge_a, edge_b);
    if (sep_b > sep_a) return np_axis_code(NP_AXIS_FACE_B, 0u, face_b);
    return np_axis_code(NP_AXIS_FACE_A, 0u, face_a);
}

// The axis a point's feature key (hull_clip.glsl) was made along: an edge pair's, or the
// reference face's.
uint np_axis_of_feature(uint key)
{
    if ((key & 0x80000000u) != 0u) return np_axis_code(NP_AXIS_EDGES, 0u, 0u) | (key & 0x3fffffffu);
    uint kind = (key & 0x40000000u) != 0u ? NP_AXIS_FACE_B : NP_AXIS_FACE_A;
    return np_axis_code(kind, 0u, (key >> 22u) & 0xffu);
}

// Steps 1 and 1b, in narrowphase/contacts: NP_HULL_APART (the cached axis still separates),
// NP_HULL_TOUCHING (the pair keeps its axis: `strict` is it) or NP_HULL_TEST (neither: the
// separating axis test decides, in narrowphase/hull_sat). Sets the cached axis when it
// decides.
#define NP_HULL_APART 0u
#define NP_HULL_TOUCHING 1u
#define NP_HULL_TEST 2u
uint np_hull_hull_cached(np_target t, np_body a, np_body b, float margin, out uint strict)
{
    strict = 0u;
    uint cached = t.prev != NP_NONE ? prev_manifolds[t.prev].axis.x : 0u;
    if (cached == 0u) return NP_HULL_TEST;
    np_hull ha = np_hull_of(a), hb = np_hull_of(b);
    np_frame b_in_a = np_frame_between(a, b), a_in_b = np_frame_between(b, a);
    float s = np_axis_separation(cached, ha, hb, b_in_a, a_in_b);
    if (s >= margin) {
        np_set_axis(t, cached, s);
        return NP_HULL_APART;
    }
    // Step 1b: a pair that had points keeps the axis they came from while the two have
    // moved less than NP_KEEP_AXIS_MOTION against each other since it was chosen (axis.y).
    float moved = uintBitsToFloat(prev_manifolds[t.prev].axis.y) + margin - params.contact.x;
    if (t.prev_count > 0u && s > -NP_BIG && moved < NP_KEEP_AXIS_MOTION &&
        np_axis_of_feature(t.prev_features.x) == cached) {
        np_set_axis(t, cached, moved);
        strict = cached;
        return NP_HULL_TOUCHING;
    }
    return NP_HULL_TEST;
}

// Step 3, after the separating axis test found no axis beyond the margin (the best face of
// A, of B and edge pair, and their separations): the reference axis, cached. Returns
// `strict`: for hulls that overlap, the axis of largest separation, which the tie rule may
// have passed over (else the cached axis again).
uint np_hull_hull_choose(np_target t, float sep_a, uint face_a, float sep_b, uint face_b,
                         float sep_e, uint edge_a, uint edge_b)
{
    bool ref_b = np_clearly_better(sep_b, sep_a);
    uint kept = np_axis_code(NP_AXIS_FACE_A, 0u, face_a);
    if (np_clearly_better(sep_e, ref_b ? sep_b : sep_a)) {
        kept = np_axis_code(NP_AXIS_EDGES, edge_a, edge_b);
    } else if (ref_b) {
        kept = np_axis_code(NP_AXIS_FACE_B, 0u, face_b);
    }
    np_set_axis(t, kept, 0.0);
    // Only an overlap is sure to lie over the strict axis's features; hulls apart may be
    // nearest at corners no axis names, and the kept axis's speculative points (or none)
    // are as good as any.
    bool overlap = max(sep_e, max(sep_a, sep_b)) < 0.0;
    return overlap ? np_strict_axis(sep_a, face_a, sep_b, face_b, sep_e, edge_a, edge_b) : kept;
}

// The points of the touching pair along the axis `code`.
uint np_hull_hull_points_on(np_target t, np_body a, np_body b, uint code, float margin,
                            out vec3 normal)
{
    np_hull ha = np_hull_of(a), hb = np_hull_of(b);
    np_frame b_in_a = np_frame_between(a, b), a_in_b = np_frame_between(b, a);
    uint kind = code >> 30u, i = (code >> 15u) & 0x7fffu, j = code & 0x7fffu;
    if (kind == NP_AXIS_EDGES) {
        vec3 n = np_edge_axis(np_load_edge_a(ha, i, a_in_b), hb, j, a_in_b.pos).xyz;
        normal = b.rot * n;
        return np_hull_edge_contact(t, a, ha, i, b, hb, j, normal, margin);
    }
    if (kind == NP_AXIS_FACE_B) {
        normal = -(b.rot * np_hull_plane(hb, j).xyz);
        return np_hull_face_contact(t, b, hb, j, ha, a_in_b, (1u << 30u) | (j << 22u), margin);
    }
    normal = a.rot * np_hull_plane(ha, j).xyz;
    return np_hull_face_contact(t, a, ha, j, hb, b_in_a, j << 22u, margin);
}

// Step 4: the points along the axis step 3 chose (`code`). A face the tie rule kept can leave
// no corner within the margin: the hulls overlap beside the face, not over it (rocks of many
// small faces pressed together in a pile, the kept face the best axis no longer). The axis
// of largest separation (`strict`) then gives the points: along it the overlap lies over its
// face, or across its edges, so it has a point. (Without it such a pair got none for steps
// on end and sank 5 to 7 cm into each other.)
uint np_hull_hull_points(np_target t, np_body a, np_body b, uint code, uint strict,
                         float margin, out vec3 normal)
{
    uint count = np_hull_hull_points_on(t, a, b, code, margin, normal);
    if (count == 0u && strict != code) {
        count = np_hull_hull_points_on(t, a, b, strict, margin, normal);
        if (count > 0u) manifolds[t.slot].axis.x = strict;   // the axis step 1b keeps
    }
    return count;
}

// The first pass's part (contacts.comp): steps 1 and 1b. A touching pair's points are left
// to hull_points.comp by marking the manifold (axis.z = the strict axis, never 0); a pair
// they do not decide is left to narrowphase/hull_sat in np_hull_sat_pending (contacts.comp
// lists it). Returns no points.
uint np_hull_sat_pending = NP_NONE;
uint np_hull_hull_deferred(np_target t, np_body a, np_body b, float margin)
{
    uint strict;
    uint cached = np_hull_hull_cached(t, a, b, margin, strict);
    if (cached == NP_HULL_TOUCHING) manifolds[t.slot].axis.z = strict;
    if (cached == NP_HULL_TEST) np_hull_sat_pending = t.slot;
    return 0u;
}

#endif
