#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Per body, after the colouring: push.args.x = 0 counts the dynamic bodies of each colour
// (counters.colour[c].x; bodies left uncoloured in counters.solver.y) and, when the host
// records the tail (all TB_MAX_COLOURS), flags the uncoloured ones (body_claim, free in the
// block solver's step until integrate resets it)
// for the compaction that lists them in body order for the tail (colour_work, the count in
// counters.colouring.z); 1 writes each coloured body into its colour's run of block_list
// (counters.colour[c].y on, in any order: bodies of one colour never touch, so the order
// changes nothing), with its list's range; 2, after the compaction, writes the tail's
// bodies after the colours' runs, in that order, and gives each its place in the tail
// (body_colour, block_order). Pass 0 also keeps in counters.colouring.w 1 + the last
// colouring round that coloured a body, so the host records no more rounds than a step
// uses (and a little room).
#include "block.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void write_tail(uint t)
{
    if (t >= counters.colouring.z) return;
    uint i = colour_work[t];
    block_list[block_tail_start() + t] = uvec4(i, block_start[i], block_fill[i], 0u);
    body_colour[i] = uint(TB_MAX_COLOURS) | (t << 8);
}

// 1 + the colouring round that coloured a body of this subgroup last, by one atomic a
// subgroup (every invocation of the pass calls this, before any returns).
void note_rounds_used(uint i)
{
    uint word = i < params.counts.x ? body_colour[i] : TB_BLOCK_NOT_SOLVED;
    bool coloured = word != TB_BLOCK_NOT_SOLVED && word != TB_BLOCK_NO_COLOUR;
    uint used = subgroupMax(coloured ? (word >> 8) + 1u : 0u);
    if (subgroupElect() && used > 0u) atomicMax(counters.colouring.w, used);
}

void main()
{
    uint i = body_thread_index();
    if (step_aborted()) return;
    if (push.args.x == 0u) note_rounds_used(i);
    if (i >= params.counts.x) return;
    if (push.args.x == 2u) {
        write_tail(i);
        return;
    }
    uint word = body_colour[i];
    bool tail_recorded = params.capacity.z == uint(TB_MAX_COLOURS);
    if (push.args.x == 0u && tail_recorded) body_claim[i] = word == TB_BLOCK_NO_COLOUR ? 1u : 0u;
    if (word == TB_BLOCK_NOT_SOLVED) return;
    if (word == TB_BLOCK_NO_COLOUR) {
        if (push.args.x == 0u) atomicAdd(counters.solver.y, 1u);
        return;
    }
    uint c = word & 0xffu;
    if (push.args.x == 0u) {
        atomicAdd(counters.colour[c].x, 1u);
        return;
    }
    uint at = atomicAdd(counters.colour[c].w, 1u);
    block_list[counters.colour[c].y + at] = uvec4(i, block_start[i], block_fill[i], 0u);
}
