// Manifolds measured again instead of found again. A pair whose bodies have hardly moved
// against each other since its manifold was found (b's centre within params.contact.w of
// where it was in a's frame, its turn within the angle whose half's cosine is
// params.limits.y; tb_world_set_contact_reuse) touches by the same features: its points
// are carried to where the bodies are now and their separations measured again along the
// normal. The pose compared with stays the one the points were found at, so the drift
// from it cannot add up step by step.
//
// A point is kept on each body as an anchor in the body's frame and a reach along the
// normal. On a flat feature (a box's, hull's, plane's, a cylinder's cap, a cone's base) the
// anchor is the surface point itself. On a round surface it is where the normal through the
// point meets the shape's axis (a sphere's centre, a capsule's segment), the reach that
// distance: a round body that rolls a little keeps touching along the normal, where a
// point fixed on its surface would turn away with it, and push it on the way it turned.
//
// Across the normal the point lies where the round surface touches (where one side is
// flat and the other round; else midway). The normal is kept in the frame of the body whose
// feature is flat (its reach 0): turned with a round body it would tilt as the body rolls.
// Where both are round at the first point (spheres, capsules side by side) it runs from a's
// anchor to b's.
//
// Round pairs are measured again in round_cull, a hull's pairs with a box, hull or plane in
// contacts.comp (np_flat_pair_reused), before their separating axis test. (Listed for
// round_points to measure in warps of their own, the round pairs took longer: 0.12 ms less
// in round_cull, 0.17 more in round_points, 100k shapes on an H200.)
//
// Only manifolds no deeper than the contact margin are kept: a deeper one is no resting
// contact, and a wrong normal (EPA's rare slip) would be held as long as the pair stayed.
//
// A pair of whole bodies only: a compound child's or a mesh triangle's pair (pairs[].w not
// 0, or a compound or mesh body) is found again each step.
#ifndef TB_NP_REUSE_GLSL
#define TB_NP_REUSE_GLSL

// Where b is in a's frame: its rotation (quaternion) and its centre.
void np_relative_pose(uint a, uint b, out vec4 turn, out vec3 offset)
{
    vec4 qa = quat_conj(body_rot[a]);
    turn = quat_mul(qa, body_rot[b]);
    offset = quat_rotate(qa, body_pos[b].xyz - body_pos[a].xyz);
}

// The two bodies' shapes, as one key: a body destroyed and another made in its slot with
// another shape does not take the old one's manifold.
uint np_shapes_key(uint a, uint b)
{
    return body_info[a].x * 0x9e3779b1u ^ body_info[b].x;
}

// How the kept normal is turned to the bodies' poses now (measured_normal.w; 0: the
// manifold is not to be measured again).
#define NP_NORMAL_IN_A 1.0
#define NP_NORMAL_IN_B 2.0
#define NP_NORMAL_BETWEEN 3.0

// Whether pair (a, b) with parts `sub` (pairs[].w) is of two whole bodies.
bool np_reusable_pair(uint a, uint b, uint sub)
{
    uint flags = TB_BODY_FLAG_COMPOUND | TB_BODY_FLAG_MESH;
    return sub == 0u && (body_info[a].y & flags) == 0u && (body_info[b].y & flags) == 0u;
}

// The anchor (xyz) and reach (w) of surface point p of shape `body` whose outward normal
// there is u, both in the body's frame.
vec4 np_anchor(uint body, vec3 p, vec3 u)
{
    // The shape is loaded here, not taken from the pair: round_points would otherwise hold it
    // in registers all through GJK.
    uint shape = body_info[body].x;
    uint type = shapes[shape].info.x;
    vec2 size_of = shapes[shape].params.xy;
    float reach = 0.0;
    if (type == TB_GPU_SHAPE_SPHERE) {
        reach = max(dot(p, u), 0.0);
    } else if (type == TB_GPU_SHAPE_CAPSULE) {
        vec3 core = vec3(0.0, clamp(p.y, -size_of.y, size_of.y), 0.0);
        reach = length(p - core);
        return vec4(core, reach);
    } else if (type == TB_GPU_SHAPE_CYLINDER || type == TB_GPU_SHAPE_CONE) {
        // The normal's line comes nearest the axis (y) at p - t u; a cap's or base's normal
        // runs along the axis (t large): that face is flat.
        float across = dot(u.xz, u.xz);
        float t = across > 1.0e-6 ? dot(p.xz, u.xz) / across : -1.0;
        float size = 2.0 * max(size_of.x, size_of.y);
        reach = t > 0.0 && t < size ? t : 0.0;
    }
    return vec4(p - u * reach, reach);
}

