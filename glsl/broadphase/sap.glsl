// The 1-axis sort and sweep (src/broadphase/sap.c): every body's AABB is sorted by its
// minimum along the axis where the centres spread most, and each body sweeps forward
// through the sorted boxes while their minima can still reach its maximum. A pair is found
// by whichever of its two bodies comes first in that order, so once.
//
// Static bodies much larger than any dynamic one ("large": planes, ground boxes) stay out
// of the sort, since one of them would sweep over everything; every dynamic body tests
// their list instead, as the grid does.
#ifndef TB_SAP_GLSL
#define TB_SAP_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "pairs.glsl"
#include "ordered.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) buffer SapUints { uint v[]; };
// Sorted boxes are kept as uints: xyz a corner's float bits, w integer (slot or flags),
// which as float bits would be denormals that a flushing move could zero.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer SapBoxes { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer SapPartials {
    tb_gpu_sap_partial v[];
};
// Align 4: kernels write its members one by one.
layout(buffer_reference, std430, buffer_reference_align = 4) buffer SapHeader {
    tb_gpu_sap_header h;
};

// Device address number `index` (TB_SAP_*) of the push constants.
uvec2 sap_address(uint index)
{
    uvec4 pair = push.address[index >> 1];
    return (index & 1u) == 0u ? pair.xy : pair.zw;
}

SapUints sap_uints(uint index) { return SapUints(sap_address(index)); }
SapBoxes sap_boxes(uint index) { return SapBoxes(sap_address(index)); }
SapHeader sap_header() { return SapHeader(sap_address(TB_SAP_HEADER)); }

// The sweep axis of this step (0, 1, 2).
uint sap_axis()
{
    return min(sap_header().h.state.x, 2u);
}

// A static body much larger than every dynamic one (see TB_SAP_LARGE_FACTOR).
bool sap_is_large(uint body)
{
    if (body_is(body, TB_BODY_FLAG_DYNAMIC)) return false;
    if (body_is(body, TB_BODY_FLAG_MESH)) return true;   // its pairs are split by triangle
    vec3 side = body_aabb_max[body].xyz - body_aabb_min[body].xyz;
    float largest_dynamic = max(uintBitsToFloat(counters.grid.x), params.contact.x);
    return max(side.x, max(side.y, side.z)) > float(TB_SAP_LARGE_FACTOR) * largest_dynamic;
}

// The corner of a sorted box.
vec3 sap_corner(uvec4 box)
{
    return uintBitsToFloat(box.xyz);
}

// The same test as aabbs_touch (pairs.glsl), on sorted boxes: the sweep's stopping rule
// uses its very expression on the axis, so the two never disagree by a rounding.
bool sap_boxes_touch(uvec4 min_a, uvec4 max_a, uvec4 min_b, uvec4 max_b)
{
    float m = params.contact.x;
    return !any(greaterThan(sap_corner(min_a) - m, sap_corner(max_b))) &&
           !any(greaterThan(sap_corner(min_b) - m, sap_corner(max_a)));
}

#endif
