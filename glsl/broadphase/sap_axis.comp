#version 450
#extension GL_GOOGLE_include_directive : require
// Second half of the choice of the sweep axis: one workgroup folds every sap_stats partial
// and keeps the axis along which the swept centres spread most (fewest boxes share a slab
// of it, so the sweeps are shortest). Any axis gives the same pairs; this one is quickest.
#include "world.glsl"
#include "sap.glsl"

shared vec4 s_mean[gl_WorkGroupSize.x];
shared vec4 s_m2[gl_WorkGroupSize.x];

// Chan, Golub and LeVeque's pairwise update: the spread of the union of two sets.
void fold(inout vec4 mean, inout vec3 m2, vec4 other_mean, vec3 other_m2)
{
    float n = mean.w + other_mean.w;
    if (other_mean.w == 0.0) return;
    vec3 delta = other_mean.xyz - mean.xyz;
    float share = other_mean.w / n;
    m2 += other_m2 + delta * delta * (mean.w * share);
    mean = vec4(mean.xyz + delta * share, n);
}

void main()
{
    if (step_aborted()) return;
    uint t = gl_LocalInvocationIndex;
    uint groups = (params.counts.x + TB_WORKGROUP_SIZE - 1u) / TB_WORKGROUP_SIZE;
    SapPartials partials = SapPartials(sap_address(TB_SAP_PARTIALS));
    vec4 mean = vec4(0.0);
    vec3 m2 = vec3(0.0);
    for (uint g = t; g < groups; g += gl_WorkGroupSize.x)
        fold(mean, m2, partials.v[g].mean, partials.v[g].m2.xyz);
    s_mean[t] = mean;
    s_m2[t] = vec4(m2, 0.0);
    barrier();
    if (t != 0u) return;
    for (uint u = 1u; u < gl_WorkGroupSize.x; u++) fold(mean, m2, s_mean[u], s_m2[u].xyz);
    uint axis = m2.y > m2.x ? 1u : 0u;
    if (m2.z > m2[axis]) axis = 2u;
    // The ends of the large bodies' run in the sorted order, until sap_gather finds them
    // (when there are none, or no dead slots, nothing is past the last entry).
    sap_header().h.state = uvec4(axis, params.counts.x, params.counts.x, 0u);
}