// Keeps manifold slot's `count` points, as written (after np_finish, which marks a manifold
// as not kept), for a later step. Only the first `count` anchors are written or read. Every
// manifold of a round or hull pair with points passes here or through np_remeasure; one
// without points is never measured again, whatever its slot held before (np_may_remeasure).
void np_keep_measured(uint a, uint b, uint sub, uint slot, uint count)
{
    bool keep = count != 0u && params.contact.w >= 0.0 && np_reusable_pair(a, b, sub);
    // Only a resting contact: a manifold deeper than the contact margin is found anew each
    // step (a step's rare wrong normal, kept, would hold the pair in it).
    for (uint k = 0u; k < count; k++)
        keep = keep && manifolds[slot].point[k].w >= -params.contact.x;
    if (!keep) return;
    vec4 qa = quat_conj(body_rot[a]), qb = quat_conj(body_rot[b]);
    vec3 xa = body_pos[a].xyz, xb = body_pos[b].xyz;
    vec3 n = manifolds[slot].normal.xyz;
    vec3 na = quat_rotate(qa, n), nb = quat_rotate(qb, -n);
    vec2 reach = vec2(0.0);
    vec2 first_reach = vec2(0.0);
    for (uint k = 0u; k < count; k++) {
        vec4 p = manifolds[slot].point[k];
        vec3 on_a = quat_rotate(qa, p.xyz - n * (0.5 * p.w) - xa);
        vec3 on_b = quat_rotate(qb, p.xyz + n * (0.5 * p.w) - xb);
        vec4 anchor_a = np_anchor(a, on_a, na);
        vec4 anchor_b = np_anchor(b, on_b, nb);
        manifolds[slot].anchor_a[k] = anchor_a;
        manifolds[slot].anchor_b[k] = anchor_b;
        reach += vec2(anchor_a.w, anchor_b.w);
        if (k == 0u) first_reach = vec2(anchor_a.w, anchor_b.w);
    }
    bool both_round = first_reach.x > 0.0 && first_reach.y > 0.0;
    float frame = both_round ? NP_NORMAL_BETWEEN : (reach.y < reach.x ? NP_NORMAL_IN_B
                                                                       : NP_NORMAL_IN_A);
    manifolds[slot].measured_normal = vec4(frame == NP_NORMAL_IN_B ? -nb : na, frame);
    vec4 turn;
    vec3 offset;
    np_relative_pose(a, b, turn, offset);
    manifolds[slot].measured_turn = turn;
    manifolds[slot].measured_offset = vec4(offset, uintBitsToFloat(np_shapes_key(a, b)));
}

// Whether contact reuse measures pair q again beside the round pairs: a hull against a box,
// hull or plane. The other pairs of contacts.comp are found anew as cheaply as they are
// measured again: two boxes' SAT and clipping took 0.137 ms in the 100k boxes pile on an
// H200, 0.150 measured again (keeping the anchors costs what the clipping saves).
bool np_flat_pair_reused(np_pair q)
{
    return q.second.type == TB_GPU_SHAPE_HULL && q.first.type != TB_GPU_SHAPE_SPHERE;
}

// Whether last step's manifold prev of pair q kept something of the very pair: of whole
// bodies, their shapes still those it was kept with (a slot reused by a new body is not).
bool np_kept_for(np_pair q, uint prev)
{
    return np_reusable_pair(q.a, q.b, q.sub) &&
           floatBitsToUint(prev_manifolds[prev].measured_offset.w) == np_shapes_key(q.a, q.b);
}

