// The choice of the sweep axis: the axis along which the centres of the swept boxes spread
// most (fewest boxes share a slab of it, so the sweeps are shortest). Any axis gives the
// same pairs; this one is quickest. A step sweeps along the axis its predecessor chose:
// sap_gather, which has every swept box in hand, leaves each workgroup's count, mean
// centre and sum of squared deviations, and workgroup 0 of the writing sweep (after
// sap_gather, so every partial is there; and only in a step that is kept) folds them into
// the next step's axis.
//
// Chan, Golub and LeVeque's pairwise update folds the partials without the cancellation
// of sum(c^2) - sum(c)^2 / n far from the origin.
#ifndef TB_SAP_AXIS_GLSL
#define TB_SAP_AXIS_GLSL

shared vec4 s_spread[2u * gl_WorkGroupSize.x];

SapPartials sap_partials()
{
    return SapPartials(sap_address(TB_SAP_PARTIALS));
}

// The sum over the workgroup of every invocation's `x` (a tree in shared memory: cheap,
// and independent of the subgroup size). Workgroup-uniform control flow.
vec4 workgroup_sum(vec4 x)
{
    uint t = gl_LocalInvocationIndex;
    s_spread[t] = x;
    barrier();
    for (uint half_size = gl_WorkGroupSize.x / 2u; half_size > 0u; half_size /= 2u) {
        if (t < half_size) s_spread[t] += s_spread[t + half_size];
        barrier();
    }
    vec4 total = s_spread[0];
    barrier();   // s_spread may be written again after this
    return total;
}

// Leave workgroup `group`'s partial: the spread of the centres of its invocations that
// are `counted`. Workgroup-uniform control flow.
void sap_axis_partial(uint group, bool counted, vec3 centre)
{
    vec4 sum = workgroup_sum(vec4(counted ? centre : vec3(0.0), counted ? 1.0 : 0.0));
    vec3 mean = sum.w > 0.0 ? sum.xyz / sum.w : vec3(0.0);
    vec3 d = counted ? centre - mean : vec3(0.0);
    vec4 m2 = workgroup_sum(vec4(d * d, 0.0));
    if (gl_LocalInvocationIndex == 0u) {
        sap_partials().v[group].mean = vec4(mean, sum.w);
        sap_partials().v[group].m2 = vec4(m2.xyz, 0.0);
    }
}

// The spread of the union of two sets (mean.w and other_mean.w are their counts).
void fold(inout vec4 mean, inout vec3 m2, vec4 other_mean, vec3 other_m2)
{
    if (other_mean.w == 0.0) return;
    float n = mean.w + other_mean.w;
    vec3 delta = other_mean.xyz - mean.xyz;
    float share = other_mean.w / n;
    m2 += other_m2 + delta * delta * (mean.w * share);
    mean = vec4(mean.xyz + delta * share, n);
}

// Fold the partials of `groups` workgroups and keep the axis of largest spread for the
// next step (header x). One workgroup, workgroup-uniform control flow.
void sap_axis_choose(uint groups)
{
    uint t = gl_LocalInvocationIndex;
    vec4 mean = vec4(0.0);
    vec3 m2 = vec3(0.0);
    for (uint g = t; g < groups; g += gl_WorkGroupSize.x)
        fold(mean, m2, sap_partials().v[g].mean, sap_partials().v[g].m2.xyz);
    s_spread[2u * t] = mean;
    s_spread[2u * t + 1u] = vec4(m2, 0.0);
    barrier();
    if (t != 0u) return;
    for (uint u = 1u; u < gl_WorkGroupSize.x; u++)
        fold(mean, m2, s_spread[2u * u], s_spread[2u * u + 1u].xyz);
    uint axis = m2.y > m2.x ? 1u : 0u;
    if (m2.z > m2[axis]) axis = 2u;
    sap_header().h.state.x = axis;
}

#endif
