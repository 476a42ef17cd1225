#version 450
#extension GL_GOOGLE_include_directive : require
// Pair finding on the grid, run twice with the same traversal: first to count the pairs
// each body owns, then to write them (pairs.glsl). Counting first makes the pair list
// deterministic, grouped by owner in slot order, and lets the host grow the pair buffer
// before anything is lost.
//
// A pair found in the grid is (lower slot, higher slot), found by whichever body searches
// the other's cell; a pair with a large static body is (dynamic body, static body), found by
// the dynamic one. Each body is entered in one cell only, and a candidate is taken only
// from the cell it really lives in (hash collisions put strangers in a bucket), so each
// overlapping pair is reported exactly once. Static-static pairs never are.
#include "world.glsl"
#include "grid.glsl"
#include "pairs.glsl"

// A pair either shares a cell or lies in two neighbouring ones. In its own cell a body takes
// the entries sorted after it; of the 26 neighbours it searches the 13 "forward" ones (the
// other 13 search it), so each pair is looked at once and the table is read 14 times, not 27.
bool forward(ivec3 d)
{
    return d.z > 0 || (d.z == 0 && (d.y > 0 || (d.y == 0 && d.x > 0)));
}

void consider(uint i, bool i_dynamic, uint j, ivec3 c, float cell)
{
    if (!i_dynamic && !body_is(j, TB_BODY_FLAG_DYNAMIC)) return;
    if (grid_cell_of(j, cell) != c || !aabbs_touch(i, j)) return;
    bp_report(min(i, j), max(i, j));
}

// Entries of cell c from sorted position `from` on (a bucket may also hold other cells).
void search_cell(uint i, bool i_dynamic, ivec3 c, float cell, uint from)
{
    uint key = grid_hash(c);
    uvec2 range = grid_table[key];
    if (range.x >= counters.grid.z || grid_keys[range.x] != key) return;
    for (uint t = max(range.x, from); t < range.y; t++)
        consider(i, i_dynamic, grid_bodies[t], c, cell);
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
        search_cell(i, dynamic, c, cell, s + 1u);
        for (int dz = 0; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    if (forward(ivec3(dx, dy, dz)))
                        search_cell(i, dynamic, c + ivec3(dx, dy, dz), cell, 0u);
        if (dynamic) search_large(i);
    }
    bp_end(i);
}
