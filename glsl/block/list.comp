#version 450
#extension GL_GOOGLE_include_directive : require
// Per body, after the colouring: push.args.x = 0 counts the dynamic bodies of each colour
// (counters.colour[c].x; bodies left uncoloured in counters.solver.y), 1 writes each into its
// colour's run of block_list (counters.colour[c].y on, in any order: bodies of one colour
// never touch, so the order changes nothing), with its list's range.
#include "block.glsl"

layout(push_constant) uniform Push { tb_gpu_push push; };

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    uint word = body_colour[i];
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
