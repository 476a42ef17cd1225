// Floats as uints that order like them: positive ones with the sign bit set, negative ones
// with every bit flipped (below the positive ones). A finite float never gives 0, so 0 can
// mean "none" (atomicMax bounds), and the keys sort in float order (radix sorts).
#ifndef TB_ORDERED_GLSL
#define TB_ORDERED_GLSL

uint ordered_bits(float f)
{
    uint b = floatBitsToUint(f);
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}

uvec3 ordered_bits(vec3 f)
{
    uvec3 b = floatBitsToUint(f);
    return mix(b | 0x80000000u, ~b, notEqual(b & 0x80000000u, uvec3(0u)));
}

vec3 from_ordered_bits(uvec3 u)
{
    return uintBitsToFloat(mix(~u, u & 0x7fffffffu, notEqual(u & 0x80000000u, uvec3(0u))));
}

#endif
