// Hull against hull, and box against hull through the box's hull data (box against box
// keeps its own path, box_box.glsl). Needs box_box.glsl (np_clearly_better, NP_BIG,
// NP_EDGE_PARALLEL) and the hull files included before it.
//
// 1. Last step's axis (tb_gpu_manifold.axis of the pair): still separating by the margin or
//    more, the pair has no contact and nothing else is tested.
// 2. The separating axis test (hull_sat.glsl), stopping at the first separating axis,
//    which becomes the cached axis.
// 3. The reference axis: A's best face, unless B's is clearly better, unless the best edge
//    pair is clearly better than that (the tolerances of box_box.glsl): faces win ties, so
//    a resting contact keeps its axis, its reference face and its feature keys from step to
//    step. It is cached too, with its separation.
// 4. Points: clipping for a face axis, closest edge points for an edge axis (hull_clip.glsl).
#ifndef TB_NP_HULL_HULL_GLSL
#define TB_NP_HULL_HULL_GLSL

uint np_hull_hull(np_target t, np_body a, np_body b, float margin, out vec3 normal)
{
    normal = vec3(0.0);
    np_hull ha = np_hull_of(a), hb = np_hull_of(b);
    np_frame b_in_a = np_frame_between(a, b), a_in_b = np_frame_between(b, a);

    uint cached = t.prev != NP_NONE ? prev_manifolds[t.prev].axis.x : 0u;
    if (cached != 0u) {
        float s = np_axis_separation(cached, ha, hb, b_in_a, a_in_b);
        if (s >= margin) {
            np_set_axis(t, cached, s);
            return 0u;
        }
    }

    uint face_a, face_b, edge_a, edge_b;
    float sep_a = np_best_face(ha, hb, b_in_a, margin, face_a);
    if (sep_a >= margin) {
        np_set_axis(t, np_axis_code(NP_AXIS_FACE_A, 0u, face_a), sep_a);
        return 0u;
    }
    float sep_b = np_best_face(hb, ha, a_in_b, margin, face_b);
    if (sep_b >= margin) {
        np_set_axis(t, np_axis_code(NP_AXIS_FACE_B, 0u, face_b), sep_b);
        return 0u;
    }
    float sep_e = np_best_edges(ha, hb, a_in_b, margin, edge_a, edge_b);
    if (sep_e >= margin) {
        np_set_axis(t, np_axis_code(NP_AXIS_EDGES, edge_a, edge_b), sep_e);
        return 0u;
    }

    bool ref_b = np_clearly_better(sep_b, sep_a);
    if (np_clearly_better(sep_e, ref_b ? sep_b : sep_a)) {
        np_set_axis(t, np_axis_code(NP_AXIS_EDGES, edge_a, edge_b), sep_e);
        vec3 n = np_edge_axis(np_load_edge_a(ha, edge_a, a_in_b), hb, edge_b, a_in_b.pos).xyz;
        normal = b.rot * n;
        return np_hull_edge_contact(t, a, ha, edge_a, b, hb, edge_b, normal, margin);
    }
    if (ref_b) {
        np_set_axis(t, np_axis_code(NP_AXIS_FACE_B, 0u, face_b), sep_b);
        normal = -(b.rot * np_hull_plane(hb, face_b).xyz);
        return np_hull_face_contact(t, b, hb, face_b, ha, a_in_b, (1u << 30u) | (face_b << 22u),
                                    margin);
    }
    np_set_axis(t, np_axis_code(NP_AXIS_FACE_A, 0u, face_a), sep_a);
    normal = a.rot * np_hull_plane(ha, face_a).xyz;
    return np_hull_face_contact(t, a, ha, face_a, hb, b_in_a, face_a << 22u, margin);
}

#endif
