#version 450
#extension GL_GOOGLE_include_directive : require
// Keys and values back from the sort's temporary arrays after an odd number of passes,
// block by block as the passes went.
#include "radix.glsl"

void main()
{
    uint block = flat_group_index();
    if (block >= plan_word(PLAN_BLOCKS)) return;
    uint n = read_count(p.count.xy, p.count.z);
    uint per_block = plan_word(PLAN_TILES_PER_BLOCK) * TB_PRIMS_SORT_TILE;
    uint end = min(n, (block + 1u) * per_block);
    Uints keys_in = Uints(p.keys.xy), keys_out = Uints(p.keys.zw);
    Uints values_in = Uints(p.values.xy), values_out = Uints(p.values.zw);
    for (uint i = block * per_block + gl_LocalInvocationIndex; i < end; i += WORKGROUP_SIZE) {
        keys_out.v[i] = keys_in.v[i];
        values_out.v[i] = values_in.v[i];
    }
}
