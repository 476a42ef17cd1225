#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// query/distance: one thread per query of tb_world_query_distances. The two convex shapes,
// placed by the query's poses, are measured by GJK on their cores (convex.glsl); where the
// cores overlap, EPA or MPR gives the depth, as the query chose (the method's bits above the
// shape index, layout.h). The distance is between the surfaces (the cores' less
// both radii): negative is the depth of overlap, the normal runs from a to b, and the points
// are the closest (apart) or deepest (overlapping) points of each surface.
#include "world.glsl"
#include "quat.glsl"
#include "../narrowphase/manifold.glsl"
#include "../narrowphase/hull.glsl"
#include "../narrowphase/convex.glsl"
#include "../narrowphase/gjk.glsl"
#include "../narrowphase/epa.glsl"
#include "../narrowphase/mpr.glsl"

layout(push_constant) uniform Push { tb_gpu_distance_push push; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Queries {
    tb_gpu_distance_query q[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer Results {
    tb_gpu_distance_result r[];
};

np_body posed(vec4 position, vec4 rotation)
{
    uint s = floatBitsToUint(position.w) & TB_DISTANCE_SHAPE_MASK;
    return np_posed_shape(s, position.xyz, quat_to_mat3(rotation));
}

// The depth of overlapping cores by the query's method, as EPA's answer.
np_epa_result penetration(np_convex A, np_convex B, np_simplex s, uint word)
{
    if ((word >> TB_DISTANCE_SHAPE_BITS) != TB_DISTANCE_METHOD_MPR) return np_epa(A, B, s);
    np_mpr_result m = np_mpr(A, B);
    return np_epa_result(m.found, m.normal, m.depth, m.pa, m.pb);
}

void main()
{
    uint i = push.range.x + gl_GlobalInvocationID.x;
    if (i >= push.range.y) return;
    tb_gpu_distance_query q = Queries(push.arrays.xy).q[i];
    // About a's centre: float keeps its digits for the pair, not for its place.
    vec3 o = q.position_a.xyz;
    np_convex A = np_convex_moved(np_convex_of(posed(q.position_a, q.rotation_a)), o);
    np_convex B = np_convex_moved(np_convex_of(posed(q.position_b, q.rotation_b)), o);
    np_gjk_result g = np_gjk(A, B);
    vec3 n = vec3(0.0, 1.0, 0.0), pa = g.pa, pb = g.pb;
    float distance;
    uint status = g.status;
    if (g.status != NP_GJK_OVERLAP && g.distance > 0.0 && dot(g.v, g.v) > 0.0) {
        // Along -v, not the points' difference: v comes off the simplex clean of the
        // rounding at the points' size (np_gjk_result), which tilts their difference.
        n = -normalize(g.v);
        distance = g.distance;
    } else {
        np_epa_result e = penetration(A, B, g.simplex, floatBitsToUint(q.position_a.w));
        // Cores that only touch: EPA's nearest face (MPR's last portal), or else GJK's
        // points, their distance and direction; neither: failed, along y.
        vec3 along;
        bool touching = np_epa_or_touch(g, e, along, pa, pb);
        status = e.found ? NP_GJK_OVERLAP : (touching ? NP_GJK_SEPARATED : 3u);
        n = touching ? along : n;
        distance = e.found ? -e.depth : length(g.pb - g.pa);
    }
    distance -= A.radius + B.radius;
    pa += o + n * A.radius;
    pb += o - n * B.radius;
    Results(push.arrays.zw).r[i] = tb_gpu_distance_result(
        vec4(pa, distance), vec4(pb, uintBitsToFloat(status)), vec4(n, uintBitsToFloat(g.iterations)));
}
