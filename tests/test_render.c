/* tools/render on lavapipe with validation (synchronization included) on: a box resting on
 * a ground plane seen by a fixed camera must appear where the same camera maths projects it,
 * in its colour, over ground and under sky; an empty world renders; the automatic camera
 * frames a few spheres. Pixels are classified by colour family, not compared exactly,
 * except the cleared sky. */
#include "harness.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"

#define W 320
#define H 240
#define PI 3.14159265358979323846

/* The renderer's clear colour (TR_SKY_* in tools/render/render_internal.h). */
static const uint8_t SKY[3] = { 204, 219, 235 };

static tb_world* zero_gravity_world(void)
{
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    return th_world_create(&wd);
}

static void assert_no_validation(const tb_world* w)
{
    tb_world_stats st = th_stats(w);
    if (st.validation_messages)
        fail_msg("%llu validation message(s) so far", (unsigned long long)st.validation_messages);
}

static tr_renderer* renderer(tb_world* w, const tr_options* o)
{
    tr_renderer* r = NULL;
    tb_result res = tr_create(w, o, &r);
    if (res) fail_msg("tr_create: %s: %s", tb_result_string(res), tr_last_error(NULL));
    return r;
}

static void render(tr_renderer* r, tb_world* w)
{
    tb_result res = tr_render(r);
    if (res) fail_msg("tr_render: %s: %s", tb_result_string(res), tr_last_error(r));
    assert_no_validation(w);
}

/* The renderer's camera maths, in double: right-handed look-at, Vulkan perspective (y down,
 * depth 0..1), viewport to pixels. Returns 0 behind the camera. */
static int project(const tr_camera* c, uint32_t width, uint32_t height, const double p[3],
                   double* px, double* py)
{
    double f[3] = { c->target.x - c->eye.x, c->target.y - c->eye.y, c->target.z - c->eye.z };
    double up[3] = { c->up.x, c->up.y, c->up.z };
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] /= fl;
    double s[3] = { f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                    f[0] * up[1] - f[1] * up[0] };
    double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int i = 0; i < 3; i++) s[i] /= sl;
    double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                    s[0] * f[1] - s[1] * f[0] };
    double d[3] = { p[0] - c->eye.x, p[1] - c->eye.y, p[2] - c->eye.z };
    double x = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
    double y = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    double depth = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
    if (depth <= 0) return 0;
    double t = 1.0 / tan(0.5 * c->fov_y_degrees * PI / 180.0);
    double aspect = (double)width / height;
    double ndc_x = t / aspect * x / depth, ndc_y = -t * y / depth;
    *px = (ndc_x + 1.0) * 0.5 * width;
    *py = (ndc_y + 1.0) * 0.5 * height;
    return 1;
}

static const uint8_t* pixel(const uint8_t* rgba, uint32_t width, int x, int y)
{
    return rgba + ((size_t)y * width + (size_t)x) * 4;
}

/* Colour families of the scene (TR_COLOR_BY_SHAPE): boxes blue, spheres orange, static
 * ground a neutral grey; lighting scales them by 0.35..1. */
static int is_box(const uint8_t* p) { return p[2] - p[0] > 50 && p[2] - p[1] > 30; }
static int is_sphere(const uint8_t* p) { return p[0] - p[2] > 50 && p[0] > p[1]; }
static int is_sky(const uint8_t* p)
{
    return p[0] == SKY[0] && p[1] == SKY[1] && p[2] == SKY[2] && p[3] == 255;
}
static int is_ground(const uint8_t* p)
{
    return abs(p[0] - p[1]) <= 12 && abs(p[1] - p[2]) <= 16 && !is_sky(p) && p[0] > 30;
}

static void describe(const uint8_t* p, char* out, size_t n)
{
    snprintf(out, n, "(%d, %d, %d, %d)", p[0], p[1], p[2], p[3]);
}

/* The pixel where world point p projects must satisfy `family`. */
static void expect_at(const tr_camera* c, const uint8_t* rgba, const double p[3],
                      int (*family)(const uint8_t*), const char* what)
{
    double px, py;
    if (!project(c, W, H, p, &px, &py)) fail_msg("%s is behind the camera", what);
    int x = (int)floor(px), y = (int)floor(py);
    if (x < 0 || y < 0 || x >= W || y >= H)
        fail_msg("%s projects outside the image, at (%.1f, %.1f)", what, px, py);
    const uint8_t* q = pixel(rgba, W, x, y);
    char got[48];
    describe(q, got, sizeof got);
    if (!family(q)) fail_msg("%s at pixel (%d, %d) has the wrong colour %s", what, x, y, got);
}

