// What a plugin stage sees of the world (abi/tumble_plugin.h). A stage's shader is
//
//     #version 450
//     #extension GL_GOOGLE_include_directive : require
//     #include "tumble_plugin.glsl"
//     void main()
//     {
//         if (!tb_plugin_begin()) return;
//         uint i = tb_plugin_thread_index();
//         ...
//     }
//
// Workgroups are 64 threads (local_size_x comes from a specialization constant). The
// bindings below are part of the plugin ABI: their numbers and layouts only change with
// TB_PLUGIN_ABI_VERSION. A stage may read and write the body arrays; everything else here
// is read-only. Bodies are indexed by slot, 0 to tb_plugin_body_count() - 1; dead slots have
// no TB_BODY_FLAG_ALIVE.
#ifndef TUMBLE_PLUGIN_GLSL
#define TUMBLE_PLUGIN_GLSL

#include "layout.h"

layout(local_size_x_id = TB_SPEC_WORKGROUP_SIZE) in;

layout(set = 0, binding = TB_BIND_PARAMS, std140) uniform TbParams { tb_gpu_params tb_params; };
// xyz position of the centre of mass (m), w inverse mass (1/kg, 0 when not dynamic)
layout(set = 0, binding = TB_BIND_BODY_POS, std430) buffer TbBodyPos { vec4 body_pos[]; };
// orientation quaternion (x, y, z, w)
layout(set = 0, binding = TB_BIND_BODY_ROT, std430) buffer TbBodyRot { vec4 body_rot[]; };
// xyz linear velocity (m/s), w linear damping (1/s)
layout(set = 0, binding = TB_BIND_BODY_LINVEL, std430) buffer TbBodyLinVel { vec4 body_linvel[]; };
// xyz angular velocity (rad/s, world frame), w angular damping (1/s)
layout(set = 0, binding = TB_BIND_BODY_ANGVEL, std430) buffer TbBodyAngVel { vec4 body_angvel[]; };
// xyz inverse principal inertia (body frame, 1/(kg m^2)), w gravity scale
layout(set = 0, binding = TB_BIND_BODY_INV_INERTIA, std430) readonly buffer TbBodyInvInertia { vec4 body_inv_inertia[]; };
// x shape slot, y flags (TB_BODY_FLAG_ALIVE, TB_BODY_FLAG_DYNAMIC)
layout(set = 0, binding = TB_BIND_BODY_INFO, std430) readonly buffer TbBodyInfo { uvec4 body_info[]; };
// world box of the body as this step's broadphase saw it (valid from post-broadphase on)
layout(set = 0, binding = TB_BIND_BODY_AABB_MIN, std430) readonly buffer TbBodyAabbMin { vec4 body_aabb_min[]; };
layout(set = 0, binding = TB_BIND_BODY_AABB_MAX, std430) readonly buffer TbBodyAabbMax { vec4 body_aabb_max[]; };
layout(set = 0, binding = TB_BIND_COUNTERS, std430) readonly buffer TbCounters { tb_gpu_counters tb_counters; };
// this step's pairs (see tb_plugin_pair)
layout(set = 0, binding = TB_BIND_PAIRS, std430) readonly buffer TbPairs { uvec4 tb_pairs[]; };
layout(set = 0, binding = TB_BIND_PLUGIN_PARAMS, std430) readonly buffer TbPluginParams { vec4 tb_plugin_params[]; };

layout(push_constant) uniform TbPluginPush { tb_gpu_plugin_push tb_plugin_push; };

// Time step of the step, s.
float tb_plugin_dt() { return tb_params.gravity.w; }
// The world's gravity, m/s^2.
vec3 tb_plugin_gravity() { return tb_params.gravity.xyz; }
// Body slots in use.
uint tb_plugin_body_count() { return tb_params.counts.x; }
bool tb_plugin_body_is(uint body, uint flags) { return (body_info[body].y & flags) == flags; }

// Vector i (0..15) of the plugin's parameter block: bytes 16 i to 16 i + 15.
vec4 tb_plugin_param(uint i) { return tb_plugin_params[tb_plugin_push.args.x + i]; }

// This thread's index in its dispatch: the body slot (per body), the pair (per pair).
uint tb_plugin_thread_index()
{
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    return group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

// Pairs this step's broadphase found (0 at the pre-step point).
uint tb_plugin_pair_count()
{
    return tb_plugin_push.args.y == TB_PLUGIN_POINT_PRE_STEP ? 0u : tb_counters.state.z;
}

// The two body slots of pair i: their boxes overlap (within the contact margin).
uvec2 tb_plugin_pair(uint i)
{
    uint half_ = tb_counters.state.y & 1u;
    return tb_pairs[half_ * tb_params.capacity.x + i].xy;
}

// False when the stage must do nothing: the step was abandoned (a buffer overflowed; it runs
// again once the buffer has grown), or this is the rerun and the stage already ran.
bool tb_plugin_begin()
{
    if (tb_counters.state.x != 0u) return false;
    uint mark = tb_counters.state.y + 1u;
    if (tb_plugin_push.args.y == TB_PLUGIN_POINT_PRE_STEP) return tb_counters.plugins.x != mark;
    if (tb_plugin_push.args.y == TB_PLUGIN_POINT_POST_BROADPHASE) return tb_counters.plugins.y != mark;
    return true;
}

#endif
