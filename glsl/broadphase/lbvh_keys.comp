#version 450
#extension GL_GOOGLE_include_directive : require
// One sort entry per body slot (value: the slot): the Morton code of its centre in the
// scene's bounds for the bodies of the tree, TB_LBVH_KEY_LARGE for static bodies larger
// than the whole scene of centres (planes, the ground), TB_LBVH_KEY_DEAD for dead slots.
// Sorted, the tree's leaves come first, then the large bodies in slot order, then the dead.
// Large bodies stay out of the tree so one plane cannot swell every node above it; each
// dynamic body tests them directly.
#include "world.glsl"

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

#include "lbvh_bodies.glsl"

// 10 bits spread to every third bit.
uint spread_bits(uint x)
{
    x = (x * 0x00010001u) & 0xff0000ffu;
    x = (x * 0x00000101u) & 0x0f00f00fu;
    x = (x * 0x00000011u) & 0xc30c30c3u;
    x = (x * 0x00000005u) & 0x49249249u;
    return x;
}

// The centre on a 1024^3 lattice over the bounds' cube (one scale for all axes keeps
// cells cubic, so a flat scene splits along its long axes first).
uint morton_code(vec3 c, vec3 lo, float extent)
{
    float scale = extent > 1.0e-30 ? 1024.0 / extent : 0.0;
    vec3 q = clamp((c - lo) * scale, vec3(0.0), vec3(1023.0));
    if (any(isnan(q))) q = vec3(0.0);
    uvec3 u = uvec3(q);
    return (spread_bits(u.x) << 2) | (spread_bits(u.y) << 1) | spread_bits(u.z);
}

void main()
{
    uint i = body_thread_index();
    if (i >= counters.grid.z || lbvh_skipped()) return;
    tb_gpu_lbvh_bounds b = lbvh_bounds().b;
    vec3 lo = from_ordered_bits(~b.lo.xyz), hi = from_ordered_bits(b.hi.xyz);
    vec3 size = b.hi.x == 0u ? vec3(0.0) : hi - lo;
    float extent = max(size.x, max(size.y, size.z));
    uint key;
    if (!body_is(i, TB_BODY_FLAG_ALIVE)) {
        key = TB_LBVH_KEY_DEAD;
    } else if (!body_is(i, TB_BODY_FLAG_DYNAMIC) &&
               (body_is(i, TB_BODY_FLAG_MESH) || body_side(i) >= TB_LBVH_UNBOUNDED_SIDE ||
                body_side(i) > extent)) {
        key = TB_LBVH_KEY_LARGE;
    } else {
        key = morton_code(body_centre(i), lo, extent);
    }
    lbvh_keys().v[i] = key;
    lbvh_values().v[i] = i;
}
