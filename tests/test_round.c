/* Capsules, cylinders and cones (GPU, lavapipe): their sizes, mass and inertia and the
 * refusal of bad ones; resting on a plane, a box, a hull and a mesh on their sides and ends
 * without drift, with the contact points a stable rest needs (a cylinder on its cap four, on
 * its side two); a cylinder rolling down an incline at (2/3) g sin(angle); pairs among
 * themselves and with spheres; a sphere or capsule against a capsule in closed form;
 * compounds with round children; the other shapes' contacts the same with round shapes in
 * the world as without; contacts measured again (contact reuse) as the narrowphase finds
 * them, and reuse's bounds refused when bad. */
#include "harness.h"

#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0f / 60.0f)

static tb_shape_id make_round(tb_world* w, tb_shape_type type, float radius, float half_height)
{
    tb_shape_def def = tb_default_shape_def();
    tb_shape_id s;
    if (type == TB_SHAPE_CAPSULE) th_assert_ok(tb_shape_create_capsule(w, &def, radius, half_height, &s));
    else if (type == TB_SHAPE_CYLINDER) th_assert_ok(tb_shape_create_cylinder(w, &def, radius, half_height, &s));
    else th_assert_ok(tb_shape_create_cone(w, &def, radius, half_height, &s));
    return s;
}

static void step(tb_world* w, int steps)
{
    for (int i = 0; i < steps; i++) th_assert_ok(tb_world_step(w, DT));
}

