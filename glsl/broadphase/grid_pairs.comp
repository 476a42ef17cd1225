#version 450
#extension GL_GOOGLE_include_directive : require
// Pair finding on the grid, run twice with the same traversal: first to count the pairs
// each body owns, then to write them (pairs.glsl). Counting first makes the pair list
// deterministic, grouped by owner in slot order, and lets the host grow the pair buffer
// before anything is lost.
//
// A pair found in the grid is owned by its lower slot; a pair with a large static body is
// owned by the dynamic body. Each body is entered in one cell only, and a candidate is
// taken only from the cell it really lives in (hash collisions put strangers in a bucket),
// so each overlapping pair is reported exactly once. Static-static pairs never are.
#include "world.glsl"
#include "grid.glsl"
#include "pairs.glsl"

void search_cell(uint i, bool i_dynamic, ivec3 c, float cell)
{
    uint key = grid_hash(c);
    uvec2 range = grid_table[key];
    if (range.x >= counters.grid.z || grid_keys[range.x] != key) return;
    for (uint t = range.x; t < range.y; t++) {
        uint j = grid_bodies[t];
        if (j <= i) continue;
        if (!i_dynamic && !body_is(j, TB_BODY_FLAG_DYNAMIC)) continue;
        if (grid_cell_of(j, cell) != c || !aabbs_touch(i, j)) continue;
        bp_report(i, j);
    }
}

void search_large(uint i)
{
    uint count = counters.grid.y;
    for (uint l = 0u; l < count; l++) {
        uint j = large_list[l];
        if (aabbs_touch(i, j)) bp_report(i, j);
    }
}

void main()
{
    uint s = body_thread_index();
    if (s >= counters.grid.z || step_aborted()) return;
    uint i = grid_bodies[s];
    bp_begin(i);
    if (grid_keys[s] < grid_sentinel()) {
        float cell = grid_cell_size();
        ivec3 c = grid_cell_of(i, cell);
        bool dynamic = body_is(i, TB_BODY_FLAG_DYNAMIC);
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    search_cell(i, dynamic, c + ivec3(dx, dy, dz), cell);
        if (dynamic) search_large(i);
    }
    bp_end(i);
}
