#version 450
#extension GL_GOOGLE_include_directive : require
// One sort entry per body slot: the hash of its cell, or the sentinel (after every cell)
// for dead and large bodies. Large static bodies are flagged for the compaction that lists
// them.
#include "world.glsl"
#include "grid.glsl"

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted()) return;
    float cell = grid_cell_size();
    bool alive = body_is(i, TB_BODY_FLAG_ALIVE);
    bool large = alive && grid_is_large(i, cell);
    large_flags[i] = large ? 1u : 0u;
    grid_keys[i] = alive && !large ? grid_hash(grid_cell_of(i, cell)) : grid_sentinel();
    grid_bodies[i] = i;
}
