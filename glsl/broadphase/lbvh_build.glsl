// What the two build kernels of the linear BVH share: their push constants (layout.h,
// tb_gpu_lbvh_push) and the arrays behind them. Neither uses the world's descriptor set.
#ifndef TB_LBVH_BUILD_GLSL
#define TB_LBVH_BUILD_GLSL

#include "layout.h"

// Declared before anything reads gl_WorkGroupSize (lbvh_thread_index).
layout(local_size_x_id = TB_SPEC_WORKGROUP_SIZE) in;

#include "lbvh.glsl"

layout(push_constant) uniform Push { tb_gpu_lbvh_push push; };

uint build_capacity()
{
    return push.args.x;
}

// The count of sorted keys (leaves and the non-leaves after them), at most the capacity.
uint build_key_count()
{
    return min(LbvhUints(push.counts.xy).v[0], build_capacity());
}

// The caller's stop flag (an abandoned step) is set: do nothing.
bool build_skipped()
{
    return push.counts.zw != uvec2(0u) && LbvhUints(push.counts.zw).v[0] != 0u;
}

uint build_link_index(uint section, uint index)
{
    return lbvh_link(section, index, build_capacity());
}

#endif
