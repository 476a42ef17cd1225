#version 450
#extension GL_GOOGLE_include_directive : require
// One round of the colouring of dynamic bodies (push.args.x = the round), per body: a body
// not yet coloured whose priority beats that of every neighbour (dynamic body it touches)
// still uncoloured when the round began takes the smallest colour no coloured neighbour
// has (Jones and Plassmann). Two neighbours never colour in the same round, and a body's
// choice depends only on what earlier rounds wrote: a neighbour coloured in this very round
// reads as uncoloured (its round is this one), and had the higher priority anyway, so the
// colouring is the same whatever order threads run in.
#include "block.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

// Largest degree first: bodies with more contact points (a proxy for more neighbours, read
// in one load) colour before the others, hashed among equals. Random priorities alone left
// the most connected bodies for last, when their neighbours had taken many colours (H100: 100k
// spheres 7 colours -> 6; the deep pile's solve 5.24 -> 4.93 ms).
uint priority(uint i)
{
    uint x = i * 0x9e3779b9u;
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return (min(block_fill[i], 255u) << 24) | (x >> 8);
}

// A body's rank in the joint graph's colouring (body_info.z, src/world/joint_ranks.c): the
// first priority, lower ranks first, so a net of joints colours as the host coloured it (a
// two-colourable net in two colours, not the five or six of hashed priorities). Every body
// has rank 0 in a world without joints, whose colouring is the same as before ranks.
uint rank_of(uint i)
{
    return params.joint_info.x != 0u ? body_info[i].z : 0u;
}

bool beats(uint a, uint ra, uint pa, uint b)
{
    uint rb = rank_of(b);
    if (ra != rb) return ra < rb;
    uint pb = priority(b);
    return pa > pb || (pa == pb && a > b);
}

void main()
{
    uint i = body_thread_index();
    uint round = push.args.x;
    if (i >= params.counts.x || step_aborted() || body_colour[i] != TB_BLOCK_NO_COLOUR) return;
    uint mine = priority(i), my_rank = rank_of(i);
    uvec2 taken = uvec2(0u);
    uint first = block_start[i], n = block_fill[i];
    for (uint k = 0u; k < n; k++) {
        uvec2 entry = block_entries[first + k];
        if (!block_is_joint(entry.x) && block_point_of(entry.x) != 0u) continue;   // one look per pair
        uint o = entry.y;
        uint word = body_colour[o];
        if (word == TB_BLOCK_NOT_SOLVED) continue;
        if (word == TB_BLOCK_NO_COLOUR || (word >> 8) == round) {
            if (!beats(i, my_rank, mine, o)) return;
            continue;
        }
        uint c = word & 0xffu;
        if (c < 32u) taken.x |= 1u << c;
        else taken.y |= 1u << (c - 32u);
    }
    uint c = taken.x != 0xffffffffu ? uint(findLSB(~taken.x))
                                    : taken.y != 0xffffffffu ? 32u + uint(findLSB(~taken.y)) : 64u;
    if (c < uint(TB_MAX_COLOURS)) body_colour[i] = c | (round << 8);
}
