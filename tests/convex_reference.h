/* The host's reference for convex shapes in double precision, shared by test_distance and
 * bench-distance: the cores' support functions (as glsl/narrowphase/convex.glsl describes
 * the cores), the shapes' separation along an axis, and their least overlap over all axes
 * (the penetration depth) by a local search. Static definitions: one program includes it
 * once. */
#ifndef TB_CONVEX_REFERENCE_H
#define TB_CONVEX_REFERENCE_H

#include <math.h>
#include <string.h>

#include "tumble.h"

typedef struct ref_shape {
    tb_shape_type type;
    double radius, half;         /* round: radius and half height; sphere: radius */
    double box[3];               /* box half extents */
    double (*points)[3];         /* hull vertices, body frame */
    uint32_t point_count;
    double size;                 /* a length of the shape's scale */
    tb_shape_id id;
} ref_shape;

typedef struct posed {
    const ref_shape* s;
    double p[3], r[9];           /* r: rotation matrix, columns the body axes */
} posed;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void rot_from_quat(tb_quat q, double r[9])
{
    double x = q.x, y = q.y, z = q.z, w = q.w;
    double n = sqrt(x * x + y * y + z * z + w * w);
    x /= n, y /= n, z /= n, w /= n;
    r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y + z * w), r[2] = 2 * (x * z - y * w);
    r[3] = 2 * (x * y - z * w), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z + x * w);
    r[6] = 2 * (x * z + y * w), r[7] = 2 * (y * z - x * w), r[8] = 1 - 2 * (x * x + y * y);
}

/* The core's farthest point along world d (the radius of spheres and capsules left out). */
static void core_support(const posed* b, const double d[3], double out[3])
{
    double l[3], c[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; i++) l[i] = dot3(&b->r[3 * i], d);
    const ref_shape* s = b->s;
    double up = l[1] >= 0 ? 1 : -1, rho = sqrt(l[0] * l[0] + l[2] * l[2]);
    double rim[2] = { rho > 1e-300 ? l[0] / rho : 1, rho > 1e-300 ? l[2] / rho : 0 };
    if (s->type == TB_SHAPE_CAPSULE) {
        c[1] = up * s->half;
    } else if (s->type == TB_SHAPE_CYLINDER) {
        c[0] = s->radius * rim[0], c[1] = up * s->half, c[2] = s->radius * rim[1];
    } else if (s->type == TB_SHAPE_CONE) {
        double apex = 1.5 * s->half * l[1];
        double base = s->radius * rho - 0.5 * s->half * l[1];
        if (apex >= base) c[1] = 1.5 * s->half;
        else c[0] = s->radius * rim[0], c[1] = -0.5 * s->half, c[2] = s->radius * rim[1];
    } else if (s->type == TB_SHAPE_BOX) {
        for (int i = 0; i < 3; i++) c[i] = l[i] >= 0 ? s->box[i] : -s->box[i];
    } else if (s->type == TB_SHAPE_HULL) {
        uint32_t best = 0;
        for (uint32_t k = 1; k < s->point_count; k++)
            if (dot3(s->points[k], l) > dot3(s->points[best], l)) best = k;
        memcpy(c, s->points[best], sizeof c);
    }
    for (int i = 0; i < 3; i++)
        out[i] = b->p[i] + b->r[i] * c[0] + b->r[3 + i] * c[1] + b->r[6 + i] * c[2];
}

static double core_radius(const ref_shape* s)
{
    return s->type == TB_SHAPE_SPHERE || s->type == TB_SHAPE_CAPSULE ? s->radius : 0;
}

/* How far apart the two shapes are along the unit axis n (negative: how far they overlap
 * along it), from their support functions in double: no axis shows them farther apart than
 * they are, and no axis overlaps them less than their penetration depth, so for the GPU's
 * normal this bounds its answer from the other side. */
static double apart_along(const posed* a, const posed* b, const double n[3])
{
    double m[3] = { -n[0], -n[1], -n[2] }, sa[3], sb[3];
    core_support(a, n, sa);
    core_support(b, m, sb);
    return dot3(n, sb) - dot3(n, sa) - core_radius(a->s) - core_radius(b->s);
}

/* The penetration depth of two overlapping shapes is their least overlap over all unit
 * axes. From the start axis n, a local search on the sphere of directions in double: a step
 * along each of eight tangent directions (turned by a fresh angle every round, so that a
 * ridge of the overlap between two of them does not hold the search), the best kept, the
 * step halved when none improves, until it is under 1e-9 rad. Returns the overlap and leaves
 * its axis in n. */
static double least_overlap(const posed* a, const posed* b, double n[3])
{
    double best = -apart_along(a, b, n), step = 0.1, turn = 0;
    for (int rounds = 0; step > 1e-9 && rounds < 4000; rounds++) {
        double e[3] = { 0, 0, 0 }, u[3], v[3], pick[3];
        e[fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2)
                                  : (fabs(n[1]) < fabs(n[2]) ? 1 : 2)] = 1;
        u[0] = n[1] * e[2] - n[2] * e[1], u[1] = n[2] * e[0] - n[0] * e[2];
        u[2] = n[0] * e[1] - n[1] * e[0];
        double lu = sqrt(dot3(u, u));
        for (int i = 0; i < 3; i++) u[i] /= lu;
        v[0] = n[1] * u[2] - n[2] * u[1], v[1] = n[2] * u[0] - n[0] * u[2];
        v[2] = n[0] * u[1] - n[1] * u[0];
        turn += 2.399963;   /* the golden angle: every round's star differs */
        int moved = 0;
        for (int k = 0; k < 8; k++) {
            double c = step * cos(turn + k * 0.785398163), d = step * sin(turn + k * 0.785398163);
            double m[3] = { n[0] + c * u[0] + d * v[0], n[1] + c * u[1] + d * v[1],
                            n[2] + c * u[2] + d * v[2] };
            double lm = sqrt(dot3(m, m));
            for (int i = 0; i < 3; i++) m[i] /= lm;
            double o = -apart_along(a, b, m);
            if (o < best) best = o, memcpy(pick, m, sizeof pick), moved = 1;
        }
        if (moved) memcpy(n, pick, sizeof pick);
        else step *= 0.5;
    }
    return best;
}

static posed posed_of(const ref_shape* s, tb_vec3 p, tb_quat q)
{
    posed b = { s, { p.x, p.y, p.z }, { 0 } };
    rot_from_quat(q, b.r);
    return b;
}

#endif
