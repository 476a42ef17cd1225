#version 450
#extension GL_GOOGLE_include_directive : require
// What decides between the incremental search and one from scratch (isap_decide): how far
// the endpoints moved between last step's orders and this step's (the work of the
// incremental scans), and whether a body became large or stopped being large.
#include "world.glsl"
#include "isap.glsl"

// Per-body values are clamped so a subgroup's sum fits a word (it only steers a choice).
const uint MOST = 1u << 25;

uint apart(uint a, uint b)
{
    return a > b ? a - b : b - a;
}

void main()
{
    if (step_aborted()) return;
    uint i = body_thread_index();
    uint n = isap_slots();
    bool old = isap_old_valid();
    uint moved = 0u;
    if (i < n) {
        IsapUints now = isap_place(isap_new_half());
        IsapUints before = isap_place(isap_old_half());
        for (uint k = 0u; k < 3u; k++) {
            uint b = now.v[isap_at(k, i)], e = now.v[isap_at(k, n + i)];
            if (old) moved += apart(b, before.v[isap_at(k, i)]) +
                              apart(e, before.v[isap_at(k, n + i)]);
        }
        moved = min(moved, MOST);
        if (old && isap_min(isap_old_half(), i).w != isap_min(isap_new_half(), i).w)
            isap_control().c.sort.w = 1u;
    }
    IsapControl c = isap_control();
    ISAP_ADD_WIDE(moved, c.c.moved.x, c.c.moved.y)
}
