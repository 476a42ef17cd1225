// The lbvh broadphase's view of the bodies (src/broadphase/lbvh.c): which bodies the tree
// holds, their centres' bounds and Morton codes. Needs world.glsl and the push constants
// (tb_gpu_broadphase_push): address[0] keys | values, [1] bounds | nodes, [2] links | skip,
// [3] the pair search's cache of partners.
#ifndef TB_LBVH_BODIES_GLSL
#define TB_LBVH_BODIES_GLSL

#include "lbvh.glsl"
#include "ordered.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer LbvhBounds {
    tb_gpu_lbvh_bounds b;
};

LbvhUints lbvh_keys() { return LbvhUints(push.address[0].xy); }
LbvhUints lbvh_values() { return LbvhUints(push.address[0].zw); }
LbvhBounds lbvh_bounds() { return LbvhBounds(push.address[1].xy); }
LbvhNodes lbvh_nodes() { return LbvhNodes(push.address[1].zw); }
LbvhUints lbvh_links() { return LbvhUints(push.address[2].xy); }
LbvhUints lbvh_cache() { return LbvhUints(push.address[3].xy); }
uint lbvh_capacity() { return push.args.y; }

// Nothing to do: the step was abandoned, or the search runs inside another broadphase that
// searched without it this step (the uint at address[2].zw is then nonzero; 0: none).
bool lbvh_skipped()
{
    return step_aborted() || (push.address[2].zw != uvec2(0u) && LbvhUints(push.address[2].zw).v[0] != 0u);
}

vec3 body_centre(uint i)
{
    return 0.5 * (body_aabb_min[i].xyz + body_aabb_max[i].xyz);
}

float body_side(uint i)
{
    vec3 side = body_aabb_max[i].xyz - body_aabb_min[i].xyz;
    return max(side.x, max(side.y, side.z));
}

// A live body whose centre counts in the scene bounds: finite, not a plane.
bool in_scene_bounds(uint i)
{
    vec3 c = body_centre(i);
    return body_is(i, TB_BODY_FLAG_ALIVE) && body_side(i) < TB_LBVH_UNBOUNDED_SIDE &&
           all(lessThan(abs(c), vec3(1.0e37)));
}

#endif