static double dist3(tb_vec3 a, tb_vec3 b)
{
    double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Contact points of the last step touching body b. */
static uint32_t points_of(tb_world* w, tb_body_id b, double* deepest)
{
    tb_contact contacts[64];
    uint32_t count = 0, n = 0;
    th_assert_ok(tb_world_read_contacts(w, contacts, 64, &count));
    *deepest = 0;
    for (uint32_t i = 0; i < count && i < 64; i++) {
        if (contacts[i].a.index1 != b.index1 && contacts[i].b.index1 != b.index1) continue;
        if (contacts[i].separation < *deepest) *deepest = contacts[i].separation;
        if (contacts[i].normal_impulse > 0) n++;
    }
    return n;
}

enum ground { ON_PLANE, ON_BOX, ON_HULL, ON_MESH };

static tb_body_id make_ground(tb_world* w, enum ground g)
{
    tb_shape_def def = tb_default_shape_def();
    tb_shape_id s;
    tb_vec3 at = th_v3(0, 0, 0);
    if (g == ON_PLANE) {
        s = th_plane(w, th_v3(0, 1, 0), 0);
    } else if (g == ON_BOX) {
        s = th_box(w, th_v3(3, 0.5f, 3));
        at = th_v3(0.3f, -0.5f, -0.2f);
    } else if (g == ON_HULL) {
        tb_vec3 p[8];
        for (int i = 0; i < 8; i++)
            p[i] = th_v3(i & 1 ? 3.0f : -2.5f, i & 2 ? 0.0f : -0.7f, i & 4 ? 2.8f : -3.1f);
        th_assert_ok(tb_shape_create_hull(w, &def, p, 8, &s));
        tb_hull_info info;
        th_assert_ok(tb_shape_get_hull_info(w, s, &info));
        at = th_v3(info.center_of_mass.x, info.center_of_mass.y, info.center_of_mass.z);
        tb_body_def b = th_static_def(s, at);
        b.rotation = (tb_quat){ info.principal_axes.x, info.principal_axes.y,
                                info.principal_axes.z, info.principal_axes.w };
        return th_body(w, &b);
    } else {
        tb_vec3 v[9];
        uint32_t idx[24], k = 0;
        for (int z = 0; z < 3; z++)
            for (int x = 0; x < 3; x++) v[z * 3 + x] = th_v3(3.0f * (x - 1), 0, 3.0f * (z - 1));
        for (int z = 0; z < 2; z++) {
            for (int x = 0; x < 2; x++) {
                uint32_t a = z * 3 + x, b = a + 1, c = a + 3, d = a + 4;
                idx[k++] = a; idx[k++] = c; idx[k++] = b;
                idx[k++] = b; idx[k++] = c; idx[k++] = d;
            }
        }
        th_assert_ok(tb_shape_create_mesh(w, &def, v, 9, idx, 8, &s));
    }
    tb_body_def b = th_static_def(s, at);
    return th_body(w, &b);
}

typedef struct rest_case {
    tb_shape_type type;
    tb_quat rotation;
    float height;             ///< of the body origin above the ground when resting
    uint32_t points;          ///< contact points a stable rest needs
} rest_case;

/* Shapes placed resting on the ground (radius 0.3, half height 0.5; several on a plane, 8 m
 * apart, in one world), 600 steps: each pose drifts less than 1 mm and turns less than 0.1
 * degree, with the expected points. */
static void rests(enum ground g, const rest_case* cases, int count)
{
    tb_world* w = th_world_create(NULL);
    make_ground(w, g);
    tb_body_id bodies[8];
    tb_body_def defs[8];
    for (int i = 0; i < count; i++) {
        tb_shape_id s = make_round(w, cases[i].type, 0.3f, 0.5f);
        defs[i] = th_dynamic_def(s, th_v3(0.1f + 8.0f * i, cases[i].height, 0.2f));
        defs[i].rotation = cases[i].rotation;
        bodies[i] = th_body(w, &defs[i]);
    }
    step(w, 600);
    for (int i = 0; i < count; i++) {
        tb_vec3 p;
        tb_quat q, r = cases[i].rotation;
        th_read_pose(w, bodies[i], &p, &q);
        double deepest, drift = dist3(p, defs[i].position);
        uint32_t n = points_of(w, bodies[i], &deepest);
        double turn = 2 * acos(fmin(1.0, fabs(q.x * r.x + q.y * r.y + q.z * r.z + q.w * r.w)));
        printf("ground %d type %d: drift %.3f mm, turn %.4f deg, %u points, deepest %.3f mm\n",
               (int)g, (int)cases[i].type, 1e3 * drift, turn * 180 / M_PI, n, 1e3 * deepest);
        assert_true(drift < 1e-3);
        assert_true(turn < 0.1 * M_PI / 180);
        /* On a mesh a body across a seam gets points from each triangle (four at most). */
        if (g == ON_MESH) assert_true(n >= cases[i].points && n <= 4);
        else assert_int_equal(n, cases[i].points);
    }
    th_world_destroy(w);
}

static const rest_case CAPSULE_UP = { TB_SHAPE_CAPSULE, { 0, 0, 0, 1 }, 0.8f, 1 };
static const rest_case CAPSULE_SIDE = { TB_SHAPE_CAPSULE, { 0, 0, 0.70710678f, 0.70710678f }, 0.3f, 2 };
static const rest_case CYLINDER_UP = { TB_SHAPE_CYLINDER, { 0, 0, 0, 1 }, 0.5f, 4 };
static const rest_case CYLINDER_SIDE = { TB_SHAPE_CYLINDER, { 0, 0, 0.70710678f, 0.70710678f }, 0.3f, 2 };
static const rest_case CONE_BASE = { TB_SHAPE_CONE, { 0, 0, 0, 1 }, 0.25f, 4 };

static void test_rest_on_plane(void** state)
{
    (void)state;
    const rest_case cases[] = { CAPSULE_UP, CAPSULE_SIDE, CYLINDER_UP, CYLINDER_SIDE, CONE_BASE };
    rests(ON_PLANE, cases, 5);
}

/* A capsule on its end stands on a plane (symmetry keeps it there), but its end is a half
 * ball whose centre lies below the centre of mass: off a plane that equilibrium is
 * unstable, and so it is not asked for. */
static void test_rest_on_box(void** state)
{
    (void)state;
    if (!th_large_scene_runs("rest_on_box", "256")) skip();
    rests(ON_BOX, &CAPSULE_SIDE, 1);
    rests(ON_BOX, &CYLINDER_UP, 1);
    rests(ON_BOX, &CYLINDER_SIDE, 1);
    rests(ON_BOX, &CONE_BASE, 1);
}

static void test_rest_on_hull(void** state)
{
    (void)state;
    if (!th_large_scene_runs("rest_on_hull", "128")) skip();
    rests(ON_HULL, &CAPSULE_SIDE, 1);
    rests(ON_HULL, &CYLINDER_UP, 1);
    rests(ON_HULL, &CYLINDER_SIDE, 1);
    rests(ON_HULL, &CONE_BASE, 1);
}

static void test_rest_on_mesh(void** state)
{
    (void)state;
    if (!th_large_scene_runs("rest_on_mesh", "256")) skip();
    rests(ON_MESH, &CAPSULE_SIDE, 1);
    rests(ON_MESH, &CYLINDER_UP, 1);
    rests(ON_MESH, &CYLINDER_SIDE, 1);
}

/* Rolling without slipping down a slope of angle a: a cylinder (I = m r^2 / 2) accelerates
 * at (2/3) g sin a, a sphere at (5/7) g sin a. Measured from the speed gained between 0.25 s
 * and 1.25 s, within 3 %. */
static double roll_acceleration(tb_shape_type type, double angle)
{
    tb_world* w = th_world_create(NULL);
    tb_vec3 n = th_v3((float)sin(angle), (float)cos(angle), 0);
    tb_shape_id plane = th_plane(w, n, 0);
    tb_body_def ground = th_static_def(plane, th_v3(0, 0, 0));
    th_body(w, &ground);
    float r = 0.3f;
    tb_shape_id s;
    if (type == TB_SHAPE_SPHERE) s = th_sphere(w, r);
    else s = make_round(w, type, r, 0.4f);
    tb_body_def def = th_dynamic_def(s, th_v3(n.x * r, n.y * r, 0));
    def.rotation = th_quat_axis_angle(th_v3(1, 0, 0), M_PI / 2);   /* the axis along z */
    tb_body_id body = th_body(w, &def);
    tb_vec3 down = th_v3((float)cos(angle), (float)-sin(angle), 0), v0, v1, omega;
    step(w, 15);
    th_assert_ok(tb_body_get_velocity(w, body, &v0, &omega));
    step(w, 60);
    th_assert_ok(tb_body_get_velocity(w, body, &v1, &omega));
    double gained = (v1.x - v0.x) * down.x + (v1.y - v0.y) * down.y;
    th_world_destroy(w);
    return gained / 1.0;
}

static void test_cylinder_rolls_down_incline(void** state)
{
    (void)state;
    double angle = 20 * M_PI / 180, g = 9.81 * sin(angle);
    double cylinder = roll_acceleration(TB_SHAPE_CYLINDER, angle);
    double capsule = roll_acceleration(TB_SHAPE_CAPSULE, angle);
    printf("cylinder %.4f (analytic %.4f), capsule %.4f\n", cylinder, 2.0 / 3.0 * g, capsule);
    th_assert_near(cylinder, 2.0 / 3.0 * g, 0, 0.03);
    /* A capsule rolls on its cylinder part: its inertia about the axis is between the
     * cylinder's and the ball's, so is its acceleration. */
    assert_true(capsule > 2.0 / 3.0 * g && capsule < 5.0 / 7.0 * g);
}

/* ---- round shapes on each other ------------------------------------------------------- */

typedef struct stacked {
    tb_shape_type type;       /* TB_SHAPE_SPHERE, _BOX or a round type */
    tb_quat rotation;
    float x, y;               /* of its origin */
} stacked;

/* A tower of shapes (radius or half extent 0.3, half height 0.5) on a plane, each placed
 * resting on those below: after 300 steps every one is within 1 mm of where it began. */
static void tower(const stacked* parts, int count)
{
    tb_world* w = th_world_create(NULL);
    make_ground(w, ON_PLANE);
    tb_body_id bodies[8];
    tb_vec3 start[8];
    for (int i = 0; i < count; i++) {
        tb_shape_id s;
        if (parts[i].type == TB_SHAPE_SPHERE) s = th_sphere(w, 0.3f);
        else if (parts[i].type == TB_SHAPE_BOX) s = th_box(w, th_v3(0.3f, 0.5f, 0.3f));
        else s = make_round(w, parts[i].type, 0.3f, 0.5f);
        start[i] = th_v3(parts[i].x, parts[i].y, 0.01f * i);
        tb_body_def def = th_dynamic_def(s, start[i]);
        def.rotation = parts[i].rotation;
        bodies[i] = th_body(w, &def);
    }
    step(w, 300);
    for (int i = 0; i < count; i++) {
        tb_vec3 p;
        tb_quat q;
        th_read_pose(w, bodies[i], &p, &q);
        printf("tower part %d (type %d): drift %.3f mm\n", i, (int)parts[i].type,
               1e3 * dist3(p, start[i]));
        assert_true(dist3(p, start[i]) < 1e-3);
    }
    th_world_destroy(w);
}

#define SIDE_Z { 0.70710678f, 0, 0, 0.70710678f }   /* axis along z */
#define SIDE_X { 0, 0, 0.70710678f, 0.70710678f }   /* axis along x */
#define UP { 0, 0, 0, 1 }

static void test_round_towers(void** state)
{
    (void)state;
    if (!th_large_scene_runs("round_towers", "128")) skip();
    /* Cylinders cap on cap (two octagons clipped), a cone on them. */
    const stacked cylinders[] = { { TB_SHAPE_CYLINDER, UP, 0, 0.5f },
                                  { TB_SHAPE_CYLINDER, UP, 0.02f, 1.5f },
                                  { TB_SHAPE_CONE, UP, 0.04f, 2.25f } };
    tower(cylinders, 3);
    /* Three capsules lying, the third in the groove of the other two (parallel lines at 60
     * degrees from the floor). */
    float groove = 0.3f + 0.6f * (float)sin(M_PI / 3);
    const stacked capsules[] = { { TB_SHAPE_CAPSULE, SIDE_Z, -0.3f, 0.3f },
                                 { TB_SHAPE_CAPSULE, SIDE_Z, 0.3f, 0.3f },
                                 { TB_SHAPE_CAPSULE, SIDE_Z, 0, groove } };
    tower(capsules, 3);
    /* A cylinder standing on a box, a capsule lying across a standing cylinder's cap (a line
     * clipped by the octagon), a cone on its base on a box. (A cylinder lying on a box that
     * rests on the floor rolls on the least push: that rest is neutral, not asked for.) */
    const stacked standing[] = { { TB_SHAPE_BOX, UP, 0, 0.5f }, { TB_SHAPE_CYLINDER, UP, 0.1f, 1.5f } };
    tower(standing, 2);
    const stacked across[] = { { TB_SHAPE_CYLINDER, UP, 0, 0.5f }, { TB_SHAPE_CAPSULE, SIDE_X, 0, 1.3f } };
    tower(across, 2);
    const stacked cone[] = { { TB_SHAPE_BOX, UP, 0, 0.5f }, { TB_SHAPE_CONE, UP, 0.1f, 1.25f } };
    tower(cone, 2);
}

/* A sled: two capsule runners under a box deck, one compound, resting on a plane on its
 * runners (two lines): within 1 mm over 600 steps, four points. */
static void test_compound_with_round_children(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    make_ground(w, ON_PLANE);
    tb_shape_id runner = make_round(w, TB_SHAPE_CAPSULE, 0.05f, 0.5f), deck = th_box(w, th_v3(0.4f, 0.05f, 0.6f));
    tb_quat along_z = th_quat_axis_angle(th_v3(1, 0, 0), M_PI / 2);
    tb_compound_child parts[3] = { { runner, th_v3(-0.3f, 0, 0), along_z },
                                   { runner, th_v3(0.3f, 0, 0), along_z },
                                   { deck, th_v3(0, 0.1f, 0), { 0, 0, 0, 1 } } };
    tb_shape_id sled;
    th_assert_ok(tb_shape_create_compound(w, parts, 3, &sled));
    tb_compound_info info;
    th_assert_ok(tb_shape_get_compound_info(w, sled, &info));
    /* The body frame is the composed principal frame: place it so the runners touch y = 0. */
    tb_body_def def = th_dynamic_def(sled, th_v3(0, 0.05f + info.center_of_mass.y, 0));
    def.rotation = (tb_quat){ info.principal_axes.x, info.principal_axes.y,
                              info.principal_axes.z, info.principal_axes.w };
    tb_body_id body = th_body(w, &def);
    step(w, 600);
    tb_vec3 p;
    tb_quat q;
    th_read_pose(w, body, &p, &q);
    double deepest;
    uint32_t n = points_of(w, body, &deepest);
    printf("sled: drift %.3f mm, %u points, deepest %.3f mm\n", 1e3 * dist3(p, def.position), n,
           1e3 * deepest);
    assert_true(dist3(p, def.position) < 1e-3);
    assert_int_equal(n, 4);
    th_world_destroy(w);
}

/* ---- the other pairs while round shapes live ------------------------------------------ */

/* A heap of 27 boxes, hulls (cuboctahedra) and spheres on a plane, overlapping a little,
 * turned each its own way. */
static void heap(tb_world* w)
{
    make_ground(w, ON_PLANE);
    tb_vec3 p[12];
    for (int i = 0; i < 12; i++) {
        float a = i & 1 ? 0.45f : -0.45f, b = i & 2 ? 0.45f : -0.45f;
        int axis = i >> 2;   /* which coordinate is zero */
        p[i] = axis == 0 ? th_v3(0, a, b) : axis == 1 ? th_v3(a, 0, b) : th_v3(a, b, 0);
    }
    tb_shape_def def = tb_default_shape_def();
    tb_shape_id shapes[3];
    shapes[0] = th_box(w, th_v3(0.45f, 0.4f, 0.5f));
    th_assert_ok(tb_shape_create_hull(w, &def, p, 12, &shapes[1]));
    shapes[2] = th_sphere(w, 0.47f);
    for (int i = 0; i < 27; i++) {
        tb_vec3 at = th_v3(0.85f * (float)(i % 3), 0.42f + 0.8f * (float)(i / 9),
                           0.85f * (float)((i / 3) % 3));
        tb_body_def b = th_dynamic_def(shapes[(i + i / 3) % 3], at);
        tb_vec3 axis = th_v3(1, (float)(i % 5), (float)(i % 7) - 3);
        b.rotation = th_quat_axis_angle(axis, 0.1f * (float)i);
        th_body(w, &b);
    }
}

static int by_pair_and_feature(const void* x, const void* y)
{
    const tb_contact *a = x, *b = y;
    if (a->a.index1 != b->a.index1) return a->a.index1 < b->a.index1 ? -1 : 1;
    if (a->b.index1 != b->b.index1) return a->b.index1 < b->b.index1 ? -1 : 1;
    return a->feature < b->feature ? -1 : a->feature > b->feature;
}

/* The first step's contacts, sorted, leaving out those of body `skip`. */
static uint32_t first_contacts(tb_world* w, tb_contact* out, uint32_t capacity, uint32_t skip)
{
    th_assert_ok(tb_world_step(w, DT));
    uint32_t count = 0, kept = 0;
    th_assert_ok(tb_world_read_contacts(w, out, capacity, &count));
    assert_true(count <= capacity);
    for (uint32_t i = 0; i < count; i++)
        if (out[i].a.index1 != skip && out[i].b.index1 != skip) out[kept++] = out[i];
    qsort(out, kept, sizeof *out, by_pair_and_feature);
    return kept;
}

/* With a capsule in the world, the pairs of boxes, hulls, spheres and the plane are listed
 * by narrowphase/round_cull and taken from that list by contacts and hull_points (spread
 * over several threads each, as they are few); without, a thread per pair. Either way the
 * same routines on the same poses: the same points, to the bit. */
static void test_other_pairs_same_with_round_shapes(void** state)
{
    (void)state;
    enum { CAP = 512 };
    static tb_contact alone[CAP], beside[CAP];
    tb_world* w = th_world_create(NULL);
    heap(w);
    uint32_t n = first_contacts(w, alone, CAP, UINT32_MAX);
    th_world_destroy(w);

    w = th_world_create(NULL);
    heap(w);
    tb_shape_id s = make_round(w, TB_SHAPE_CAPSULE, 0.3f, 0.5f);
    tb_body_def def = th_dynamic_def(s, th_v3(40, 0.8f, 0));
    tb_body_id capsule = th_body(w, &def);
    uint32_t m = first_contacts(w, beside, CAP, capsule.index1);
    th_world_destroy(w);

    printf("heap: %u contact points\n", n);
    assert_true(n > 40);
    assert_int_equal(m, n);
    for (uint32_t i = 0; i < n; i++) {
        assert_int_equal(alone[i].a.index1, beside[i].a.index1);
        assert_int_equal(alone[i].b.index1, beside[i].b.index1);
        assert_int_equal(alone[i].feature, beside[i].feature);
        assert_memory_equal(&alone[i].point, &beside[i].point, sizeof alone[i].point);
        assert_memory_equal(&alone[i].normal, &beside[i].normal, sizeof alone[i].normal);
        assert_memory_equal(&alone[i].separation, &beside[i].separation, sizeof(float));
    }
}

/* ---- sizes, mass and refusals --------------------------------------------------------- */

/* Volume and principal moments per unit mass of a solid of revolution about y, integrated
 * on a fine grid of (distance from the axis, height) cells: the reference for the closed
 * forms the library uses. inside(rho, y) says whether the point lies in the solid. */
typedef int (*solid_fn)(double rho, double y, double r, double h);

static int in_capsule(double rho, double y, double r, double h)
{
    double dy = fabs(y) > h ? fabs(y) - h : 0;
    return rho * rho + dy * dy <= r * r;
}

static int in_cylinder(double rho, double y, double r, double h)
{
    return rho <= r && fabs(y) <= h;
}

static int in_cone(double rho, double y, double r, double h)
{
    return y >= -h / 2 && y <= 1.5 * h && rho <= r * (1.5 * h - y) / (2 * h);
}

static void integrate(solid_fn inside, double r, double h, double out[4])
{
    const int n = 1500;
    /* The solid's extent along y: cells straddle its ends only. */
    double y0 = inside == in_capsule ? -h - r : (inside == in_cone ? -h / 2 : -h);
    double y1 = inside == in_capsule ? h + r : (inside == in_cone ? 1.5 * h : h);
    double dr = r / n, dy = (y1 - y0) / (2 * n);
    double v = 0, my = 0, iy = 0, ix = 0;
    for (int j = 0; j < 2 * n; j++) {
        double y = y0 + (j + 0.5) * dy;
        for (int i = 0; i < n; i++) {
            double rho = (i + 0.5) * dr;
            if (!inside(rho, y, r, h)) continue;
            double dv = 2 * M_PI * rho * dr * dy;
            v += dv;
            my += y * dv;
            iy += rho * rho * dv;
            ix += (y * y + rho * rho / 2) * dv;
        }
    }
    out[0] = v;
    out[1] = my / v;          /* the centre of mass's height: 0 */
    out[2] = ix / v;
    out[3] = iy / v;
}

static void check_mass(tb_world* w, tb_shape_type type, solid_fn inside, float r, float h)
{
    tb_shape_id s = make_round(w, type, r, h);
    float radius, half_height;
    th_assert_ok(tb_shape_get_round_size(w, s, &radius, &half_height));
    assert_true(radius == r && half_height == h);
    tb_shape_type got;
    th_assert_ok(tb_shape_get_type(w, s, &got));
    assert_int_equal(got, type);
    tb_body_def def = th_dynamic_def(s, th_v3(0, 0, 0));
    tb_body_id body = th_body(w, &def);
    float mass;
    tb_vec3 inertia;
    th_assert_ok(tb_body_get_mass(w, body, &mass, &inertia));
    double ref[4];
    integrate(inside, r, h, ref);
    th_assert_near(mass, 1000 * ref[0], 0, 2e-3);
    th_assert_near(ref[1], 0, 1e-3 * (r + h), 0);
    th_assert_near(inertia.x / mass, ref[2], 0, 3e-3);
    th_assert_near(inertia.z / mass, ref[2], 0, 3e-3);
    th_assert_near(inertia.y / mass, ref[3], 0, 3e-3);
    th_assert_ok(tb_body_destroy(w, body));
}

/* A sphere or capsule against a capsule goes in closed form (the closest points of the two
 * segments): placed still in a world without gravity, one step's contact reads the exact
 * separation and normal. Each case: the first body (a sphere when its half height is
 * negative), the capsule, the separation and the normal's direction expected, the points. */
typedef struct segment_case {
    float radius_a, half_a;   ///< half_a < 0: a sphere
    tb_vec3 at_a;
    tb_quat turn_a;
    tb_vec3 at_b;             ///< a capsule of radius 0.2, half height 0.5
    tb_quat turn_b;
    float separation;
    tb_vec3 normal;           ///< from the first body to the capsule, up to sign when crossed
    uint32_t points;
} segment_case;

static void test_capsule_pairs_closed_form(void** state)
{
    (void)state;
    const tb_quat along_x = { 0, 0, 0.70710678f, 0.70710678f }, along_z = { 0.70710678f, 0, 0, 0.70710678f };
    const segment_case cases[] = {
        /* crossing at right angles, 0.3 apart: 0.1 deep */
        { 0.2f, 0.5f, { 0, 0, 0 }, along_x, { 0, 0.3f, 0 }, along_z, -0.1f, { 0, 1, 0 }, 1 },
        /* the cores cross: the normal square to both, as deep as both radii */
        { 0.2f, 0.5f, { 0, 0, 0 }, along_x, { 0.1f, 0, -0.2f }, along_z, -0.4f, { 0, 1, 0 }, 1 },
        /* a sphere over the capsule's side, off its middle */
        { 0.25f, -1.0f, { 0.2f, 0.4f, 0 }, { 0, 0, 0, 1 }, { 0, 0, 0 }, along_x, -0.05f, { 0, -1, 0 }, 1 },
        /* a sphere beyond the capsule's end, along its axis */
        { 0.25f, -1.0f, { 0.9f, 0, 0 }, { 0, 0, 0, 1 }, { 0, 0, 0 }, along_x, -0.05f, { -1, 0, 0 }, 1 },
        /* side by side, parallel and shifted: a line contact */
        { 0.2f, 0.5f, { 0, 0, 0 }, along_x, { 0.3f, 0.35f, 0 }, along_x, -0.05f, { 0, 1, 0 }, 2 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const segment_case* c = &cases[i];
        tb_world_def wd = tb_default_world_def();
        wd.gravity = th_v3(0, 0, 0);
        tb_world* w = th_world_create(&wd);
        tb_shape_id sa = c->half_a < 0 ? th_sphere(w, c->radius_a)
                                       : make_round(w, TB_SHAPE_CAPSULE, c->radius_a, c->half_a);
        tb_body_def da = th_dynamic_def(sa, c->at_a), db = th_dynamic_def(make_round(w, TB_SHAPE_CAPSULE, 0.2f, 0.5f), c->at_b);
        da.rotation = c->turn_a;
        db.rotation = c->turn_b;
        tb_body_id a = th_body(w, &da), b = th_body(w, &db);
        th_assert_ok(tb_world_step(w, 1e-4f));
        tb_contact contacts[8];
        uint32_t count = 0;
        th_assert_ok(tb_world_read_contacts(w, contacts, 8, &count));
        printf("case %zu: %u points", i, count);
        assert_int_equal(count, c->points);
        for (uint32_t k = 0; k < count; k++) {
            tb_vec3 n = contacts[k].normal;
            float sign = contacts[k].a.index1 == a.index1 ? 1.0f : -1.0f;   /* first to capsule */
            float along = sign * (n.x * c->normal.x + n.y * c->normal.y + n.z * c->normal.z);
            printf(", separation %.6f normal %.5f %.5f %.5f", contacts[k].separation, n.x, n.y, n.z);
            assert_true(contacts[k].a.index1 == a.index1 || contacts[k].a.index1 == b.index1);
            assert_true(fabs(contacts[k].separation - c->separation) < 1e-5);
            assert_true(i == 1 ? fabs(along) > 0.99999 : along > 0.99999);
        }
        printf("\n");
        th_world_destroy(w);
    }
}

static void test_sizes_and_mass(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    check_mass(w, TB_SHAPE_CAPSULE, in_capsule, 0.3f, 0.5f);
    check_mass(w, TB_SHAPE_CAPSULE, in_capsule, 0.5f, 0.0f);
    check_mass(w, TB_SHAPE_CYLINDER, in_cylinder, 0.3f, 0.5f);
    check_mass(w, TB_SHAPE_CYLINDER, in_cylinder, 2.0f, 0.05f);
    check_mass(w, TB_SHAPE_CONE, in_cone, 0.3f, 0.5f);
    check_mass(w, TB_SHAPE_CONE, in_cone, 1.0f, 0.2f);
    th_world_destroy(w);
}

static void test_bad_round_shapes_refused(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    tb_shape_def def = tb_default_shape_def();
    tb_shape_id s = { 0 }, kept = make_round(w, TB_SHAPE_CYLINDER, 1, 1);
    const float bad_radius[] = { 0.0f, -1.0f, NAN, INFINITY, 2e6f };
    for (size_t i = 0; i < sizeof bad_radius / sizeof *bad_radius; i++) {
        th_assert_result(tb_shape_create_capsule(w, &def, bad_radius[i], 1, &s), TB_ERROR_INVALID_ARGUMENT);
        assert_non_null(strstr(tb_world_last_error(w), "capsule needs"));
        th_assert_result(tb_shape_create_cylinder(w, &def, bad_radius[i], 1, &s), TB_ERROR_INVALID_ARGUMENT);
        assert_non_null(strstr(tb_world_last_error(w), "cylinder needs"));
        th_assert_result(tb_shape_create_cone(w, &def, bad_radius[i], 1, &s), TB_ERROR_INVALID_ARGUMENT);
        assert_non_null(strstr(tb_world_last_error(w), "cone needs"));
    }
    const float bad_height[] = { -1.0f, NAN, -INFINITY, 2e6f };
    for (size_t i = 0; i < sizeof bad_height / sizeof *bad_height; i++) {
        th_assert_result(tb_shape_create_capsule(w, &def, 1, bad_height[i], &s), TB_ERROR_INVALID_ARGUMENT);
        th_assert_result(tb_shape_create_cylinder(w, &def, 1, bad_height[i], &s), TB_ERROR_INVALID_ARGUMENT);
        th_assert_result(tb_shape_create_cone(w, &def, 1, bad_height[i], &s), TB_ERROR_INVALID_ARGUMENT);
    }
    /* A flat cylinder or cone has no volume; a capsule of no length is a ball. */
    th_assert_result(tb_shape_create_cylinder(w, &def, 1, 0, &s), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_cone(w, &def, 1, 0, &s), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_shape_create_capsule(w, &def, 1, 1, NULL), TB_ERROR_INVALID_ARGUMENT);
    tb_shape_def raw;
    memset(&raw, 0, sizeof raw);
    th_assert_result(tb_shape_create_cone(w, &raw, 1, 1, &s), TB_ERROR_INVALID_ARGUMENT);
    assert_int_equal(s.index1, 0);
    /* Nothing was made: the one good shape is the only one. */
    tb_shape_id ids[4];
    assert_int_equal(tb_world_shape_ids(w, ids, 4), 1);
    float r, h;
    th_assert_result(tb_shape_get_round_size(w, kept, NULL, &h), TB_ERROR_INVALID_ARGUMENT);
    tb_shape_id ball = th_sphere(w, 1);
    th_assert_result(tb_shape_get_round_size(w, ball, &r, &h), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "is not a capsule, cylinder or cone"));
    th_world_destroy(w);
}

/* ---- contact reuse (tb_world_set_contact_reuse) -------------------------------------- */

#define REUSE_CAPACITY 512

static uint32_t read_all_contacts(tb_world* w, tb_contact* out)
{
    uint32_t count = 0;
    th_assert_ok(tb_world_read_contacts(w, out, REUSE_CAPACITY, &count));
    assert_true(count <= REUSE_CAPACITY);
    return count;
}

/* What a pair's contacts in `list` come to (a pile's manifolds may pick other points of
 * the same features from step to step: four of a cap's eight corners, the other face of two
 * parallel ones): how many, their centroid, their deepest separation and the normal. */
typedef struct pair_summary {
    uint32_t count;
    tb_vec3 centroid, normal;
    double deepest;
} pair_summary;

static pair_summary summarise(const tb_contact* c, const tb_contact* list, uint32_t n)
{
    pair_summary s = { 0, { 0, 0, 0 }, { 0, 0, 0 }, 1e9 };
    for (uint32_t i = 0; i < n; i++) {
        if (list[i].a.index1 != c->a.index1 || list[i].b.index1 != c->b.index1) continue;
        s.count++;
        s.centroid.x += list[i].point.x, s.centroid.y += list[i].point.y;
        s.centroid.z += list[i].point.z;
        s.normal = list[i].normal;
        s.deepest = fmin(s.deepest, list[i].separation);
    }
    if (s.count) s.centroid.x /= s.count, s.centroid.y /= s.count, s.centroid.z /= s.count;
    return s;
}

/* A settled heap of capsules, cylinders, cones, boxes and hulls on a plane and a box, stepped
 * once from its snapshot with reuse (the default) and once without: each pair's contacts
 * measured again are as many as those found anew, within what the bounds allow of them
 * (centroid 5 mm, deepest separation 1 mm, normal 1.5 degrees), and not all to the bit (so
 * they were measured again). */
static void test_contact_reuse_matches_narrowphase(void** state)
{
    (void)state;
    tb_world* w = th_world_create(NULL);
    make_ground(w, ON_PLANE);
    tb_body_def ledge = th_static_def(th_box(w, th_v3(1.0f, 0.25f, 1.0f)), th_v3(1.5f, 0.25f, 0));
    th_body(w, &ledge);
    tb_shape_type kinds[3] = { TB_SHAPE_CAPSULE, TB_SHAPE_CYLINDER, TB_SHAPE_CONE };
    tb_shape_id box = th_box(w, th_v3(0.2f, 0.15f, 0.25f)), rock = th_rock(w);
    for (int i = 0; i < 24; i++) {
        tb_shape_id s = i % 4 == 3 ? (i % 8 == 3 ? box : rock) : make_round(w, kinds[i % 3], 0.2f, 0.3f);
        tb_body_def d = th_dynamic_def(s, th_v3(0.55f * (i % 6) - 0.4f, 0.8f + 0.7f * (i / 6),
                                                 0.3f * ((i * 7) % 3) - 0.3f));
        float angle = 0.4f * (float)i;
        d.rotation = (tb_quat){ sinf(angle) * 0.6f, 0, cosf(angle) * 0.8f, 1.0f };
        float norm = sqrtf(d.rotation.x * d.rotation.x + d.rotation.z * d.rotation.z + 1.0f);
        d.rotation.x /= norm, d.rotation.z /= norm, d.rotation.w /= norm;
        th_body(w, &d);
    }
    step(w, 300);
    size_t size = 0;
    th_assert_ok(tb_world_snapshot(w, NULL, 0, &size));
    void* bytes = malloc(size);
    assert_non_null(bytes);
    th_assert_ok(tb_world_snapshot(w, bytes, size, &size));
    static tb_contact reused[REUSE_CAPACITY], fresh[REUSE_CAPACITY];
    step(w, 1);
    uint32_t n_reused = read_all_contacts(w, reused);
    th_assert_ok(tb_world_restore(w, bytes, size));
    th_assert_ok(tb_world_set_contact_reuse(w, 0, 0));
    step(w, 1);
    uint32_t n_fresh = read_all_contacts(w, fresh);
    free(bytes);
    uint32_t pairs = 0, differ = 0;
    double worst_centroid = 0, worst_separation = 0, worst_normal = 1;
    for (uint32_t i = 0; i < n_fresh; i++) {
        if (i > 0 && fresh[i].a.index1 == fresh[i - 1].a.index1 &&
            fresh[i].b.index1 == fresh[i - 1].b.index1)
            continue;   /* grouped by pair: its first contact stands for it */
        pair_summary f = summarise(&fresh[i], fresh, n_fresh);
        pair_summary r = summarise(&fresh[i], reused, n_reused);
        pairs++;
        assert_int_equal(r.count, f.count);
        double dn = r.normal.x * f.normal.x + r.normal.y * f.normal.y + r.normal.z * f.normal.z;
        worst_centroid = fmax(worst_centroid, dist3(r.centroid, f.centroid));
        worst_separation = fmax(worst_separation, fabs(r.deepest - f.deepest));
        worst_normal = fmin(worst_normal, dn);
    }
    for (uint32_t i = 0; i < n_fresh && i < n_reused; i++)
        differ += memcmp(&fresh[i], &reused[i], sizeof fresh[i]) != 0;
    printf("reuse: %u contacts in %u pairs (%u not to the bit); worst centroid %.3f mm, "
           "deepest separation %.4f mm, normal %.3f deg\n", n_fresh, pairs, differ,
           1e3 * worst_centroid, 1e3 * worst_separation,
           acos(fmin(1.0, worst_normal)) * 180 / M_PI);
    assert_true(n_fresh >= 20 && n_reused == n_fresh);
    assert_true(differ > 0);
    assert_true(worst_centroid < 5e-3);
    assert_true(worst_separation < 1e-3);
    assert_true(worst_normal > cos(1.5 * M_PI / 180));
    th_world_destroy(w);
}

/* Pairs of round and other convex shapes in free flight, each mover turning as it closes
 * on its target, meets it and leaves: stepped with contact reuse whose bounds nothing at
 * rest within them (so only the directions along which GJK found pairs apart are kept,
 * round_cull trying them first) and without reuse, every pose stays the same to the bit.
 * A kept direction only ever shows a pair apart that is, so it changes no result. */
static tb_world* flyby_world(float reuse_distance, tb_body_id ids[20])
{
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&def);
    th_assert_ok(tb_world_set_contact_reuse(w, reuse_distance, reuse_distance));
    tb_shape_id shapes[5] = { make_round(w, TB_SHAPE_CYLINDER, 0.2f, 0.3f),
                              make_round(w, TB_SHAPE_CONE, 0.25f, 0.3f),
                              th_box(w, th_v3(0.25f, 0.2f, 0.3f)), th_rock(w),
                              make_round(w, TB_SHAPE_CAPSULE, 0.15f, 0.3f) };
    for (int i = 0; i < 10; i++) {
        tb_vec3 at = th_v3(4.0f * (float)i, 0, 0);
        tb_body_def target = th_dynamic_def(shapes[i % 5], at);
        target.rotation = th_quat_axis_angle(th_v3(1, 0.3f, 0), 0.5 * i);
        ids[2 * i] = th_body(w, &target);
        double angle = 0.7 * i;
        tb_vec3 dir = th_v3((float)cos(angle), 0.5f, (float)sin(angle));
        float len = sqrtf(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
        dir = th_v3(dir.x / len, dir.y / len, dir.z / len);
        tb_body_def mover = th_dynamic_def(shapes[(i * 3 + 1) % 5],
                                           th_v3(at.x + 0.9f * dir.x, 0.9f * dir.y, 0.9f * dir.z));
        mover.rotation = th_quat_axis_angle(th_v3(0.2f, 1, 0.4f), 0.9 * i);
        mover.linear_velocity = th_v3(-0.5f * dir.x + 0.03f, -0.5f * dir.y, -0.5f * dir.z);
        mover.angular_velocity = th_v3(0.3f, 1.1f, -0.7f);
        ids[2 * i + 1] = th_body(w, &mover);
    }
    return w;
}

static void test_apart_directions_change_nothing(void** state)
{
    (void)state;
    tb_body_id ids[20], same[20];
    tb_world* kept = flyby_world(1.0e-7f, ids);
    tb_world* fresh = flyby_world(0.0f, same);
    uint32_t count = 20;
    int touching_steps = 0;
    for (int s = 0; s < 150; s++) {
        step(kept, 1);
        step(fresh, 1);
        uint32_t contacts = th_stats(kept).contact_count;
        assert_int_equal(contacts, th_stats(fresh).contact_count);
        touching_steps += contacts > 0;
        for (uint32_t i = 0; i < count; i++) {
            tb_vec3 pk, pf;
            tb_quat qk, qf;
            th_read_pose(kept, ids[i], &pk, &qk);
            th_read_pose(fresh, same[i], &pf, &qf);
            assert_memory_equal(&pk, &pf, sizeof pk);
            assert_memory_equal(&qk, &qf, sizeof qk);
        }
    }
    printf("apart directions: %d of 150 steps with contacts, poses to the bit\n", touching_steps);
    assert_true(touching_steps >= 10);
    th_world_destroy(kept);
    th_world_destroy(fresh);
}

/* Bad bounds are refused and change nothing; get reads back what was set. */
static void test_contact_reuse_settings(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    float d = 0, a = 0;
    tb_world_get_contact_reuse(w, &d, &a);
    assert_true(d == TB_DEFAULT_REUSE_DISTANCE && a == TB_DEFAULT_REUSE_ANGLE);
    th_assert_ok(tb_world_set_contact_reuse(w, 0.002f, 0.01f));
    const float bad[][2] = { { -0.001f, 0.01f }, { NAN, 0.01f }, { 0.001f, INFINITY },
                             { 0.001f, -0.1f }, { 0.001f, 1.0f } };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        th_assert_result(tb_world_set_contact_reuse(w, bad[i][0], bad[i][1]),
                         TB_ERROR_INVALID_ARGUMENT);
    tb_world_get_contact_reuse(w, &d, &a);
    assert_true(d == 0.002f && a == 0.01f);
    th_assert_result(tb_world_set_contact_reuse(NULL, 0, 0), TB_ERROR_INVALID_ARGUMENT);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sizes_and_mass),
        cmocka_unit_test(test_bad_round_shapes_refused),
        cmocka_unit_test(test_rest_on_plane),
        cmocka_unit_test(test_rest_on_box),
        cmocka_unit_test(test_rest_on_hull),
        cmocka_unit_test(test_rest_on_mesh),
        cmocka_unit_test(test_cylinder_rolls_down_incline),
        cmocka_unit_test(test_round_towers),
        cmocka_unit_test(test_compound_with_round_children),
        cmocka_unit_test(test_capsule_pairs_closed_form),
        cmocka_unit_test(test_other_pairs_same_with_round_shapes),
        cmocka_unit_test(test_contact_reuse_matches_narrowphase),
        cmocka_unit_test(test_apart_directions_change_nothing),
        cmocka_unit_test(test_contact_reuse_settings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
