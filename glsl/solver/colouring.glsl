// Graph colouring of the contact constraints (Jones-Plassmann / Luby rounds).
//
// A constraint is a pair whose manifold has at least one point. Round r makes colour r; it
// runs in one or more sub-rounds, each a claim pass and a decide pass. In a claim pass every
// uncoloured constraint writes its claim v into each of its dynamic bodies with atomicMin;
// in the decide pass a constraint that holds the claim of all its dynamic bodies is the
// smallest around them and takes colour r. Static bodies are never written by the solver,
// so they never block.
//
// v = ((TB_MAX_COLOURS - 1 - r) << TB_COLOUR_INDEX_BITS) | scramble(p, r). The round sits in
// the top bits and decreases, so a round's claims are below every value left by earlier
// rounds and the claims need no reset between rounds. scramble is a bijection on the index
// bits (unique claims) that changes every round: index order would let a chain colour one
// link per round, and fresh priorities keep one unlucky constraint from losing every round.
//
// Sub-rounds fill a colour further, towards a maximal set: when another sub-round follows,
// a winner marks its bodies taken (colour_taken_mark(r): below every claim of round r and
// unlike any of them) and a loser releases the bodies it held (TB_CLAIM_FREE), so the next
// sub-round's claims can land there; constraints touching a taken body sit the sub-round out.
// A claim equal to TB_CLAIM_FREE (round 0, one index at most) sits its round out, so "free"
// never reads as somebody's claim.
//
// Every decision depends only on the claims, not on the order of the atomics: the same pairs
// give the same colours on every run.
//
// Work lists: only the first pass looks at every pair. Its decide pass appends each
// constraint that did not win to a work list, and every later pass reads only the list the
// pass before it wrote (push.args.w is the pass number; list w & 1 is read, the other is
// written), so a round costs what is left to colour rather than all pairs. The lists are
// unordered (appends race), which changes nothing: decisions depend on claims alone.
#ifndef TB_COLOURING_GLSL
#define TB_COLOURING_GLSL

#include "world.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

const uint TB_CLAIM_FREE = 0xffffffffu;

// A bijection on TB_COLOUR_INDEX_BITS bits, different each round, that scatters neighbouring
// indices: xor with a constant, odd multipliers (invertible modulo 2^k) and x ^ (x >> s) are
// all invertible.
uint colour_scramble(uint p, uint round)
{
    const uint mask = (1u << TB_COLOUR_INDEX_BITS) - 1u;
    uint x = (p ^ (round * 0x2F0B3D5u)) & mask;
    x = (x * 0x9E3779B1u) & mask;
    x ^= x >> 13;
    x = (x * 0x85EBCA77u) & mask;
    x ^= x >> 11;
    return x;
}

uint colour_claim_value(uint p, uint round)
{
    return ((TB_MAX_COLOURS - 1u - round) << TB_COLOUR_INDEX_BITS) | colour_scramble(p, round);
}

// Below every claim of round `round`, above every claim of later rounds but the largest of
// the next one (which it may equal: that claim then simply holds the body).
uint colour_taken_mark(uint round)
{
    return ((TB_MAX_COLOURS - 1u - round) << TB_COLOUR_INDEX_BITS) - 1u;
}

// The constraint that work item i of this pass stands for, or TB_NO_COLOUR past the end:
// the first pass covers every pair of the step, later ones the list the pass before wrote.
uint colour_work_item(uint i)
{
    uint pass = push.args.w;
    if (pass == 0u) return i < counters.state.z ? i : TB_NO_COLOUR;
    uint list = pass & 1u;
    uint length = list == 0u ? counters.colouring.x : counters.colouring.y;
    return i < length ? colour_work[list * params.capacity.x + i] : TB_NO_COLOUR;
}

#endif
