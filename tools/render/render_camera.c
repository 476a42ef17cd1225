/* Cameras: the host-side look at the scene (bounds of the finite AABBs, whether a plane
 * exists), the automatic camera that frames it, and the view-projection matrix with Vulkan
 * clip conventions (right-handed view, y down in NDC, depth 0..1). Double precision. */
#include <math.h>
#include <stdlib.h>

#include "render_internal.h"

/* AABBs beyond this are unbounded (planes get TB_UNBOUNDED_EXTENT, 1e18). */
#define UNBOUNDED 1e17
#define DEG 0.017453292519943295

static int finite_box(tb_vec3 lo, tb_vec3 hi)
{
    const float v[6] = { lo.x, lo.y, lo.z, hi.x, hi.y, hi.z };
    for (int i = 0; i < 6; i++)
        if (!(fabs(v[i]) <= UNBOUNDED)) return 0;
    return 1;
}

static void add_box(tr_scene* s, tb_vec3 lo, tb_vec3 hi)
{
    const double l[3] = { lo.x, lo.y, lo.z }, h[3] = { hi.x, hi.y, hi.z };
    for (int i = 0; i < 3; i++) {
        s->lo[i] = s->has_bounds ? fmin(s->lo[i], l[i]) : l[i];
        s->hi[i] = s->has_bounds ? fmax(s->hi[i], h[i]) : h[i];
    }
    s->has_bounds = 1;
}

tb_result tr_scene_scan(tr_renderer* r, tr_scene* out)
{
    *out = (tr_scene){ 0 };
    tb_world_stats stats;
    tb_result res = tb_world_get_stats(r->world, &stats);
    if (res) return tr_fail(r, res, "tb_world_get_stats: %s", tb_world_last_error(r->world));
    uint32_t n = stats.body_count;
    if (n == 0) return TB_OK;
    tb_body_id* ids = malloc(n * sizeof *ids);
    tb_vec3* lo = malloc(n * sizeof *lo);
    tb_vec3* hi = malloc(n * sizeof *hi);
    if (!ids || !lo || !hi) {
        res = tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for %u body AABBs", n);
    } else {
        n = tb_world_body_ids(r->world, ids, n);
        res = tb_world_read_aabbs(r->world, ids, n, lo, hi);
        if (res) res = tr_fail(r, res, "tb_world_read_aabbs: %s", tb_world_last_error(r->world));
    }
    for (uint32_t i = 0; !res && i < n; i++) {
        if (finite_box(lo[i], hi[i])) add_box(out, lo[i], hi[i]);
        else out->has_plane = 1;
    }
    free(ids);
    free(lo);
    free(hi);
    return res;
}

int tr_camera_valid(const tr_camera* c)
{
    if (!(c->fov_y_degrees > 1.0f && c->fov_y_degrees < 179.0f)) return 0;
    if (c->automatic) return 1;
    const double d[3] = { c->target.x - c->eye.x, c->target.y - c->eye.y, c->target.z - c->eye.z };
    const double u[3] = { c->up.x, c->up.y, c->up.z };
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double cx = d[1] * u[2] - d[2] * u[1], cy = d[2] * u[0] - d[0] * u[2];
    double cz = d[0] * u[1] - d[1] * u[0];
    /* Finite, eye apart from target, up not along the view direction. */
    return isfinite(dd) && dd > 1e-12 && cx * cx + cy * cy + cz * cz > 1e-12 * dd;
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* Frame the scene's bounding sphere from a fixed direction, in both fields of view. */
static void automatic_camera(const tr_options* o, const tr_scene* s, tr_view* v)
{
    double centre[3] = { 0, 0, 0 }, radius = 5.0;
    if (s->has_bounds) {
        double half2 = 0;
        for (int i = 0; i < 3; i++) {
            centre[i] = 0.5 * (s->lo[i] + s->hi[i]);
            half2 += 0.25 * (s->hi[i] - s->lo[i]) * (s->hi[i] - s->lo[i]);
        }
        radius = fmax(sqrt(half2), 0.5);
    }
    double aspect = (double)o->width / o->height;
    double half_y = 0.5 * o->camera.fov_y_degrees * DEG;
    double half_x = atan(tan(half_y) * aspect);
    double distance = 1.05 * radius / sin(fmin(half_x, half_y));
    double dir[3] = { 1.0, 1.7, 1.3 };   /* from above: the inside of a container shows */
    normalize3(dir);
    tr_camera* c = &v->camera;
    *c = o->camera;
    c->target = (tb_vec3){ (float)centre[0], (float)centre[1], (float)centre[2] };
    c->eye = (tb_vec3){ (float)(centre[0] + dir[0] * distance), (float)(centre[1] + dir[1] * distance),
                        (float)(centre[2] + dir[2] * distance) };
    c->up = (tb_vec3){ 0, 1, 0 };
    v->near_plane = 0.02 * distance;
    v->far_plane = 20.0 * distance + 2.0 * radius;
}

/* view_proj = P * V, column-major. V: right-handed look-at. P: Vulkan perspective. */
static void build_matrix(const tr_view* v, double aspect, float out[16])
{
    const tr_camera* c = &v->camera;
    const double eye[3] = { c->eye.x, c->eye.y, c->eye.z };
    double f[3] = { c->target.x - eye[0], c->target.y - eye[1], c->target.z - eye[2] };
    const double up[3] = { c->up.x, c->up.y, c->up.z };
    double s[3], u[3];
    normalize3(f);
    tr_cross3(f, up, s);
    normalize3(s);
    tr_cross3(s, f, u);
    /* Rows of V. */
    const double view[4][4] = {
        { s[0], s[1], s[2], -tr_dot3(s, eye) },
        { u[0], u[1], u[2], -tr_dot3(u, eye) },
        { -f[0], -f[1], -f[2], tr_dot3(f, eye) },
        { 0, 0, 0, 1 },
    };
    double t = 1.0 / tan(0.5 * c->fov_y_degrees * DEG), n = v->near_plane, fa = v->far_plane;
    const double proj[4][4] = {
        { t / aspect, 0, 0, 0 },
        { 0, -t, 0, 0 },
        { 0, 0, fa / (n - fa), n * fa / (n - fa) },
        { 0, 0, -1, 0 },
    };
    for (int row = 0; row < 4; row++) {
        for (int col = 0; col < 4; col++) {
            double sum = 0;
            for (int k = 0; k < 4; k++) sum += proj[row][k] * view[k][col];
            out[col * 4 + row] = (float)sum;
        }
    }
}

void tr_view_resolve(const tr_options* o, const tr_scene* scene, tr_view* out)
{
    if (o->camera.automatic) {
        automatic_camera(o, scene, out);
    } else {
        out->camera = o->camera;
        const tb_vec3 e = o->camera.eye, t = o->camera.target;
        double d = sqrt((double)(t.x - e.x) * (t.x - e.x) + (double)(t.y - e.y) * (t.y - e.y) +
                        (double)(t.z - e.z) * (t.z - e.z));
        out->near_plane = 0.01 * d;
        out->far_plane = 100.0 * d;
    }
    out->floor_y = scene->has_bounds ? scene->lo[1] : 0.0;
    build_matrix(out, (double)o->width / o->height, out->view_proj);
}
