#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Colouring, decide pass of round r = push.args.x, sub-round s = push.args.y of
// push.args.z (see colouring.glsl): an uncoloured constraint that holds the claim of each of
// its dynamic bodies takes colour r (pairs[].z = r) and places itself in the colour list at
// once, after the colours of earlier rounds (colour[r].y, written by the round's first claim
// pass); one atomic per subgroup reserves the places of its winners, so no scatter pass is
// needed. When another sub-round follows, winners mark their bodies taken and losers release
// the bodies they hold. Per pair, counters.pair_dispatch.
//
// Other threads may read a body while its holder marks or releases it: they see the holder's
// claim, the mark or TB_CLAIM_FREE, none of which is their own claim, so the outcome does not
// depend on timing.
#include "colouring.glsl"

bool holds_claim(uint body, uint v)
{
    return !body_is(body, TB_BODY_FLAG_DYNAMIC) || body_claim[body] == v;
}

void set_claim(uint body, bool held, uint value)
{
    if (held && body_is(body, TB_BODY_FLAG_DYNAMIC)) body_claim[body] = value;
}

// Places this thread's winner in colour `round` of the colour list, after the colours of
// earlier rounds: one atomic per subgroup.
void append(bool won, uint round, uint p)
{
    uvec4 ballot = subgroupBallot(won);
    uint winners = subgroupBallotBitCount(ballot);
    if (winners == 0u) return;
    uint first = 0u;
    if (subgroupElect()) first = atomicAdd(counters.colour[round].x, winners);
    first = subgroupBroadcastFirst(first);
    if (won)
        colour_list[counters.colour[round].y + first + subgroupBallotExclusiveBitCount(ballot)] = p;
}

// Appends the constraints still uncoloured to the work list the next pass reads: one atomic
// per subgroup.
void keep_for_next_pass(bool keep, uint p)
{
    uvec4 ballot = subgroupBallot(keep);
    uint kept = subgroupBallotBitCount(ballot);
    if (kept == 0u) return;
    uint list = (push.args.w & 1u) ^ 1u, first = 0u;
    if (subgroupElect())
        first = list == 0u ? atomicAdd(counters.colouring.x, kept)
                           : atomicAdd(counters.colouring.y, kept);
    first = subgroupBroadcastFirst(first);
    if (keep)
        colour_work[list * params.capacity.x + first + subgroupBallotExclusiveBitCount(ballot)] = p;
}

void main()
{
    if (step_aborted()) return;
    uint round = push.args.x;
    bool another_sub_round = push.args.y + 1u < push.args.z && round + 1u < TB_MAX_COLOURS;
    if (round >= TB_MAX_COLOURS) return;
    uint p = colour_work_item(pair_thread_index());
    bool won = false, constraint = false;
    if (p != TB_NO_COLOUR) {
        uint at = pair_half_base() + p;
        uvec4 pair = pairs[at];
        uint v = colour_claim_value(p, round);
        constraint = push.args.w != 0u || manifolds[p].info.x > 0u;
        if (constraint && v != TB_CLAIM_FREE) {
            bool holds_a = holds_claim(pair.x, v), holds_b = holds_claim(pair.y, v);
            won = holds_a && holds_b;
            if (won) pairs[at].z = round;
            if (another_sub_round) {
                uint value = won ? colour_taken_mark(round) : TB_CLAIM_FREE;
                set_claim(pair.x, holds_a, value);
                set_claim(pair.y, holds_b, value);
            }
        }
    }
    append(won, round, p);
    keep_for_next_pass(constraint && !won, p);
}
