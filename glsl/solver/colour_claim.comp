#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Colouring, claim pass of round r = push.args.x, sub-round s = push.args.y (see
// colouring.glsl): every uncoloured constraint claims its dynamic bodies, unless one of them
// was taken in an earlier sub-round of this round. Per pair, counters.pair_dispatch.
// Round 0 also counts the step's constraints into counters.solver.y (one atomic per
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
    uint p = pair_thread_index();
    uint round = push.args.x, sub_round = push.args.y;
    if (round >= TB_MAX_COLOURS) return;
    if (p == 0u && sub_round == 0u)
        counters.colour[round].y = round == 0u ? 0u
            : counters.colour[round - 1u].y + counters.colour[round - 1u].x;
    uint points = 0u;
    if (p < counters.state.z) {
        uint at = pair_half_base() + p;
        uvec4 pair = pairs[at];
        points = min(manifolds[p].info.x, uint(TB_MAX_MANIFOLD_POINTS));
        uint v = colour_claim_value(p, round), mark = colour_taken_mark(round);
        bool blocked = sub_round > 0u && (taken(pair.x, mark) || taken(pair.y, mark));
        if (points > 0u && pair.z == TB_NO_COLOUR && v != TB_CLAIM_FREE && !blocked) {
            claim(pair.x, v);
            claim(pair.y, v);
        }
    }
    if (round == 0u && sub_round == 0u) {
        uint constraints = subgroupAdd(points > 0u ? 1u : 0u);
        if (subgroupElect() && constraints > 0u) atomicAdd(counters.solver.y, constraints);
    }
}
