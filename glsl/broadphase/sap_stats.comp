#version 450
#extension GL_GOOGLE_include_directive : require
// First half of the choice of the sweep axis: each workgroup's count, mean centre and sum
// of squared deviations over the bodies that are swept (dead and large ones would only
// drag the spread towards themselves), for sap_axis to fold.
#include "world.glsl"
#include "sap.glsl"

shared vec4 s_sum[gl_WorkGroupSize.x];

// The sum over the workgroup of every invocation's `x` (tree in shared memory: cheap, and
// independent of the subgroup size). Uniform control flow only.
vec4 workgroup_sum(vec4 x)
{
    uint t = gl_LocalInvocationIndex;
    s_sum[t] = x;
    barrier();
    for (uint half_size = gl_WorkGroupSize.x / 2u; half_size > 0u; half_size /= 2u) {
        if (t < half_size) s_sum[t] += s_sum[t + half_size];
        barrier();
    }
    vec4 total = s_sum[0];
    barrier();   // s_sum may be written again after this
    return total;
}

void main()
{
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    // The whole workgroup returns together: past the last row's end (dispatches in rows
    // have a few spare workgroups), or from an abandoned step.
    if (group * gl_WorkGroupSize.x >= params.counts.x || step_aborted()) return;
    uint i = body_thread_index();
    bool counted = i < params.counts.x && sap_is_swept(i);
    vec3 centre = vec3(0.0);
    if (counted) centre = 0.5 * (body_aabb_min[i].xyz + body_aabb_max[i].xyz);
    vec4 sum = workgroup_sum(vec4(centre, counted ? 1.0 : 0.0));
    vec3 mean = sum.w > 0.0 ? sum.xyz / sum.w : vec3(0.0);
    vec3 d = counted ? centre - mean : vec3(0.0);
    vec4 m2 = workgroup_sum(vec4(d * d, 0.0));
    if (gl_LocalInvocationIndex == 0u) {
        SapPartials partials = SapPartials(sap_address(TB_SAP_PARTIALS));
        partials.v[group].mean = vec4(mean, sum.w);
        partials.v[group].m2 = vec4(m2.xyz, 0.0);
    }
}
