/* Convex hull shapes: their meshes, built on the host from the public API; and the
 * upkeep of every shape's own mesh, triangle-mesh shapes' (render_meshes.c) included, and
 * of the set of shape types that live (a unit mesh is drawn only while a shape of its type
 * lives).
 *
 * A hull body reads its shape slot from the world's body arrays (body_info.x), as every
 * body draw does; the hull's geometry is not in the arrays the renderer binds, so each hull
 * shape gets a mesh of its own here: tb_shape_get_hull_vertices gives the vertices in the
 * body frame, and tr_hull_triangles closes them into outward triangles (flat shaded).
 *
 * The shapes come from tb_world_shape_ids (a shape's slot is its id's index1 - 1). The
 * meshes are built again only when the shape slots, the live shape count or a known
 * shape's validity changed, so a frame normally costs one tb_shape_is_valid per shape.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

/* ---- convex hull of a point set, incremental ---------------------------------------- */

typedef struct hull_face {
    uint32_t v[3];      /* counter-clockwise seen from outside */
    double n[3], d;     /* unit outward normal, dot(n, x) = d on the face */
    int alive;
    uint32_t seen;      /* the insertion that found it visible */
} hull_face;

typedef struct hull_build {
    const double* p;    /* xyz per point */
    uint32_t n;
    hull_face* faces;
    uint32_t count, capacity;
    int32_t* owner;     /* n * n: face of directed edge a -> b, or -1 */
    double eps;
} hull_build;

static double distance_to_face(const hull_build* h, const hull_face* f, uint32_t point)
{
    return tr_dot3(f->n, h->p + 3 * point) - f->d;
}

/* Adds face (a, b, c) and claims its three directed edges; 0 when out of memory. */
static int add_face(hull_build* h, uint32_t a, uint32_t b, uint32_t c)
{
    if (h->count == h->capacity) {
        uint32_t cap = h->capacity ? 2 * h->capacity : 64;
        hull_face* grown = realloc(h->faces, cap * sizeof *grown);
        if (!grown) return 0;
        h->faces = grown;
        h->capacity = cap;
    }
    hull_face* f = &h->faces[h->count];
    f->v[0] = a; f->v[1] = b; f->v[2] = c;
    double e1[3], e2[3];
    tr_sub3(h->p + 3 * b, h->p + 3 * a, e1);
    tr_sub3(h->p + 3 * c, h->p + 3 * a, e2);
    tr_cross3(e1, e2, f->n);
    double len = sqrt(tr_dot3(f->n, f->n));
    for (int i = 0; i < 3; i++) f->n[i] = len > 0 ? f->n[i] / len : 0.0;
    f->d = tr_dot3(f->n, h->p + 3 * a);
    f->alive = 1;
    f->seen = 0;
    for (int i = 0; i < 3; i++) h->owner[f->v[i] * h->n + f->v[(i + 1) % 3]] = (int32_t)h->count;
    h->count++;
    return 1;
}

static uint32_t farthest(const hull_build* h, double (*measure)(const hull_build*, uint32_t,
                                                               const uint32_t*),
                         const uint32_t* from, double* best)
{
    uint32_t arg = 0;
    *best = -1.0;
    for (uint32_t i = 0; i < h->n; i++) {
        double m = measure(h, i, from);
        if (m > *best) { *best = m; arg = i; }
    }
    return arg;
}

static double from_point(const hull_build* h, uint32_t i, const uint32_t* s)
{
    double d[3];
    tr_sub3(h->p + 3 * i, h->p + 3 * s[0], d);
    return sqrt(tr_dot3(d, d));
}

static double from_line(const hull_build* h, uint32_t i, const uint32_t* s)
{
    double u[3], d[3], c[3];
    tr_sub3(h->p + 3 * s[1], h->p + 3 * s[0], u);
    tr_sub3(h->p + 3 * i, h->p + 3 * s[0], d);
    tr_cross3(u, d, c);
    return sqrt(tr_dot3(c, c) / tr_dot3(u, u));
}

static double from_plane(const hull_build* h, uint32_t i, const uint32_t* s)
{
    double u[3], v[3], n[3], d[3];
    tr_sub3(h->p + 3 * s[1], h->p + 3 * s[0], u);
    tr_sub3(h->p + 3 * s[2], h->p + 3 * s[0], v);
    tr_cross3(u, v, n);
    tr_sub3(h->p + 3 * i, h->p + 3 * s[0], d);
    return fabs(tr_dot3(n, d)) / sqrt(tr_dot3(n, n));
}

