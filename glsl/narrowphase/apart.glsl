// Where a round pair was apart. A pair whose bounding balls meet but that GJK found farther
// apart than the margin keeps, in its empty manifold, the direction it found them apart
// along (measured_normal, w NP_APART_ALONG), and its shapes' key (measured_offset.w). The
// next step's round_cull takes one support of each shape along it: while the gap along it
// still exceeds the margin, a support plane of each shows the pair apart, as GJK would have,
// in one support where GJK takes several. Kept while contact reuse is on
// (tb_world_set_contact_reuse), for whole bodies only, like reuse.glsl's manifolds.
#ifndef TB_NP_APART_GLSL
#define TB_NP_APART_GLSL

// measured_normal.w of a manifold without points: xyz a unit direction, in the first
// shape's frame (the canonical order, pair.glsl), from it to the second along which the two
// were farther apart than the margin (np_round_apart_along).
#define NP_APART_ALONG 4.0

// Keeps where GJK found the pair of manifold slot apart (without points), for round_cull to
// try first in the next step: while the shapes stay apart along it, one support of each
// shows that, where GJK would need several.
void np_keep_apart(np_pair q, uint slot, vec3 along)
{
    if (dot(along, along) == 0.0 || params.contact.w < 0.0 || !np_reusable_pair(q.a, q.b, q.sub))
        return;
    // The first body's turn loaded again: kept in registers from the pair, its rotation
    // would be held all through GJK.
    vec4 turn = quat_conj(body_rot[q.swapped ? q.b : q.a]);
    manifolds[slot].measured_normal = vec4(quat_rotate(turn, along), NP_APART_ALONG);
    manifolds[slot].measured_offset.w = uintBitsToFloat(np_shapes_key(q.a, q.b));
}

// Whether last step's manifold prev of pair q kept a direction along which its shapes were
// apart (np_keep_apart) and they still are, by more than the margin: a support plane of
// each, the proof GJK would find (the cores' supports and their rounding, np_round_normal).
bool np_still_apart(np_pair q, uint prev)
{
    if (prev == NP_NONE || prev_manifolds[prev].measured_normal.w != NP_APART_ALONG ||
        prev_manifolds[prev].info.x != 0u || !np_kept_for(q, prev))
        return false;
    vec3 along = q.first.rot * prev_manifolds[prev].measured_normal.xyz;
    np_convex A = np_convex_rounded(q.first), B = np_convex_rounded(q.second);
    vec3 o = np_core_centre(A);
    A = np_convex_moved(A, o);
    B = np_convex_moved(B, o);
    vec3 a, b;
    np_core_supports(A, B, along, a, b);
    return dot(along, b - a) - A.radius - B.radius >= q.margin;
}

// Pair q's empty manifold (slot p) while its shapes stay apart along last step's direction:
// the direction is kept on.
void np_stay_apart(np_pair q, uint prev)
{
    np_finish_empty(q.t.slot, q.a, q.b);
    manifolds[q.t.slot].measured_normal = prev_manifolds[prev].measured_normal;
    manifolds[q.t.slot].measured_offset.w = prev_manifolds[prev].measured_offset.w;
}

#endif
