#version 450
#extension GL_GOOGLE_include_directive : require
// Cell ranges of the sorted entries: the first entry of a run of equal keys writes the
// run's start into the table, the last its end. The table is never cleared: a lookup
// trusts an entry only when the key at its start is the key looked up (see grid_pairs).
#include "world.glsl"
#include "grid.glsl"

void main()
{
    uint s = body_thread_index();
    uint n = counters.grid.z;
    if (s >= n || step_aborted()) return;
    uint key = grid_keys[s];
    if (key >= grid_sentinel()) return;
    if (s == 0u || grid_keys[s - 1u] != key) grid_table[key].x = s;
    if (s + 1u == n || grid_keys[s + 1u] != key) grid_table[key].y = s + 1u;
}