// Whether last step's manifold prev of pair q may be measured again now (round_cull asks
// only while reuse is on, params.contact.w >= 0).
bool np_may_remeasure(np_pair q, uint prev)
{
    if (prev == NP_NONE || prev_manifolds[prev].info.x == 0u ||
        prev_manifolds[prev].measured_normal.w == 0.0 || !np_kept_for(q, prev))
        return false;
    vec4 turn;
    vec3 offset;
    np_relative_pose(q.a, q.b, turn, offset);
    vec3 drift = offset - prev_manifolds[prev].measured_offset.xyz;
    float reach = params.contact.w;
    return dot(drift, drift) <= reach * reach &&
           abs(dot(turn, prev_manifolds[prev].measured_turn)) >= params.limits.y;
}

// Manifold slot of pair q as last step's manifold prev measured again at the bodies' poses
// now: the same features, with their impulses and slip (np_emit), the supports it took.
uint np_remeasure(np_pair q, uint slot, uint prev)
{
    q.t = np_target_after(slot, prev);
    np_pair_start(q);
    vec4 qa = body_rot[q.a], qb = body_rot[q.b];
    vec3 xa = body_pos[q.a].xyz, xb = body_pos[q.b].xyz;
    vec4 kept = prev_manifolds[prev].measured_normal;
    vec3 n = quat_rotate(kept.w == NP_NORMAL_IN_B ? qb : qa, kept.xyz);
    if (kept.w == NP_NORMAL_BETWEEN) {
        vec3 between = xb + quat_rotate(qb, prev_manifolds[prev].anchor_b[0].xyz) - xa -
                       quat_rotate(qa, prev_manifolds[prev].anchor_a[0].xyz);
        if (dot(between, between) > 1.0e-12) n = normalize(between);
    }
    uint count = q.t.prev_count;
    for (uint k = 0u; k < count; k++) {
        vec4 anchor_a = prev_manifolds[prev].anchor_a[k];
        vec4 anchor_b = prev_manifolds[prev].anchor_b[k];
        manifolds[slot].anchor_a[k] = anchor_a;
        manifolds[slot].anchor_b[k] = anchor_b;
        vec3 pa = xa + quat_rotate(qa, anchor_a.xyz) + n * anchor_a.w;
        vec3 pb = xb + quat_rotate(qb, anchor_b.xyz) - n * anchor_b.w;
        float separation = dot(pb - pa, n);
        // Across the normal, the point where a round side touches now (a flat side's anchor
        // lags it as the round body rolls on, and the push there would roll it further).
        float on_a = anchor_a.w > 0.0 && anchor_b.w == 0.0 ? 1.0
                   : (anchor_b.w > 0.0 && anchor_a.w == 0.0 ? 0.0 : 0.5);
        vec3 point = mix(pb, pa, on_a) + n * ((on_a - 0.5) * separation);
        // Point k continues last step's point k (np_emit's match, known here).
        manifolds[slot].point[k] = vec4(point, separation);
        manifolds[slot].impulse[k] = vec4(prev_manifolds[prev].impulse[k].xyz, 0.0);
        set_manifold_slip(slot, k, np_prev_slip(prev, k));
    }
    np_pair_finish(q, count, q.swapped ? -n : n);   // it takes the canonical order's normal
    manifolds[slot].feature = q.t.prev_features;
    // A round pair's GJK supports (axis.y) carry on; so does a hull pair's separating axis
    // (x, hull_hull.glsl), its motion since it was chosen (y) summed as step 1b sums it, for
    // the step the pair is found anew.
    uvec2 axis = prev_manifolds[prev].axis.xy;
    float moved = uintBitsToFloat(axis.y) + q.margin - params.contact.x;
    manifolds[slot].axis.xy = uvec2(axis.x, axis.x != 0u ? floatBitsToUint(moved) : axis.y);
    manifolds[slot].measured_normal = prev_manifolds[prev].measured_normal;
    manifolds[slot].measured_turn = prev_manifolds[prev].measured_turn;
    manifolds[slot].measured_offset = prev_manifolds[prev].measured_offset;
    return count;
}

#endif
