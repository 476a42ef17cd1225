// Counting and grouping the round pairs by kind (round_cull counts them, round_order groups
// them): a subgroup's lanes of one kind are ranked by a ballot and only the first of them
// adds to the workgroup's shared count, so a workgroup's lanes do not queue on a few shared
// counters. Call every function from uniform control flow.
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require

shared uint np_kind_count[TB_ROUND_KINDS];   // the workgroup's pairs of each kind

// Of this subgroup's lanes of this lane's kind: x this lane's rank, y the lowest lane, z how
// many they are. A round per kind present in the subgroup (the lowest lane not yet ranked
// names it), not per kind there is.
uvec3 np_kind_peers(uint kind)
{
    uvec3 mine = uvec3(0u);
    bool ranked = false;
    for (uint round = 0u; round < 128u; round++) {
        uvec4 left = subgroupBallot(!ranked);
        if (subgroupBallotBitCount(left) == 0u) break;
        uint named = subgroupShuffle(kind, subgroupBallotFindLSB(left));
        uvec4 same = subgroupBallot(kind == named);
        if (kind == named) {
            mine = uvec3(subgroupBallotExclusiveBitCount(same), subgroupBallotFindLSB(same),
                         subgroupBallotBitCount(same));
            ranked = true;
        }
    }
    return mine;
}

void np_kind_clear()
{
    for (uint k = gl_LocalInvocationID.x; k < TB_ROUND_KINDS; k += gl_WorkGroupSize.x)
        np_kind_count[k] = 0u;
    barrier();
}

// Counts this lane's pair of `kind` (TB_ROUND_KINDS for none) in the workgroup's count (after
// np_kind_clear); returns its rank among the workgroup's pairs of that kind.
uint np_kind_add(uint kind)
{
    uvec3 peers = np_kind_peers(kind);
    uint first = 0u;
    if (kind < TB_ROUND_KINDS && peers.x == 0u) first = atomicAdd(np_kind_count[kind], peers.z);
    return subgroupShuffle(first, peers.y) + peers.x;
}