/* The first tetrahedron, its faces turned outwards; 0 when the points span no volume. */
static int start(hull_build* h)
{
    uint32_t s[4] = { 0, 0, 0, 0 };
    double extent;
    for (uint32_t i = 1; i < h->n; i++)
        if (h->p[3 * i] < h->p[3 * s[0]]) s[0] = i;
    s[1] = farthest(h, from_point, s, &extent);
    h->eps = 1e-7 * extent;
    double away;
    if (extent <= 0) return 0;
    s[2] = farthest(h, from_line, s, &away);
    if (away <= h->eps) return 0;
    s[3] = farthest(h, from_plane, s, &away);
    if (away <= h->eps) return 0;
    static const uint32_t sides[4][3] = { { 0, 1, 2 }, { 0, 3, 1 }, { 1, 3, 2 }, { 0, 2, 3 } };
    for (int k = 0; k < 4; k++) {
        uint32_t a = s[sides[k][0]], b = s[sides[k][1]], c = s[sides[k][2]];
        uint32_t other = s[6 - sides[k][0] - sides[k][1] - sides[k][2]];
        double e1[3], e2[3], n[3], d[3];
        tr_sub3(h->p + 3 * b, h->p + 3 * a, e1);
        tr_sub3(h->p + 3 * c, h->p + 3 * a, e2);
        tr_cross3(e1, e2, n);
        tr_sub3(h->p + 3 * other, h->p + 3 * a, d);
        int ok = tr_dot3(n, d) < 0 ? add_face(h, a, b, c) : add_face(h, a, c, b);
        if (!ok) return -1;
    }
    return 1;
}

/* Adds point p: the faces it sees go, and the horizon they leave is closed to p. */
static int insert(hull_build* h, uint32_t p, uint32_t round)
{
    uint32_t visible = 0, alive_before = h->count;
    for (uint32_t f = 0; f < alive_before; f++) {
        hull_face* face = &h->faces[f];
        if (face->alive && distance_to_face(h, face, p) > h->eps) {
            face->seen = round;
            visible++;
        }
    }
    if (!visible) return 1;
    /* Horizon: edges of visible faces whose neighbour across is not visible. */
    uint32_t* horizon = malloc(2 * 3 * (size_t)visible * sizeof *horizon);
    if (!horizon) return 0;
    uint32_t edges = 0;
    for (uint32_t f = 0; f < alive_before; f++) {
        hull_face* face = &h->faces[f];
        if (!face->alive || face->seen != round) continue;
        for (int i = 0; i < 3; i++) {
            uint32_t a = face->v[i], b = face->v[(i + 1) % 3];
            int32_t across = h->owner[b * h->n + a];
            if (across < 0 || h->faces[across].seen != round) {
                horizon[2 * edges] = a;
                horizon[2 * edges + 1] = b;
                edges++;
            }
        }
    }
    for (uint32_t f = 0; f < alive_before; f++) {
        hull_face* face = &h->faces[f];
        if (!face->alive || face->seen != round) continue;
        face->alive = 0;
        for (int i = 0; i < 3; i++) h->owner[face->v[i] * h->n + face->v[(i + 1) % 3]] = -1;
    }
    int ok = 1;
    for (uint32_t e = 0; e < edges && ok; e++) ok = add_face(h, horizon[2 * e], horizon[2 * e + 1], p);
    free(horizon);
    return ok;
}

uint32_t tr_hull_triangles(const tb_vec3* points, uint32_t count, uint32_t** out)
{
    *out = NULL;
    if (count < 4) return 0;
    hull_build h = { 0 };
    double* p = malloc(3 * (size_t)count * sizeof *p);
    h.owner = malloc((size_t)count * count * sizeof *h.owner);
    uint32_t triangles = 0;
    if (p && h.owner) {
        for (uint32_t i = 0; i < count; i++) {
            p[3 * i] = points[i].x; p[3 * i + 1] = points[i].y; p[3 * i + 2] = points[i].z;
        }
        h.p = p;
        h.n = count;
        for (size_t i = 0; i < (size_t)count * count; i++) h.owner[i] = -1;
        int ok = start(&h) == 1;
        for (uint32_t i = 0; ok && i < count; i++) ok = insert(&h, i, i + 1);
        uint32_t* tris = ok ? malloc(3 * (size_t)h.count * sizeof *tris) : NULL;
        for (uint32_t f = 0; tris && f < h.count; f++) {
            if (!h.faces[f].alive) continue;
            memcpy(tris + 3 * triangles, h.faces[f].v, sizeof h.faces[f].v);
            triangles++;
        }
        *out = tris;
        if (!tris) triangles = 0;
    }
    free(p);
    free(h.owner);
    free(h.faces);
    return triangles;
}

/* ---- the renderer's hull and triangle-mesh shapes' meshes --------------------------- */

/* A hull or triangle-mesh shape's flat-shaded mesh, three vertices per triangle. */
typedef struct shape_mesh {
    uint32_t slot;
    tb_shape_type type;
    tr_vertex* vertices;
    uint32_t vertex_count;
} shape_mesh;

