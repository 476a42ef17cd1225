// The pair output every broadphase shares (src/broadphase/broadphase.h): a search kernel
// runs twice with the same traversal, first counting the pairs each finder body finds
// (TB_BROADPHASE_COUNT), then, once a scan turned the counts into offsets and pair_check
// made sure they fit, writing them (TB_BROADPHASE_WRITE) as one run per finder.
//
//     bp_begin(finder);
//     ... for each candidate j: if (bp_wanted(i, j)) bp_report(i, j);
//     bp_end(finder);
//
// A pair with a mesh body is reported once per triangle whose BVH leaf box its partner's box
// (grown by the contact margin) touches, as (a, b, TB_NO_COLOUR, triangle + 1): the midphase
// of meshes, done where the pair is found so the narrowphase and the solver see one convex
// pair per triangle and the four broadphases share it. Mesh bodies are large to every
// broadphase, so only the plain walks over large bodies meet them; against a compound,
// once per child and triangle. A pair of a compound and a body other than a mesh is
// reported once, as (a, b, TB_NO_COLOUR, TB_PAIR_UNSPLIT), and split by pairs of children
// after the search, one thread a pair (glsl/midphase/split.glsl); layout.h,
// TB_PAIR_TRIANGLE_BITS, says how pairs[].w holds children and triangles.
#ifndef TB_PAIRS_GLSL
#define TB_PAIRS_GLSL

#include "../midphase/mesh.glsl"
#include "../midphase/compound.glsl"

layout(push_constant) uniform Push { tb_gpu_broadphase_push push; };

uint bp_base;     // where the finder's run starts (write mode)
uint bp_found;    // pairs the finder found so far
bool bp_measuring = false;   // count only, even in write mode (bp_report_count)

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
    if (bp_writing() && !bp_measuring)
        pairs[pair_half_base() + bp_base + bp_found] = uvec4(a, b, TB_NO_COLOUR, sub);
    bp_found++;
}

// A heightfield's triangles under the box [lo, hi] (its frame): both of every cell in
// the box's range of rows and columns whose corners reach the box's height range. `part`
// (the other body's child, shifted into place) joins each triangle + 1.
void bp_report_cells(uint a, uint b, uint shape, vec3 lo, vec3 hi, uint part)
{
    field_view field = field_of_shape(shape);
    uvec4 range = field_cells(field, lo, hi);
    for (uint k = range.y; k < range.w; k++) {
        for (uint i = range.x; i < range.z; i++) {
            float h0 = field_height(field, i, k), h1 = field_height(field, i + 1u, k);
            float h2 = field_height(field, i, k + 1u), h3 = field_height(field, i + 1u, k + 1u);
            if (min(min(h0, h1), min(h2, h3)) > hi.y || max(max(h0, h1), max(h2, h3)) < lo.y)
                continue;
            uint n = k * (field.count.x - 1u) + i;
            if ((field_flags(field, 2u * n) & TB_MESH_DEGENERATE) != 0u) continue;   // a hole
            bp_put(a, b, (2u * n + 1u) | part);
            bp_put(a, b, (2u * n + 2u) | part);
        }
    }
}

// A mesh's triangles whose BVH leaf boxes touch the box [lo, hi] (its frame).
void bp_report_leaves(uint a, uint b, uint shape, vec3 lo, vec3 hi, uint part)
{
    mesh_view mesh = mesh_of_shape(shape);
    uvec3 qlo, qhi;
    if (!mesh_query(mesh, lo, hi, qlo, qhi)) return;
    for (uint i = 0u; i < mesh.nodes;) {
        uvec4 node = mesh.image.v[mesh.sections.x + i];
        bool hit = bvh_node_overlaps(node, qlo, qhi);
        if (hit && bvh_is_leaf(node)) bp_put(a, b, ((node.w & ~TB_BVH_LEAF) + 1u) | part);
        i = bvh_next(i, node, hit);
    }
}

// The pairs of (a, b), one of them a mesh or heightfield body: one per triangle near the
// other's box, or near each of its children's boxes when it is a compound.
void bp_report_triangles(uint a, uint b)
{
    uint m = body_is(a, TB_BODY_FLAG_MESH) ? a : b, other = m == a ? b : a;
    uint shape = body_info[m].x;
    bool field = shapes[shape].info.x == TB_GPU_SHAPE_HEIGHTFIELD;
    part_frame f = part_frame_of(other);
    for (uint c = 0u; c < f.parts; c++) {
        vec3 lo, hi;
        frame_part_box(f, c, params.contact.x, lo, hi);
        mesh_local_box(body_pos[m].xyz, body_rot[m], lo, hi, lo, hi);
        uint part = c << TB_PAIR_TRIANGLE_BITS;
        if (field) bp_report_cells(a, b, shape, lo, hi, part);
        else bp_report_leaves(a, b, shape, lo, hi, part);
    }
}

// Report the pair (a, b), in the order the output keeps for it.
void bp_report(uint a, uint b)
{
    if (body_is(a, TB_BODY_FLAG_MESH) || body_is(b, TB_BODY_FLAG_MESH)) bp_report_triangles(a, b);
    else if (body_is(a, TB_BODY_FLAG_COMPOUND) || body_is(b, TB_BODY_FLAG_COMPOUND)) bp_put(a, b, TB_PAIR_UNSPLIT);
    else bp_put(a, b, 0u);
}

// For a kernel that writes pairs for another invocation's finder: how many pairs (a, b)
// gives, and those pairs written from `at` in the pair array's half. This invocation's own
// run (bp_base, bp_found) is left as it was.
uint bp_report_count(uint a, uint b)
{
    uint base = bp_base, found = bp_found;
    bp_found = 0u;
    bp_measuring = true;
    bp_report(a, b);
    uint count = bp_found;
    bp_measuring = false;
    bp_base = base;
    bp_found = found;
    return count;
}

void bp_report_at(uint a, uint b, uint at)
{
    uint base = bp_base, found = bp_found;
    bp_base = at;
    bp_found = 0u;
    bp_report(a, b);
    bp_base = base;
    bp_found = found;
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
