#version 450
#extension GL_GOOGLE_include_directive : require
// Per body, first pass of the block solver's step: empty contact lists, and every dynamic
// body uncoloured (the others are never coloured nor solved).
#include "block.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    block_start[i] = 0u;
    block_fill[i] = 0u;
    body_colour[i] = block_dynamic(i) ? TB_BLOCK_NO_COLOUR : TB_BLOCK_NOT_SOLVED;
}