/* One flat-shaded mesh for the hull `id`: three vertices per triangle, the triangle's
 * normal on each. */
static tb_result hull_mesh_of(tr_renderer* r, tb_shape_id id, shape_mesh* out)
{
    return tr_hull_vertices(r, id, &out->vertices, &out->vertex_count);
}

tb_result tr_hull_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** vertices,
                           uint32_t* vertex_count)
{
    *vertices = NULL;
    *vertex_count = 0;
    uint32_t count = 0;
    tb_result res = tb_shape_get_hull_vertices(r->world, id, NULL, 0, &count);
    if (res) return tr_fail(r, res, "tb_shape_get_hull_vertices: %s",
                            tb_world_last_error(r->world));
    tb_vec3* points = malloc((count ? count : 1) * sizeof *points);
    if (!points) return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for a hull");
    res = tb_shape_get_hull_vertices(r->world, id, points, count, &count);
    if (res) {
        free(points);
        return tr_fail(r, res, "tb_shape_get_hull_vertices: %s", tb_world_last_error(r->world));
    }
    uint32_t* tris = NULL;
    uint32_t n = tr_hull_triangles(points, count, &tris);
    tr_vertex* v = n ? malloc(3 * (size_t)n * sizeof *v) : NULL;
    for (uint32_t t = 0; t < n && v; t++)
        tr_flat_triangle(&points[tris[3 * t]], &points[tris[3 * t + 1]],
                         &points[tris[3 * t + 2]], &v[3 * t]);
    free(tris);
    free(points);
    if (n && !v) return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for a hull mesh");
    *vertices = v;
    *vertex_count = v ? 3 * n : 0;
    return TB_OK;
}

/* Whether the shapes the last scan saw are still the world's. */
static int scan_current(tr_renderer* r, uint32_t slots, uint32_t live)
{
    if (!r->hulls_scanned || slots != r->scan_slots || live != r->scan_live) return 0;
    for (uint32_t s = 0; s < slots; s++)
        if (r->shape_ids[s].index1 && !tb_shape_is_valid(r->world, r->shape_ids[s])) return 0;
    return 1;
}

static tb_result grow_slot_table(tr_renderer* r, uint32_t slots)
{
    if (slots <= r->shape_capacity) return TB_OK;
    tb_shape_id* ids = realloc(r->shape_ids, slots * sizeof *ids);
    if (!ids) return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for %u shape slots", slots);
    r->shape_ids = ids;
    r->shape_capacity = slots;
    return TB_OK;
}

/* Room for `count` draws of each kind, the old draws gone; the mesh lists follow. */
static tb_result reset_draws(tr_renderer* r, uint32_t count)
{
    free(r->hull_draws);
    free(r->mesh_draws);
    r->hull_draw_count = r->mesh_draw_count = 0;
    r->hull_draws = malloc((count ? count : 1) * sizeof *r->hull_draws);
    r->mesh_draws = malloc((count ? count : 1) * sizeof *r->mesh_draws);
    r->mesh_lists_stale = 1;
    if (!r->hull_draws || !r->mesh_draws)
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for shape draws");
    return TB_OK;
}

/* Each shape's mesh into the new buffers after the unit meshes, and its draw. */
static void place_meshes(tr_renderer* r, const shape_mesh* meshes, uint32_t count,
                         tr_vertex* v, uint32_t unit_vertices, uint32_t unit_indices)
{
    uint32_t first = 0;
    for (uint32_t i = 0; i < count; i++) {
        if (!meshes[i].vertex_count) continue;
        memcpy(v + unit_vertices + first, meshes[i].vertices,
               (size_t)meshes[i].vertex_count * sizeof *v);
        tr_shape_draw d = { meshes[i].slot, (uint32_t)meshes[i].type, unit_indices + first,
                            meshes[i].vertex_count, (int32_t)unit_vertices };
        if (meshes[i].type == TB_SHAPE_MESH) r->mesh_draws[r->mesh_draw_count++] = d;
        else r->hull_draws[r->hull_draw_count++] = d;
        first += meshes[i].vertex_count;
    }
}

/* New vertex and index buffers: the unit meshes as they are, then the shapes' meshes (three
 * vertices and indices 0, 1, 2, ... per triangle); one draw per shape. The old buffers go
 * (no frame is in flight: every frame waits for its fence). */