static tr_options fixed_camera_options(void)
{
    tr_options o = tr_default_options();
    o.width = W;
    o.height = H;
    o.color = TR_COLOR_BY_SHAPE;
    o.camera.automatic = 0;
    o.camera.eye = th_v3(4, 3, 5);
    o.camera.target = th_v3(0, 0.5f, 0);
    o.camera.up = th_v3(0, 1, 0);
    o.camera.fov_y_degrees = 45;
    return o;
}

/* The box's silhouette: every box-coloured pixel inside the bounding rectangle of its
 * projected corners, and the disc around its projected centre (inside the projection of
 * its inscribed sphere) box-coloured. */
static void check_box_region(const tr_camera* c, const uint8_t* rgba)
{
    double lo_x = 1e9, lo_y = 1e9, hi_x = -1e9, hi_y = -1e9;
    for (int k = 0; k < 8; k++) {
        double p[3] = { (k & 1) ? 0.5 : -0.5, (k & 2) ? 1.0 : 0.0, (k & 4) ? 0.5 : -0.5 };
        double px, py;
        assert_true(project(c, W, H, p, &px, &py));
        lo_x = fmin(lo_x, px); hi_x = fmax(hi_x, px);
        lo_y = fmin(lo_y, py); hi_y = fmax(hi_y, py);
    }
    const double centre[3] = { 0, 0.5, 0 };
    double cx, cy;
    assert_true(project(c, W, H, centre, &cx, &cy));
    uint32_t box = 0, outside = 0, disc = 0, disc_box = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            const uint8_t* p = pixel(rgba, W, x, y);
            double fx = x + 0.5, fy = y + 0.5;
            if (is_box(p)) {
                box++;
                if (fx < lo_x - 1 || fx > hi_x + 1 || fy < lo_y - 1 || fy > hi_y + 1) outside++;
            }
            if ((fx - cx) * (fx - cx) + (fy - cy) * (fy - cy) <= 12.0 * 12.0) {
                disc++;
                disc_box += is_box(p) != 0;
            }
        }
    }
    double rect = (hi_x - lo_x) * (hi_y - lo_y);
    print_message("box: %u pixels, rectangle [%.1f, %.1f] x [%.1f, %.1f] (%.0f pixels), "
                  "centre disc %u/%u\n", box, lo_x, hi_x, lo_y, hi_y, rect, disc_box, disc);
    if (outside) fail_msg("%u box-coloured pixels outside the box's projection", outside);
    /* A box's silhouette covers well over a third of its bounding rectangle. */
    if (box < rect * 0.4) fail_msg("only %u box-coloured pixels of %.0f", box, rect);
    if (disc_box < disc * 0.98) fail_msg("centre disc: %u of %u box-coloured", disc_box, disc);
}

static void check_png(const char* path)
{
    FILE* f = fopen(path, "rb");
    assert_non_null(f);
    unsigned char head[8] = { 0 };
    size_t n = fread(head, 1, 8, f);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fclose(f);
    const unsigned char signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    assert_int_equal(n, 8);
    assert_memory_equal(head, signature, 8);
    assert_true(size > 100);
}

