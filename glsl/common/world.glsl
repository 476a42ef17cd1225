// The world's descriptor set as every stage sees it, and the per-body thread index.
// Layouts come from layout.h, shared with the C core.
#ifndef TB_WORLD_GLSL
#define TB_WORLD_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "layout.h"

layout(local_size_x_id = TB_SPEC_WORKGROUP_SIZE) in;
layout(constant_id = TB_SPEC_SUBGROUP_SIZE) const uint SUBGROUP_SIZE = 32;
layout(constant_id = TB_SPEC_CPU_DEVICE) const uint CPU_DEVICE = 0;

layout(set = 0, binding = TB_BIND_PARAMS, std140) uniform Params { tb_gpu_params params; };
layout(set = 0, binding = TB_BIND_BODY_POS, std430) buffer BodyPos { vec4 body_pos[]; };
layout(set = 0, binding = TB_BIND_BODY_ROT, std430) buffer BodyRot { vec4 body_rot[]; };
layout(set = 0, binding = TB_BIND_BODY_LINVEL, std430) buffer BodyLinVel { vec4 body_linvel[]; };
layout(set = 0, binding = TB_BIND_BODY_ANGVEL, std430) buffer BodyAngVel { vec4 body_angvel[]; };
layout(set = 0, binding = TB_BIND_BODY_INV_INERTIA, std430) readonly buffer BodyInvInertia { vec4 body_inv_inertia[]; };
// Read-only but where a kernel defines TB_BODY_INFO_WRITABLE first (integrate, which
// isolates a body whose state stopped being finite).
#ifdef TB_BODY_INFO_WRITABLE
layout(set = 0, binding = TB_BIND_BODY_INFO, std430) buffer BodyInfo { uvec4 body_info[]; };
#else
layout(set = 0, binding = TB_BIND_BODY_INFO, std430) readonly buffer BodyInfo { uvec4 body_info[]; };
#endif
layout(set = 0, binding = TB_BIND_BODY_AABB_MIN, std430) buffer BodyAabbMin { vec4 body_aabb_min[]; };
layout(set = 0, binding = TB_BIND_BODY_AABB_MAX, std430) buffer BodyAabbMax { vec4 body_aabb_max[]; };
layout(set = 0, binding = TB_BIND_SHAPES, std430) readonly buffer Shapes { tb_gpu_shape shapes[]; };
layout(set = 0, binding = TB_BIND_COUNTERS, std430) coherent buffer Counters { tb_gpu_counters counters; };
layout(set = 0, binding = TB_BIND_BODY_PAIRS, std430) buffer BodyPairs { uvec4 body_pairs[]; };
layout(set = 0, binding = TB_BIND_SOLVER_BODIES, std430) buffer SolverBodies { tb_gpu_solver_body solver_bodies[]; };
layout(set = 0, binding = TB_BIND_BODY_CLAIM, std430) buffer BodyClaim { uint body_claim[]; };
layout(set = 0, binding = TB_BIND_BODY_PAIR_COUNT, std430) buffer BodyPairCount { uint body_pair_count[]; };
layout(set = 0, binding = TB_BIND_GRID_KEYS, std430) buffer GridKeys { uint grid_keys[]; };
layout(set = 0, binding = TB_BIND_GRID_BODIES, std430) buffer GridBodies { uint grid_bodies[]; };
layout(set = 0, binding = TB_BIND_GRID_TABLE, std430) buffer GridTable { uvec2 grid_table[]; };
layout(set = 0, binding = TB_BIND_LARGE_FLAGS, std430) buffer LargeFlags { uint large_flags[]; };
layout(set = 0, binding = TB_BIND_LARGE_LIST, std430) buffer LargeList { uint large_list[]; };
layout(set = 0, binding = TB_BIND_PAIRS, std430) buffer Pairs { uvec4 pairs[]; };
layout(set = 0, binding = TB_BIND_COLOUR_LIST, std430) buffer ColourList { uint colour_list[]; };
layout(set = 0, binding = TB_BIND_COLOUR_WORK, std430) buffer ColourWork { uint colour_work[]; };
layout(set = 0, binding = TB_BIND_HULL_VECTORS, std430) readonly buffer HullVectors { vec4 hull_vectors[]; };
layout(set = 0, binding = TB_BIND_HULL_TOPOLOGY, std430) readonly buffer HullTopology { uint hull_topology[]; };
layout(set = 0, binding = TB_BIND_BLOCK_START, std430) buffer BlockStart { uint block_start[]; };
layout(set = 0, binding = TB_BIND_BLOCK_FILL, std430) buffer BlockFill { uint block_fill[]; };
layout(set = 0, binding = TB_BIND_BODY_COLOUR, std430) buffer BodyColour { uint body_colour[]; };
layout(set = 0, binding = TB_BIND_BLOCK_LIST, std430) buffer BlockList { uvec4 block_list[]; };
layout(set = 0, binding = TB_BIND_BLOCK_TARGET, std430) buffer BlockTarget { vec4 block_target[]; };

