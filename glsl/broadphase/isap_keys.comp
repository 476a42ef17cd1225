#version 450
#extension GL_GOOGLE_include_directive : require
// First pass of the incremental sort and sweep: each body's six sort keys (begin and end on
// each axis), the endpoint ids the sort carries along, and its box for the next step. Dead
// slots and large static bodies get keys after every real one, so they sit at the end of
// each order and no sweep or scan ever passes them; large ones are tested directly by every
// dynamic body instead (a plane would otherwise lie across everything). Invocation 0 starts
// this step's counts and writes the header of this step's half.
#include "world.glsl"
#include "isap.glsl"
#include "ordered.glsl"

// Floats as uints that order like them, -0 and +0 equal (aabbs_touch cannot tell them apart).
uint ordered_key(float x)
{
    return ordered_bits(floatBitsToUint(x) == 0x80000000u ? 0.0 : x);
}

// Last step's bound while the bodies are the same, else one fresh from the largest dynamic
// box: a static body wider than four of them would make a sweep long.
float large_side()
{
    if (isap_old_valid()) return isap_control().c.header[isap_old_half()].large.x;
    return 4.0 * (uintBitsToFloat(counters.grid.x) + params.contact.x);
}

void start_step(float large)
{
    IsapControl c = isap_control();
    c.c.sort = uvec4(2u * isap_slots(), 0u, 0u, 0u);
    c.c.moved = uvec4(0u);
    c.c.header[isap_new_half()].set = uvec4(1u, params.counts.w, params.counts.x,
                                            floatBitsToUint(params.contact.x));
    c.c.header[isap_new_half()].large = vec4(large, 0.0, 0.0, 0.0);
}

void main()
{
    uint i = body_thread_index();
    uint n = isap_slots();
    if (i >= n || step_aborted()) return;
    float large = large_side();
    if (i == 0u) start_step(large);
    vec3 lo = body_aabb_min[i].xyz, hi = body_aabb_max[i].xyz;
    bool alive = body_is(i, TB_BODY_FLAG_ALIVE);
    vec3 side = hi - lo;
    bool is_large = alive && !body_is(i, TB_BODY_FLAG_DYNAMIC) &&
                    (body_is(i, TB_BODY_FLAG_MESH) || max(side.x, max(side.y, side.z)) > large);
    uint key = !alive ? TB_ISAP_KEY_DEAD : TB_ISAP_KEY_LARGE;
    vec3 begin = lo - params.contact.x;   // the very terms aabbs_touch compares
    IsapUints keys = isap_keys();
    for (uint k = 0u; k < 3u; k++) {
        bool real = alive && !is_large;
        keys.v[isap_at(k, i)] = real ? ordered_key(begin[k]) : key;
        keys.v[isap_at(k, n + i)] = real ? ordered_key(hi[k]) : key;
        keys.v[isap_sorted_at(k, i)] = i;
        keys.v[isap_sorted_at(k, n + i)] = n + i;
    }
    IsapVec4s boxes = isap_boxes(isap_new_half());
    boxes.v[i] = vec4(lo, is_large ? 1.0 : 0.0);
    boxes.v[isap_capacity() + i] = vec4(hi, 0.0);
}