static void test_box_on_plane(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_body_def box = th_dynamic_def(th_box(w, th_v3(0.5f, 0.5f, 0.5f)), th_v3(0, 0.5f, 0));
    th_body(w, &box);
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));   /* computes the AABBs */

    tr_options o = fixed_camera_options();
    tr_renderer* r = renderer(w, &o);
    uint8_t* rgba = malloc((size_t)W * H * 4);
    assert_non_null(rgba);
    th_assert_result(tr_read_pixels(r, rgba), TB_ERROR_INVALID_ARGUMENT);  /* no frame yet */
    render(r, w);
    th_assert_ok(tr_read_pixels(r, rgba));
    th_assert_ok(tr_write_png(r, "/tmp/tumble_render_box.png"));
    check_png("/tmp/tumble_render_box.png");

    tr_camera c = tr_last_camera(r);
    th_assert_vec3_near(c.eye, o.camera.eye, 0, 0);
    const double centre[3] = { 0, 0.5, 0 }, top[3] = { 0, 1.0, 0 };
    const double ground_left[3] = { -2.5, 0, 1.5 }, ground_front[3] = { 1.5, 0, 2.5 };
    expect_at(&c, rgba, centre, is_box, "the box centre");
    expect_at(&c, rgba, top, is_box, "the box's top face centre");
    expect_at(&c, rgba, ground_left, is_ground, "the ground at (-2.5, 0, 1.5)");
    expect_at(&c, rgba, ground_front, is_ground, "the ground in front of the box");
    for (int x = 0; x < W; x += 7) {
        const uint8_t* p = pixel(rgba, W, x, 1);
        char got[48];
        describe(p, got, sizeof got);
        if (!is_sky(p)) fail_msg("top row pixel %d is %s, not the sky colour", x, got);
    }
    check_box_region(&c, rgba);

    /* A second frame after another step, with AABB lines: the world's compute writes and
     * our reads interleave on one queue (synchronization validation watches). */
    o.show_aabbs = 1;
    th_assert_ok(tr_set_options(r, &o));
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    render(r, w);
    th_assert_ok(tr_read_pixels(r, rgba));
    th_assert_ok(tr_write_png(r, "/tmp/tumble_render_aabb.png"));
    expect_at(&c, rgba, centre, is_box, "the box centre (second frame)");

    free(rgba);
    tr_destroy(r);
    th_world_destroy(w);
}

static void test_empty_world(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    tr_options o = tr_default_options();
    o.width = 160;
    o.height = 120;
    tr_renderer* r = renderer(w, &o);
    render(r, w);
    uint8_t* rgba = malloc(200 * 100 * 4);
    assert_non_null(rgba);
    th_assert_ok(tr_read_pixels(r, rgba));
    /* The default view looks down at the origin: the default grid at y = 0 fills it. */
    assert_true(is_ground(pixel(rgba, 160, 80, 60)));
    assert_true(is_ground(pixel(rgba, 160, 80, 115)));

    /* Bad options are refused and leave the renderer as it was; a new size works. */
    tr_options bad = o;
    bad.width = 0;
    th_assert_result(tr_set_options(r, &bad), TB_ERROR_INVALID_ARGUMENT);
    assert_true(strlen(tr_last_error(r)) > 0);
    bad = o;
    bad.camera.automatic = 0;
    bad.camera.eye = bad.camera.target;
    th_assert_result(tr_set_options(r, &bad), TB_ERROR_INVALID_ARGUMENT);
    o.width = 200;
    o.height = 100;
    o.show_grid = 0;
    th_assert_ok(tr_set_options(r, &o));
    render(r, w);
    th_assert_ok(tr_read_pixels(r, rgba));
    for (int i = 0; i < 200 * 100; i += 97) assert_true(is_sky(rgba + 4 * i));  /* nothing */

    free(rgba);
    tr_destroy(r);
    th_world_destroy(w);
}

static void test_automatic_camera(void** state)
{
    (void)state;
    tb_world* w = zero_gravity_world();
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_id ball = th_sphere(w, 0.5f);
    const double centres[5][3] = { { -3, 1, 0 }, { 4, 2, -2 }, { 0, 5, 3 }, { 1, 0.5, 6 },
                                   { -2, 3, -5 } };
    for (int i = 0; i < 5; i++) {
        tb_body_def d = th_dynamic_def(ball, th_v3((float)centres[i][0], (float)centres[i][1],
                                                   (float)centres[i][2]));
        th_body(w, &d);
    }
    th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
    tr_options o = tr_default_options();
    o.width = W;
    o.height = H;
    o.color = TR_COLOR_BY_SHAPE;
    tr_renderer* r = renderer(w, &o);
    render(r, w);
    uint8_t* rgba = malloc((size_t)W * H * 4);
    assert_non_null(rgba);
    th_assert_ok(tr_read_pixels(r, rgba));
    th_assert_ok(tr_write_png(r, "/tmp/tumble_render_spheres.png"));
    tr_camera c = tr_last_camera(r);
    assert_true(c.automatic);
    for (int i = 0; i < 5; i++) {
        char what[64];
        snprintf(what, sizeof what, "sphere %d", i);
        expect_at(&c, rgba, centres[i], is_sphere, what);
    }
    free(rgba);
    tr_destroy(r);
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_on_plane),
        cmocka_unit_test(test_empty_world),
        cmocka_unit_test(test_automatic_camera),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
