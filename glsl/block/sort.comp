#version 450
#extension GL_GOOGLE_include_directive : require
// Per body: its contact list in increasing entry order (insertion sort; lists are short), so
// the sums of the solve run in the same order every time and a run is repeatable.
#include "block.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    uint first = block_start[i], n = block_fill[i];
    for (uint a = 1u; a < n; a++) {
        uvec2 e = block_entries[first + a];
        uint b = a;
        for (; b > 0u && block_entries[first + b - 1u].x > e.x; b--)
            block_entries[first + b] = block_entries[first + b - 1u];
        block_entries[first + b] = e;
    }
}
