// The body of each invocation in a pass over the bodies of one colour (block/solve,
// block/bounce). Needs GL_KHR_shader_subgroup_basic, which the including shader enables.
#ifndef TB_BLOCK_LISTED_GLSL
#define TB_BLOCK_LISTED_GLSL

#include "block.glsl"

// This invocation's body in a pass over the bodies of colour c (BLOCK_LANES neighbouring
// invocations a body, finish.comp sizes the dispatch): its entry of block_list (body, first
// entry, entry count; zero beyond the colour's bodies), its lane, and whether it has one.
bool block_listed(uint c, out uvec4 listed, out uint lane)
{
    uint thread = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x
                + gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    uint slot = thread / BLOCK_LANES;
    lane = gl_SubgroupInvocationID % BLOCK_LANES;
    bool valid = slot < counters.colour[c].x;
    listed = valid ? block_list[counters.colour[c].y + slot] : uvec4(0u);
    return valid;
}

#endif
