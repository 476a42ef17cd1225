#version 450
#extension GL_GOOGLE_include_directive : require
// The VkDispatchIndirectCommand whose workgroups cover a count of threads. Workgroups go
// in rows when there are more than the device allows in x: x = ceil(groups / rows) with
// rows = ceil(groups / limit) keeps x within the limit and wastes fewer than `rows`
// groups. Shaders find their group as y * gl_NumWorkGroups.x + x and skip what is beyond.
#include "prims.glsl"

layout(push_constant) uniform Push { tb_gpu_indirect_push p; };

void main()
{
    if (gl_LocalInvocationIndex != 0u) return;
    uint n = read_count(p.ptrs.xy, p.args.z);
    uint groups = ceil_div(n, p.args.x);
    uint rows = ceil_div(groups, p.args.y);
    Uints command = Uints(p.ptrs.zw);
    command.v[0] = groups == 0u ? 0u : ceil_div(groups, rows);
    command.v[1] = max(rows, 1u);
    command.v[2] = 1u;
}
