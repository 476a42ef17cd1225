#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Colouring, claim pass of round r = push.args.x, sub-round s = push.args.y (see
// colouring.glsl): every uncoloured constraint of the pass's work claims its dynamic bodies,
// unless one of them was taken in an earlier sub-round of this round. Dispatched over
// counters.pair_dispatch (every pair; later passes have fewer items and the rest return).
// The first pass also counts the step's constraints into counters.solver.y (one atomic per
// subgroup; the narrowphase counted their points). In the first sub-round the first thread writes
// where colour r starts in the colour list: every earlier round is complete by now.
#include "colouring.glsl"

bool taken(uint body, uint mark)
{
    return body_is(body, TB_BODY_FLAG_DYNAMIC) && body_claim[body] == mark;
}

void claim(uint body, uint v)
{
    if (body_is(body, TB_BODY_FLAG_DYNAMIC)) atomicMin(body_claim[body], v);
}

void main()
{
    if (step_aborted()) return;
    uint i = pair_thread_index();
    uint round = push.args.x, sub_round = push.args.y;
    if (round >= TB_MAX_COLOURS) return;
    if (i == 0u && sub_round == 0u)
        counters.colour[round].y = round == 0u ? 0u
            : counters.colour[round - 1u].y + counters.colour[round - 1u].x;
    // The decide pass of this pass appends to the other list: it starts empty.
    if (i == 0u) {
        if ((push.args.w & 1u) == 0u) counters.colouring.y = 0u;
        else counters.colouring.x = 0u;
    }
    uint p = colour_work_item(i);
    uint points = 0u;
    if (p != TB_NO_COLOUR) {
        uvec4 pair = pairs[pair_half_base() + p];
        // Work lists hold constraints only; the first pass finds them among all pairs.
        points = push.args.w == 0u ? min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS)) : 1u;
        uint v = colour_claim_value(p, round), mark = colour_taken_mark(round);
        bool blocked = sub_round > 0u && (taken(pair.x, mark) || taken(pair.y, mark));
        if (points > 0u && v != TB_CLAIM_FREE && !blocked) {
            claim(pair.x, v);
            claim(pair.y, v);
        }
    }
    if (push.args.w == 0u) {
        uint found = subgroupAdd(points > 0u ? 1u : 0u);
        if (subgroupElect() && found > 0u) atomicAdd(counters.solver.y, found);
    }
}
