// The pair output every broadphase shares (src/broadphase/broadphase.h): a search kernel
// runs twice with the same traversal, first counting the pairs each finder body finds
// (TB_BROADPHASE_COUNT), then, once a scan turned the counts into offsets and pair_check
// made sure they fit, writing them (TB_BROADPHASE_WRITE) as one run per finder.
//
//     bp_begin(finder);
//     ... for each candidate j: if (bp_wanted(i, j)) bp_report(i, j);
//     bp_end(finder);
//
// A pair with a mesh or compound body is reported once, as (a, b, TB_NO_COLOUR,
// TB_PAIR_UNSPLIT), and the midphase splits it after the search, one thread a pair
// (glsl/midphase/split.glsl): by triangle against a mesh, by pair of children between
// compounds, so the narrowphase and the solver see convex pairs. Mesh bodies are large to
// every broadphase, so only the plain walks over large bodies meet them.
#ifndef TB_PAIRS_GLSL
#define TB_PAIRS_GLSL

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

uint bp_base;     // where the finder's run starts (write mode)
uint bp_found;    // pairs the finder found so far

bool bp_writing()
{
    return push.args.x == TB_BROADPHASE_WRITE;
}

// AABBs overlap once each is grown by half the contact margin.
bool aabbs_touch(uint a, uint b)
{
    float m = params.contact.x;
    return !any(greaterThan(body_aabb_min[a].xyz - m, body_aabb_max[b].xyz)) &&
           !any(greaterThan(body_aabb_min[b].xyz - m, body_aabb_max[a].xyz));
}

// A pair the step wants: not static against static, boxes touching. Dead slots have empty
// boxes, which touch nothing.
bool bp_wanted(uint a, uint b)
{
    return (body_is(a, TB_BODY_FLAG_DYNAMIC) || body_is(b, TB_BODY_FLAG_DYNAMIC)) &&
           aabbs_touch(a, b);
}

void bp_begin(uint finder)
{
    bp_found = 0u;
    bp_base = bp_writing() ? body_pair_count[finder] : 0u;
}

void bp_put(uint a, uint b, uint sub)
{
    if (bp_writing())
        pairs[pair_half_base() + bp_base + bp_found] = uvec4(a, b, TB_NO_COLOUR, sub);
    bp_found++;
}

// Report the pair (a, b), in the order the output keeps for it, unless a joint holds the
// two together that keeps them from colliding (every broadphase's pairs pass here, in the
// count and the write alike).
void bp_report(uint a, uint b)
{
    if (joint_keeps_apart(a, b)) return;
    uint parts = TB_BODY_FLAG_MESH | TB_BODY_FLAG_COMPOUND;
    bool split = ((body_info[a].y | body_info[b].y) & parts) != 0u;
    bp_put(a, b, split ? TB_PAIR_UNSPLIT : 0u);
}

// Every body slot must end here once per pass, found pairs or not.
void bp_end(uint finder)
{
    if (!bp_writing()) {
        body_pair_count[finder] = bp_found;
    } else if (current_half() == 0u) {
        body_pairs[finder].xy = uvec2(bp_base, bp_found);
    } else {
        body_pairs[finder].zw = uvec2(bp_base, bp_found);
    }
}

#endif
