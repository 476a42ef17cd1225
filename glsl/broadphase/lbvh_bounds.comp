#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The bounds of the live bodies' centres (planes left out), which the Morton codes are
// relative to. A fixed count of workgroups strides over the slots and each subgroup adds
// its share with one atomicMax per coordinate; the count pass of lbvh_pairs clears the
// bounds again for the next step, once the codes no longer need them.
#include "world.glsl"

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

#include "lbvh_bodies.glsl"

void main()
{
    if (lbvh_skipped()) return;
    uint n = counters.grid.z;
    uint stride = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_WorkGroupSize.x;
    uvec3 hi = uvec3(0u), lo = uvec3(0u);
    for (uint i = body_thread_index(); i < n; i += stride) {
        if (!in_scene_bounds(i)) continue;
        uvec3 c = ordered_bits(body_centre(i));
        hi = max(hi, c);
        lo = max(lo, ~c);
    }
    hi = subgroupMax(hi);
    lo = subgroupMax(lo);
    if (!subgroupElect() || hi.x == 0u) return;
    LbvhBounds bounds = lbvh_bounds();
    for (int a = 0; a < 3; a++) {
        atomicMax(bounds.b.hi[a], hi[a]);
        atomicMax(bounds.b.lo[a], lo[a]);
    }
}
