// Convex shapes as support functions, for GJK and EPA (gjk.glsl, epa.glsl) and the
// manifolds of round shapes (round.glsl).
//
// Every convex shape is a core swept by a ball: the points within `radius` of the core. A
// sphere's core is its centre and a capsule's its segment; every other shape is its own core
// with radius 0. GJK measures the cores, so a sphere or capsule touching something is a
// separated pair of cores (no penetration query), and the shapes' distance is the cores'
// distance less both radii.
//
// Contacts (np_convex_rounded) give cylinders and cones a core too: the shape shrunk by a
// skin (NP_SKIN, at most a tenth of its radius and height) swept by a ball of the skin's
// radius. Its caps, base and sides stay where they are, its rims and a cone's apex are
// rounded by the skin. Resting contacts then sink into the skin only, so GJK alone finds
// them and EPA runs only for overlaps deeper than the skin. Distance queries measure the
// exact shapes (np_convex_of).
//
// Capsules, cylinders and cones lie along the body's y axis (params: x radius, y half
// height h; a cone's base circle at y = -h/2 and apex at 3h/2, the body origin at its centre
// of mass). A mesh triangle joins as a shape of its own (NP_SHAPE_TRIANGLE) whose three
// corners are given in world space.
#ifndef TB_NP_CONVEX_GLSL
#define TB_NP_CONVEX_GLSL

#extension GL_EXT_control_flow_attributes : require

#define NP_SHAPE_TRIANGLE 100u

#define NP_SKIN 0.04         // m: the most skin a cylinder or cone gets for contacts

struct np_convex {
    np_body body;       // pose and shape (body.type NP_SHAPE_TRIANGLE for a triangle)
    vec3 v0, v1, v2;    // a triangle's corners, world space
    vec3 core;          // capsule, cylinder, cone: x the core's rim radius, y its bottom and
                        // z its top along the body's y axis (a cone's apex)
    float radius;       // the ball swept over the core
};

// The exact shape: spheres and capsules balls about their points and segments.
np_convex np_convex_of(np_body b)
{
    np_convex c;
    c.body = b;
    c.v0 = c.v1 = c.v2 = vec3(0.0);
    float r = b.params.x, h = b.params.y;
    c.core = b.type == TB_GPU_SHAPE_CONE ? vec3(r, -0.5 * h, 1.5 * h) : vec3(r, -h, h);
    if (b.type == TB_GPU_SHAPE_CAPSULE) c.core.x = 0.0;
    bool balled = b.type == TB_GPU_SHAPE_SPHERE || b.type == TB_GPU_SHAPE_CAPSULE;
    c.radius = balled ? r : 0.0;
    return c;
}

// The shape for contacts: a cylinder or cone as its core shrunk by the skin s, swept by a
// ball of radius s. A cone's core is the cone whose sides lie s inside the shape's: its base
// s higher, its apex s / sin(half angle) lower, its rim radius in the same proportion.
np_convex np_convex_rounded(np_body b)
{
    np_convex c = np_convex_of(b);
    float r = b.params.x, h = b.params.y;
    if (b.type == TB_GPU_SHAPE_CYLINDER) {
        float s = min(NP_SKIN, 0.1 * min(r, h));
        c.core = vec3(r - s, s - h, h - s);
        c.radius = s;
    } else if (b.type == TB_GPU_SHAPE_CONE) {
        float height = 2.0 * h, slant = length(vec2(r, height));
        float s = min(NP_SKIN, 0.1 * min(r, height));
        float inner = height - s - s * slant / r;    // sin(half angle) = r / slant
        if (inner > 0.1 * height) {
            c.core = vec3(r * inner / height, s - 0.5 * h, s - 0.5 * h + inner);
            c.radius = s;
        }
    }
    return c;
}

// The direction of xz within the xz plane scaled to length r, or (r, 0) when xz is (nearly)
// zero: a rim point of a disc about the y axis.
vec2 np_rim(vec2 xz, float r)
{
    float len = length(xz);
    return len > 1.0e-6 ? xz * (r / len) : vec2(r, 0.0);
}

// The core's farthest point along d, in the body frame (d in the body frame too).
vec3 np_core_support_local(np_convex c, vec3 d)
{
    uint type = c.body.type;
    vec4 p = c.body.params;
    vec3 core = c.core;
    if (type == TB_GPU_SHAPE_CAPSULE) return vec3(0.0, d.y >= 0.0 ? core.z : core.y, 0.0);
    if (type == TB_GPU_SHAPE_CYLINDER) {
        vec2 rim = np_rim(d.xz, core.x);
        return vec3(rim.x, d.y >= 0.0 ? core.z : core.y, rim.y);
    }
    if (type == TB_GPU_SHAPE_CONE) {
        vec3 apex = vec3(0.0, core.z, 0.0);
        vec2 rim = np_rim(d.xz, core.x);
        vec3 base = vec3(rim.x, core.y, rim.y);
        return dot(d, apex) >= dot(d, base) ? apex : base;
    }
    if (type == TB_GPU_SHAPE_BOX) return np_signs(d) * p.xyz;
    if (type == TB_GPU_SHAPE_HULL) {
        np_hull h = np_hull_of(c.body);
        return np_hull_vertex(h, np_hull_support(h, d, 0u));
    }
    return vec3(0.0);   // sphere
}

// The core's farthest point along d, world space.
vec3 np_core_support(np_convex c, vec3 d)
{
    if (c.body.type == NP_SHAPE_TRIANGLE) {
        float s0 = dot(d, c.v0), s1 = dot(d, c.v1), s2 = dot(d, c.v2);
        return s0 >= s1 && s0 >= s2 ? c.v0 : (s1 >= s2 ? c.v1 : c.v2);
    }
    return c.body.pos + c.body.rot * np_core_support_local(c, transpose(c.body.rot) * d);
}

// A's farthest core point along d and B's along -d: a - b is the Minkowski difference's
// support along d. On a CPU device one np_core_support in a loop rather than two calls: the
// support is large (every shape kind), kernels call it in many places, and each call is a
// copy of it, whose compile time on lavapipe grows faster than the kernel's size (round_points
// took minutes). On a GPU the loop's choice between the two shapes costs 14 % of
// round_points (H100), so there the two calls stay.
void np_core_supports(np_convex A, np_convex B, vec3 d, out vec3 a, out vec3 b)
{
    a = b = vec3(0.0);
    if (CPU_DEVICE == 0u) {
        a = np_core_support(A, d);
        b = np_core_support(B, -d);
        return;
    }
    [[dont_unroll]] for (uint s = 0u; s < 2u; s++) {
        vec3 p = np_core_support(s == 0u ? A : B, s == 0u ? d : -d);
        if (s == 0u) a = p;
        else b = p;
    }
}

// The same shape moved by -o: GJK and EPA work about a point of the pair (the first shape's
// centre), so float keeps its digits for the pair's size rather than its place in the world.
np_convex np_convex_moved(np_convex c, vec3 o)
{
    c.body.pos -= o;
    c.v0 -= o;
    c.v1 -= o;
    c.v2 -= o;
    return c;
}

// A point deep inside the core: where GJK starts.
vec3 np_core_centre(np_convex c)
{
    if (c.body.type == NP_SHAPE_TRIANGLE) return (c.v0 + c.v1 + c.v2) / 3.0;
    return c.body.pos;
}

#endif
