// Convex shapes as support functions, for GJK and EPA (gjk.glsl, epa.glsl) and the
// manifolds of round shapes (round.glsl).
//
// Every convex shape is a core swept by a ball: the points within `radius` of the core. A
// sphere's core is its centre and a capsule's its segment; every other shape is its own core
// with radius 0. GJK measures the cores, so a sphere or capsule touching something is a
// separated pair of cores (no penetration query), and the shapes' distance is the cores'
// distance less both radii.
//
// Capsules, cylinders and cones lie along the body's y axis (params: x radius, y half
// height h; a cone's base circle at y = -h/2 and apex at 3h/2, the body origin at its centre
// of mass). A mesh triangle joins as a shape of its own (NP_SHAPE_TRIANGLE) whose three
// corners are given in world space.
#ifndef TB_NP_CONVEX_GLSL
#define TB_NP_CONVEX_GLSL

#define NP_SHAPE_TRIANGLE 100u

struct np_convex {
    np_body body;       // pose and shape (body.type NP_SHAPE_TRIANGLE for a triangle)
    vec3 v0, v1, v2;    // a triangle's corners, world space
    float radius;       // the ball swept over the core
};

np_convex np_convex_of(np_body b)
{
    np_convex c;
    c.body = b;
    c.v0 = c.v1 = c.v2 = vec3(0.0);
    bool balled = b.type == TB_GPU_SHAPE_SPHERE || b.type == TB_GPU_SHAPE_CAPSULE;
    c.radius = balled ? b.params.x : 0.0;
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
    float up = d.y >= 0.0 ? 1.0 : -1.0;
    if (type == TB_GPU_SHAPE_CAPSULE) return vec3(0.0, up * p.y, 0.0);
    if (type == TB_GPU_SHAPE_CYLINDER) {
        vec2 rim = np_rim(d.xz, p.x);
        return vec3(rim.x, up * p.y, rim.y);
    }
    if (type == TB_GPU_SHAPE_CONE) {
        vec3 apex = vec3(0.0, 1.5 * p.y, 0.0);
        vec2 rim = np_rim(d.xz, p.x);
        vec3 base = vec3(rim.x, -0.5 * p.y, rim.y);
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
