#version 450
#extension GL_GOOGLE_include_directive : require
// After the three sorts: keep this step's order in its half and each endpoint's place in
// it (invocation t handles places t and n + t of every axis: coalesced reads). On axis 0
// the class of the keys (real, large, dead) changes at most twice: the invocation that
// sees a change writes where, so the large bodies' begins (in slot order: the sort is
// stable) form the list every dynamic body tests.
#include "world.glsl"
#include "isap.glsl"

uint key_class(uint key)
{
    return key == TB_ISAP_KEY_DEAD ? 2u : key == TB_ISAP_KEY_LARGE ? 1u : 0u;
}

// Entry p of axis 0: the first large and first dead entries (2n when there is none).
void mark_classes(uint p, uint n)
{
    IsapControl c = isap_control();
    uint here = key_class(isap_keys().v[isap_at(0u, p)]);
    uint before = p == 0u ? 0u : key_class(isap_keys().v[isap_at(0u, p - 1u)]);
    if (here >= 1u && (p == 0u || before == 0u)) c.c.sort.y = p;
    if (here == 2u && (p == 0u || before < 2u)) c.c.sort.z = p;
    if (p + 1u == 2u * n) {
        if (here < 1u) c.c.sort.y = 2u * n;
        if (here < 2u) c.c.sort.z = 2u * n;
    }
}

void main()
{
    uint t = body_thread_index();
    uint n = isap_slots();
    if (t >= n || step_aborted()) return;
    IsapUints keys = isap_keys();
    IsapUints order = isap_order(isap_new_half());
    IsapUints place = isap_place(isap_new_half());
    for (uint k = 0u; k < 3u; k++) {
        for (uint p = t; p < 2u * n; p += n) {
            uint e = keys.v[isap_sorted_at(k, p)];
            order.v[isap_at(k, p)] = e;
            place.v[isap_at(k, e)] = p;
        }
    }
    mark_classes(t, n);
    mark_classes(n + t, n);
}