static tb_result upload(tr_renderer* r, shape_mesh* meshes, uint32_t count)
{
    const uint32_t unit_vertices = TR_UNIT_VERTICES, unit_indices = TR_UNIT_INDICES;
    uint64_t total = 0;
    for (uint32_t i = 0; i < count; i++) total += meshes[i].vertex_count;
    /* Draws take 32-bit index counts and offsets. */
    if (total > UINT32_MAX - unit_indices)
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "the hull and mesh shapes have %llu "
                       "triangles; the renderer draws at most %u", (unsigned long long)total / 3,
                       (UINT32_MAX - unit_indices) / 3);
    tb_result res = reset_draws(r, count);
    tr_buffer vertices = { 0 }, indices = { 0 };
    if (!res) res = tr_host_buffer(r, (unit_vertices + total) * sizeof(tr_vertex),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &vertices);
    if (!res) res = tr_host_buffer(r, (unit_indices + total) * sizeof(uint32_t),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &indices);
    if (res) {
        tr_buffer_destroy(r, &vertices);
        tr_buffer_destroy(r, &indices);
        return res;
    }
    uint32_t* idx = indices.mapped;
    memcpy(vertices.mapped, r->vertices.mapped, unit_vertices * sizeof(tr_vertex));
    memcpy(idx, r->indices.mapped, unit_indices * sizeof *idx);
    for (uint32_t i = 0; i < total; i++) idx[unit_indices + i] = i;
    place_meshes(r, meshes, count, vertices.mapped, unit_vertices, unit_indices);
    tr_buffer_destroy(r, &r->vertices);
    tr_buffer_destroy(r, &r->indices);
    r->vertices = vertices;
    r->indices = indices;
    return TB_OK;
}

/* The mesh of shape `id` in slot `s`, if it is a hull, a compound or a triangle mesh:
 * *made says. out->type is its type either way (TB_SHAPE_TYPE_FORCE_32 if unknown). */
static tb_result shape_mesh_of(tr_renderer* r, tb_shape_id id, uint32_t s, shape_mesh* out,
                               int* made)
{
    *made = 0;
    if (tb_shape_get_type(r->world, id, &out->type) != TB_OK) {
        out->type = TB_SHAPE_TYPE_FORCE_32;
        return TB_OK;
    }
    if (out->type != TB_SHAPE_HULL && out->type != TB_SHAPE_MESH &&
        out->type != TB_SHAPE_COMPOUND)
        return TB_OK;
    out->slot = s;
    *made = 1;
    if (out->type == TB_SHAPE_HULL) return hull_mesh_of(r, id, out);
    if (out->type == TB_SHAPE_COMPOUND)
        return tr_compound_vertices(r, id, &out->vertices, &out->vertex_count);
    return tr_mesh_shape_vertices(r, id, &out->vertices, &out->vertex_count);
}

static tb_result rescan(tr_renderer* r, uint32_t slots, uint32_t live)
{
    tb_result res = grow_slot_table(r, slots);
    if (res) return res;
    if (slots) memset(r->shape_ids, 0, slots * sizeof *r->shape_ids);
    tb_shape_id* live_ids = malloc((live ? live : 1) * sizeof *live_ids);
    shape_mesh* meshes = calloc(live ? live : 1, sizeof *meshes);
    if (!live_ids || !meshes) {
        free(live_ids);
        free(meshes);
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for shape meshes");
    }
    uint32_t found = tb_world_shape_ids(r->world, live_ids, live), count = 0;
    r->shape_types = 0;
    for (uint32_t i = 0; i < found && !res; i++) {
        uint32_t s = live_ids[i].index1 - 1;
        if (s >= slots) continue;   /* made after the bodies' arrays were read: next frame */
        r->shape_ids[s] = live_ids[i];
        int made;
        res = shape_mesh_of(r, live_ids[i], s, &meshes[count], &made);
        uint32_t type = (uint32_t)meshes[count].type;
        if (type < TR_SHAPE_TYPES) r->shape_types |= 1u << type;
        count += made;
    }
    if (!res) res = upload(r, meshes, count);
    for (uint32_t i = 0; i < count; i++) free(meshes[i].vertices);
    free(meshes);
    free(live_ids);
    if (res) return res;
    r->hulls_scanned = 1;
    r->scan_slots = slots;
    r->scan_live = live;
    return TB_OK;
}

tb_result tr_hulls_update(tr_renderer* r, const tb_vulkan_bodies* bodies)
{
    tb_world_stats stats;
    tb_result res = tb_world_get_stats(r->world, &stats);
    if (res) return tr_fail(r, res, "tb_world_get_stats: %s", tb_world_last_error(r->world));
    uint32_t slots = bodies->shape_slots;
    if (scan_current(r, slots, stats.shape_count)) return TB_OK;
    return rescan(r, slots, stats.shape_count);
}

void tr_hulls_destroy(tr_renderer* r)
{
    free(r->hull_draws);
    free(r->mesh_draws);
    free(r->shape_ids);
    r->hull_draws = NULL;
    r->mesh_draws = NULL;
    r->hull_draw_count = r->mesh_draw_count = 0;
    r->shape_ids = NULL;
    r->shape_capacity = 0;
    r->shape_types = 0;
    r->hulls_scanned = 0;
}
