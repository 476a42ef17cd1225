#version 450
#extension GL_GOOGLE_include_directive : require
// dst[i] = value for every i below the count. A grid-stride loop, so a fixed dispatch
// covers any count, the one only the GPU knows included.
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_fill_push p; };

void main()
{
    uint n = p.args.x;
    if (!is_null(p.dst.zw)) {
        n = Uints(p.dst.zw).v[0];
        if (p.args.x != 0u) n = min(n, p.args.x);
    }
    Uints dst = Uints(p.dst.xy);
    uint stride = gl_NumWorkGroups.x * gl_NumWorkGroups.y * WORKGROUP_SIZE;
    for (uint i = flat_group_index() * WORKGROUP_SIZE + gl_LocalInvocationIndex; i < n;
         i += stride)
        dst.v[i] = p.args.y;
}
