#version 450
#extension GL_GOOGLE_include_directive : require
// Narrowphase of mesh pairs, second pass: a body pair split by triangle keeps at most four
// points over all its triangles' manifolds (a box over a fine mesh would otherwise hold
// dozens, and every one costs the solver). The pairs of one body pair are consecutive (the
// broadphase writes them together); the thread of the first does the whole run: it picks
// four points as the narrowphase reduces a clipped polygon (hull.glsl: the deepest, the
// farthest from it in the plane of the deepest point's normal, the farthest either side of
// the line through the two), in the run's order, and takes the others out of their
// manifolds. Each point keeps its own triangle's normal and warm start.
//
// Only points the body can reach within the step take part: a gap no wider than the
// contact margin plus how far the bodies close in along that point's normal (and turn).
// A body's triangles around it give speculative points of every direction (a triangle
// beside a hull meets it along one of its side faces), and a pick for spread takes those
// far ones first; a hull landing on a fine terrain then kept points beside it instead of
// under it and sank through.
//
// The picks after the deepest take a point that held the body last step (warm: a normal
// impulse carried over) when its spread is at least NP_WARM_SHARE of the best's, and never
// a second point at the same place (the corner of two triangles gives one from each). The block solver leans on the force a point
// carries from step to step: a hull rocking on the terrain, its four points chosen afresh
// each step, started them cold and sank 7 cm into it (2.6 cm now, and back out once at
// rest; without any reduction 3 mm). Dispatched indirectly over counters.pair_dispatch.
#include "world.glsl"
#include "quat.glsl"
#include "manifold.glsl"
#include "box_box.glsl"
#include "hull.glsl"

// Whether pairs p and p + 1 belong to the same split body pair.
bool same_run(uvec4 p, uvec4 next)
{
    return next.w != 0u && next.xy == p.xy;
}

// Point `point` (pair << 2 | k) of the run.
vec4 run_point(uint point)
{
    return manifolds[point >> 2u].point[point & 3u];
}

// Keeps only the points in `kept` of manifold q; returns how many it took out.
uint keep_points(uint q, uvec4 kept)
{
    uint count = manifolds[q].info.x, left = 0u;
    for (uint k = 0u; k < count; k++) {
        if (!any(equal(kept, uvec4((q << 2u) | k)))) continue;
        if (left != k) {
            manifolds[q].point[left] = manifolds[q].point[k];
            manifolds[q].impulse[left] = manifolds[q].impulse[k];
            manifolds[q].feature[left] = manifolds[q].feature[k];
            set_manifold_slip(q, left, slip_of_point(manifolds[q].slip[k >> 1u], k));
        }
        left++;
    }
    for (uint k = left; k < count; k++) {
        manifolds[q].point[k] = vec4(0.0);
        manifolds[q].impulse[k] = vec4(0.0);
        manifolds[q].feature[k] = 0u;
        set_manifold_slip(q, k, vec2(0.0));
    }
    manifolds[q].info.x = left;
    return count - left;
}

// How the bodies of the run (pair `pair`) move within the step, found once per run: how
// far a closes in on b, and how far each one's turn may carry a point (its turn times its
// half diagonal).
struct run_motion {
    vec3 closing;
    float turn_a, turn_b;
};

run_motion run_motion_of(uvec4 pair)
{
    run_motion m;
    m.closing = body_step_motion(pair.x) - body_step_motion(pair.y);
    m.turn_a = body_step_turn(pair.x) * length(shapes[body_info[pair.x].x].aabb_half.xyz);
    m.turn_b = body_step_turn(pair.y) * length(shapes[body_info[pair.y].x].aabb_half.xyz);
    return m;
}

// How far the bodies close in along `normal` (a to b) within the step, turning included:
// a point farther apart than this and the margin stays apart.
float reach_along(run_motion m, vec3 normal)
{
    return params.contact.x + max(dot(m.closing, normal), 0.0) + m.turn_a + m.turn_b;
}

// A warm point keeps its place while its spread is at least this share of the best.
#define NP_WARM_SHARE 0.1
// Points closer than this to a kept one (m) are the same place seen from two triangles.
#define NP_SAME_PLACE 5.0e-3

// Whether x lies at a point already kept (picks before `pick`).
bool near_kept(uvec4 kept, uint pick, vec3 x)
{
    for (uint j = 0u; j < pick; j++) {
        vec3 d = run_point(kept[j]).xyz - x;
        if (dot(d, d) < NP_SAME_PLACE * NP_SAME_PLACE) return true;
    }
    return false;
}

void reduce_run(uint first, uint end)
{
    run_motion motion = run_motion_of(pairs[pair_half_base() + first]);
    uvec4 kept = uvec4(NP_NONE);
    vec3 p0 = vec3(0.0), p1 = vec3(0.0), n = vec3(0.0, 1.0, 0.0);
    for (uint pick = 0u; pick < 4u; pick++) {
        // The best candidate, and the best of those that held the body last step.
        float best = -NP_BIG, best_warm = -NP_BIG;
        uint warm = NP_NONE;
        for (uint q = first; q < end; q++) {
            uint count = manifolds[q].info.x;
            float reach = count != 0u ? reach_along(motion, manifolds[q].normal.xyz) : 0.0;
            for (uint k = 0u; k < count; k++) {
                uint point = (q << 2u) | k;
                vec4 x = manifolds[q].point[k];
                if (x.w >= reach || any(equal(kept, uvec4(point))) || near_kept(kept, pick, x.xyz))
                    continue;
                float score = np_reduce_score(pick, x.xyz, x.w, p0, p1, n);
                if (score > best) {
                    best = score;
                    kept[pick] = point;
                }
                if (manifolds[q].impulse[k].x > 0.0 && score > best_warm) {
                    best_warm = score;
                    warm = point;
                }
            }
        }
        // After the deepest, a warm point nearly as good as the best keeps its place.
        if (pick > 0u && warm != NP_NONE && best_warm >= NP_WARM_SHARE * best) kept[pick] = warm;
        if (kept[pick] == NP_NONE) break;
        if (pick == 0u) {
            p0 = run_point(kept[0]).xyz;
            n = manifolds[kept[0] >> 2u].normal.xyz;
        }
        if (pick == 1u) p1 = run_point(kept[1]).xyz;
    }
    uint removed = 0u;
    for (uint q = first; q < end; q++) removed += keep_points(q, kept);
    if (removed != 0u) atomicAdd(counters.solver.w, 0u - removed);
}

void main()
{
    if (counters.state.x != 0u) return;
    uint p = pair_thread_index(), pairs_now = counters.state.z, base = pair_half_base();
    if (p >= pairs_now) return;
    uvec4 pair = pairs[base + p];
    if (!pair_has_mesh(pair) || (p > 0u && same_run(pairs[base + p - 1u], pair))) return;
    uint end = p + 1u, total = manifolds[p].info.x;
    for (; end < pairs_now && same_run(pair, pairs[base + end]); end++) total += manifolds[end].info.x;
    if (total > uint(TB_MAX_MANIFOLD_POINTS)) reduce_run(p, end);
}