// The contact arrays live at device addresses (see layout.h); these names read like arrays.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ManifoldArray { tb_gpu_manifold v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ConstraintArray { tb_gpu_constraint v[]; };
#define manifolds (ManifoldArray(params.contact_arrays[0].xy).v)
#define prev_manifolds (ManifoldArray(params.contact_arrays[0].zw).v)
#define constraints (ConstraintArray(params.contact_arrays[1].xy).v)
layout(buffer_reference, std430, buffer_reference_align = 8) buffer BlockEntryArray { uvec2 v[]; };
#define block_entries (BlockEntryArray(params.contact_arrays[1].zw).v)
// The joints (layout.h, tb_gpu_params.joint_arrays and joints): read only while
// params.joint_info.x (joint slots) or params.joint_info.y (the filter's entries) is not zero.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer JointArray { tb_gpu_joint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer JointStateArray { tb_gpu_joint_state v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer JointFilterArray { uvec2 v[]; };
#define joints (JointArray(params.joint_arrays.xy).v)
#define joint_states (JointStateArray(params.joint_arrays.zw).v)
#define joint_filter (JointFilterArray(params.joint_info.zw).v)

// Whether a joint without collide_connected holds bodies a and b together: then they do
// not collide. The host's open-addressed table of slot pairs (src/joints/joints.c).
bool joint_keeps_apart(uint a, uint b)
{
    uint size = params.joint_info.y;
    if (size == 0u) return false;
    uvec2 key = uvec2(min(a, b), max(a, b)) + 1u;
    uint mask = size - 1u;
    for (uint h = TB_JOINT_FILTER_HASH(key.x, key.y) & mask, n = 0u; n < size; n++) {
        uvec2 e = joint_filter[h];
        if (e == key) return true;
        if (e.x == 0u) return false;
        h = (h + 1u) & mask;
    }
    return false;
}

// Point k's static friction slip (the block solver's) in a manifold's slip array, which
// holds two points a vec4: slips[k / 2].xy for even k, .zw for odd.
vec2 slip_of_point(vec4 pair_of_slips, uint k)
{
    return (k & 1u) == 0u ? pair_of_slips.xy : pair_of_slips.zw;
}

void set_manifold_slip(uint p, uint k, vec2 slip)
{
    if ((k & 1u) == 0u) manifolds[p].slip[k >> 1].xy = slip;
    else manifolds[p].slip[k >> 1].zw = slip;
}

// Per-body dispatches may be laid out in rows of workgroups (see body_dispatch in layout.h).
uint body_thread_index()
{
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    return group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

// Per-pair (and per-colour) indirect dispatches are laid out the same way.
uint pair_thread_index()
{
    return body_thread_index();
}

// The VkDispatchIndirectCommand covering `threads` threads in workgroups of `group_size`,
// in rows of at most TB_DISPATCH_MAX_X workgroups.
uvec4 dispatch_covering(uint threads, uint group_size)
{
    uint groups = (threads + group_size - 1u) / group_size;
    uint x = min(groups, uint(TB_DISPATCH_MAX_X));
    return uvec4(x, x == 0u ? 1u : (groups + x - 1u) / x, 1u, 0u);
}

// The step was abandoned (a buffer overflowed): no stage may change anything.
bool step_aborted()
{
    return counters.state.x != 0u;
}

// This step's half of the pair array and of the per-body pair ranges: the step parity.
uint current_half()
{
    return counters.state.y & 1u;
}

// First element of this step's half of the pair array.
uint pair_half_base()
{
    return current_half() * params.capacity.x;
}

// Whether every component is finite, by its exponent bits: a compiler may take isnan and
// isinf to be false (Vulkan does not promise NaNs are kept), never a bit test.
bool finite_all(vec4 v)
{
    uvec4 exponent = floatBitsToUint(v) & 0x7f800000u;
    return all(notEqual(exponent, uvec4(0x7f800000u)));
}

bool finite_all(vec3 v)
{
    return finite_all(vec4(v, 0.0));
}

bool body_is(uint i, uint flags)
{
    return (body_info[i].y & flags) == flags;
}

// A pair with a mesh or heightfield body: one of a body pair's triangles (layout.h,
// TB_PAIR_TRIANGLE_BITS), which mesh_points.comp, not contacts.comp, turns into points.
bool pair_has_mesh(uvec4 pair)
{
    return body_is(pair.x, TB_BODY_FLAG_MESH) || body_is(pair.y, TB_BODY_FLAG_MESH);
}

// How far body i's centre may move this step: its velocity with this step's gravity, times
// dt; zero unless it is dynamic. The broadphase sweeps boxes and the narrowphase widens a
// pair's speculative reach by it.
vec3 body_step_motion(uint i)
{
    if (!body_is(i, TB_BODY_FLAG_DYNAMIC)) return vec3(0.0);
    float dt = params.gravity.w;
    return (body_linvel[i].xyz + params.gravity.xyz * (body_inv_inertia[i].w * dt)) * dt;
}

// The angle body i may turn this step (clamped like the integration); zero unless dynamic.
// A point r from the centre moves at most this times |r|.
float body_step_turn(uint i)
{
    if (!body_is(i, TB_BODY_FLAG_DYNAMIC)) return 0.0;
    return min(length(body_angvel[i].xyz) * params.gravity.w, params.limits.x);
}

#endif
