/* Shapes through the API: checks, geometry and mass properties per unit mass; the world
 * keeps them (src/world/shapes.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/api.h"
#include "base/checks.h"
#include "world/world.h"

#define PI 3.14159265358979323846

tb_result tb_api_check_shape_def(tb_world* w, const tb_shape_def* def, tb_shape_id* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    if (!def || def->internal_cookie != TB_DEF_COOKIE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT,
                       "shape def was not initialised with tb_default_shape_def()");
    if (!isfinite(def->density) || def->density < 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "density must be finite and >= 0, not %g",
                       (double)def->density);
    if (!isfinite(def->friction) || def->friction < 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "friction must be finite and >= 0, not %g",
                       (double)def->friction);
    if (!isfinite(def->restitution) || def->restitution < 0 || def->restitution > 1)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "restitution must be in [0, 1], not %g",
                       (double)def->restitution);
    return TB_OK;
}

/* The caller's vertices as the packed xyz triples geometry code reads. */
static float* copy_points(const tb_vec3* points, uint32_t count)
{
    float* xyz = malloc(((size_t)count + 1) * 3 * sizeof *xyz);
    for (uint32_t i = 0; xyz && i < count; i++) {
        xyz[3 * i] = points[i].x;
        xyz[3 * i + 1] = points[i].y;
        xyz[3 * i + 2] = points[i].z;
    }
    return xyz;
}

tb_gpu_shape tb_api_gpu_shape(uint32_t type, tb_vec3 half, tb_gpu_vec4 params)
{
    tb_gpu_shape s;
    memset(&s, 0, sizeof s);
    s.aabb_half = (tb_gpu_vec4){ half.x, half.y, half.z, 0.0f };
    s.params = params;
    s.info.x = type;
    return s;
}

/* A shape whose local box [lo, hi] (body frame) need not be centred on the origin. */
static tb_gpu_shape boxed_shape(uint32_t type, const float lo[3], const float hi[3])
{
    tb_gpu_shape s = tb_api_gpu_shape(type, (tb_vec3){ (hi[0] - lo[0]) / 2, (hi[1] - lo[1]) / 2,
                                                (hi[2] - lo[2]) / 2 }, (tb_gpu_vec4){ 0 });
    s.aabb_center = (tb_gpu_vec4){ (hi[0] + lo[0]) / 2, (hi[1] + lo[1]) / 2,
                                   (hi[2] + lo[2]) / 2, 0 };
    return s;
}

tb_result tb_shape_create_sphere(tb_world* w, const tb_shape_def* def, float radius,
                                 tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    if (!isfinite(radius) || radius <= 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "sphere radius must be finite and > 0, "
                       "not %g", (double)radius);
    if (radius > TB_MAX_COORDINATE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "sphere radius must be at most "
                       "TB_MAX_COORDINATE (%g m), not %g", (double)TB_MAX_COORDINATE,
                       (double)radius);
    double r2 = (double)radius * radius;
    tb_shape_record rec = { .type = TB_SHAPE_SPHERE, .material = *def,
                            .volume = (float)(4.0 / 3.0 * PI * r2 * radius) };
    rec.unit_inertia = (tb_vec3){ (float)(0.4 * r2), (float)(0.4 * r2), (float)(0.4 * r2) };
    tb_gpu_shape gpu = tb_api_gpu_shape(TB_GPU_SHAPE_SPHERE, (tb_vec3){ radius, radius, radius },
                                 (tb_gpu_vec4){ radius, 0, 0, 0 });
    return tb_shapes_add(w, &rec, &gpu, out);
}

/* Hulls (boxes too) own their geometry; the hull table packs it for the GPU. */
static tb_result add_hull_shape(tb_world* w, tb_shape_record* rec, tb_gpu_shape* gpu,
                                tb_hull* hull, tb_shape_id* out)
{
    rec->hull = malloc(sizeof *rec->hull);
    if (!rec->hull) {
        tb_hull_free(hull);
        return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    }
    *rec->hull = *hull;
    return tb_shapes_add(w, rec, gpu, out);
}

tb_result tb_shape_create_box(tb_world* w, const tb_shape_def* def, tb_vec3 h, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    if (!tb_finite3(h) || h.x <= 0 || h.y <= 0 || h.z <= 0)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "box half extents must be finite and "
                       "> 0, not (%g, %g, %g)", (double)h.x, (double)h.y, (double)h.z);
    if (!tb_coordinates_within(h, TB_MAX_COORDINATE))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "box half extents must be at most "
                       "TB_MAX_COORDINATE (%g m), not (%g, %g, %g)", (double)TB_MAX_COORDINATE,
                       (double)h.x, (double)h.y, (double)h.z);
    double x2 = (double)h.x * h.x, y2 = (double)h.y * h.y, z2 = (double)h.z * h.z;
    tb_shape_record rec = { .type = TB_SHAPE_BOX, .material = *def,
                            .volume = (float)(8.0 * h.x * h.y * h.z) };
    rec.unit_inertia = (tb_vec3){ (float)((y2 + z2) / 3), (float)((x2 + z2) / 3),
                                  (float)((x2 + y2) / 3) };
    tb_gpu_shape gpu = tb_api_gpu_shape(TB_GPU_SHAPE_BOX, h, (tb_gpu_vec4){ h.x, h.y, h.z, 0 });
    tb_hull hull;
    char error[256];
    if (tb_hull_box((const float[3]){ h.x, h.y, h.z }, &hull, error, sizeof error))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "box: %s", error);
    return add_hull_shape(w, &rec, &gpu, &hull, out);
}

tb_result tb_shape_create_hull(tb_world* w, const tb_shape_def* def, const tb_vec3* points,
                               uint32_t count, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    if (!points) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "hull points are NULL");
    float* xyz = copy_points(points, count);
    if (!xyz) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_hull hull;
    char error[256];
    int failed = tb_hull_build(xyz, count, &hull, error, sizeof error);
    free(xyz);
    if (failed) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "convex hull: %s", error);
    tb_shape_record rec = { .type = TB_SHAPE_HULL, .material = *def, .volume = (float)hull.volume };
    rec.unit_inertia = (tb_vec3){ (float)hull.unit_inertia[0], (float)hull.unit_inertia[1],
                                  (float)hull.unit_inertia[2] };
    tb_gpu_shape gpu = boxed_shape(TB_GPU_SHAPE_HULL, hull.aabb_min, hull.aabb_max);
    return add_hull_shape(w, &rec, &gpu, &hull, out);
}

tb_result tb_shape_create_mesh(tb_world* w, const tb_shape_def* def, const tb_vec3* vertices,
                               uint32_t vertex_count, const uint32_t* indices,
                               uint32_t triangle_count, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    if (!vertices || !indices)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "mesh vertices or indices are NULL");
    tb_mesh* mesh = malloc(sizeof *mesh);
    float* xyz = mesh ? copy_points(vertices, vertex_count) : NULL;
    if (!xyz) {
        free(mesh);
        return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    }
    char error[256];
    int failed = tb_mesh_build(xyz, vertex_count, indices, triangle_count, mesh, error,
                               sizeof error);
    free(xyz);
    if (failed) {
        free(mesh);
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "triangle mesh: %s", error);
    }
    tb_shape_record rec = { .type = TB_SHAPE_MESH, .material = *def, .mesh = mesh };
    tb_gpu_shape gpu = boxed_shape(TB_GPU_SHAPE_MESH, mesh->bvh.lo, mesh->bvh.hi);
    return tb_shapes_add(w, &rec, &gpu, out);
}

tb_result tb_shape_create_heightfield(tb_world* w, const tb_shape_def* def, const float* heights,
                                      uint32_t count_x, uint32_t count_z, float cell_x,
                                      float cell_z, const uint8_t* holes, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    tb_heightfield* field = malloc(sizeof *field);
    if (!field) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    char error[256];
    if (tb_heightfield_build(heights, count_x, count_z, cell_x, cell_z, holes, field, error,
                             sizeof error)) {
        free(field);
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "heightfield: %s", error);
    }
    tb_shape_record rec = { .type = TB_SHAPE_HEIGHTFIELD, .material = *def, .heightfield = field };
    tb_gpu_shape gpu = boxed_shape(TB_GPU_SHAPE_HEIGHTFIELD, field->lo, field->hi);
    return tb_shapes_add(w, &rec, &gpu, out);
}

tb_result tb_shape_create_plane(tb_world* w, const tb_shape_def* def, tb_vec3 n, float offset,
                                tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (r) return r;
    double len = sqrt((double)n.x * n.x + (double)n.y * n.y + (double)n.z * n.z);
    if (!tb_finite3(n) || !isfinite(offset) || !(len > 1e-12) || !isfinite(len) ||
        fabsf(offset) > TB_MAX_COORDINATE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "plane needs a finite non-zero normal "
                       "and an offset within TB_MAX_COORDINATE (%g m)", (double)TB_MAX_COORDINATE);
    tb_shape_record rec = { .type = TB_SHAPE_PLANE, .material = *def };
    const float big = (float)TB_UNBOUNDED_EXTENT;
    tb_gpu_shape gpu = tb_api_gpu_shape(TB_GPU_SHAPE_PLANE, (tb_vec3){ big, big, big },
                                 (tb_gpu_vec4){ (float)(n.x / len), (float)(n.y / len),
                                                (float)(n.z / len), offset });
    return tb_shapes_add(w, &rec, &gpu, out);
}

tb_result tb_shape_destroy(tb_world* w, tb_shape_id id)
{
    uint32_t slot;
    tb_result r;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, &r);
    if (!s) return r;
    if (s->users)
        return tb_fail(&w->diag, TB_ERROR_IN_USE, "shape is used by %u bodies or compounds; "
                       "destroy them first",
                       s->users);
    tb_shapes_remove(w, slot);
    return TB_OK;
}

int tb_shape_is_valid(const tb_world* w, tb_shape_id id)
{
    if (!w || id.index1 == 0 || id.world != w->serial || id.index1 > w->shape_slots.used) return 0;
    const tb_shape_record* s = &w->shapes[id.index1 - 1];
    return s->alive && s->generation == id.generation;
}

uint32_t tb_world_shape_ids(const tb_world* w, tb_shape_id* out, uint32_t capacity)
{
    if (!w || !out) return 0;
    uint32_t n = 0;
    for (uint32_t s = 0; s < w->shape_slots.used && n < capacity; s++)
        if (w->shapes[s].alive)
            out[n++] = (tb_shape_id){ s + 1, w->serial, w->shapes[s].generation };
    return n;
}

tb_result tb_shape_get_type(const tb_world* cw, tb_shape_id id, tb_shape_type* out)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, &r);
    if (!s) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_shape_get_type: out is NULL");
    *out = s->type;
    return TB_OK;
}

/* The record of a shape of the given type, or an error naming what the id is instead. */
static const tb_shape_record* record_of(tb_world* w, tb_shape_id id, tb_shape_type type,
                                        const char* what, tb_result* r)
{
    uint32_t slot;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, r);
    if (!s) return NULL;
    if (s->type != type) {
        *r = tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "shape {%u, %u, %u} is not a %s",
                     id.index1, id.world, id.generation, what);
        return NULL;
    }
    return s;
}

tb_result tb_shape_get_sphere_radius(const tb_world* cw, tb_shape_id id, float* out)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_shape_record* s = record_of(w, id, TB_SHAPE_SPHERE, "sphere", &r);
    if (!s) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = w->gpu_shapes[id.index1 - 1].params.x;
    return TB_OK;
}

tb_result tb_shape_get_box_half_extents(const tb_world* cw, tb_shape_id id, tb_vec3* out)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_shape_record* s = record_of(w, id, TB_SHAPE_BOX, "box", &r);
    if (!s) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    tb_gpu_vec4 p = w->gpu_shapes[id.index1 - 1].params;
    *out = (tb_vec3){ p.x, p.y, p.z };
    return TB_OK;
}

static const tb_hull* hull_of(tb_world* w, tb_shape_id id, tb_result* r)
{
    const tb_shape_record* s = record_of(w, id, TB_SHAPE_HULL, "hull", r);
    return s ? s->hull : NULL;
}

tb_result tb_shape_get_hull_info(const tb_world* cw, tb_shape_id id, tb_hull_info* out)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_hull* h = hull_of(w, id, &r);
    if (!h) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    *out = (tb_hull_info){
        .vertex_count = h->vertex_count, .face_count = h->face_count,
        .edge_count = h->edge_count, .volume = (float)h->volume,
        .center_of_mass = { (float)h->center[0], (float)h->center[1], (float)h->center[2] },
        .principal_axes = { (float)h->rotation[0], (float)h->rotation[1], (float)h->rotation[2],
                            (float)h->rotation[3] },
        .unit_inertia = { (float)h->unit_inertia[0], (float)h->unit_inertia[1],
                          (float)h->unit_inertia[2] },
    };
    return TB_OK;
}

tb_result tb_shape_get_hull_vertices(const tb_world* cw, tb_shape_id id, tb_vec3* out,
                                     uint32_t capacity, uint32_t* count)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_hull* h = hull_of(w, id, &r);
    if (!h) return r;
    if (!count || (!out && capacity))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "count is NULL, or out is NULL "
                       "with a capacity");
    for (uint32_t i = 0; i < h->vertex_count && i < capacity; i++)
        out[i] = (tb_vec3){ h->vertices[i][0], h->vertices[i][1], h->vertices[i][2] };
    *count = h->vertex_count;
    return TB_OK;
}

static const tb_mesh* mesh_of(tb_world* w, tb_shape_id id, tb_result* r)
{
    const tb_shape_record* s = record_of(w, id, TB_SHAPE_MESH, "mesh", r);
    return s ? s->mesh : NULL;
}

tb_result tb_shape_get_mesh_info(const tb_world* cw, tb_shape_id id, tb_mesh_info* out)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_mesh* m = mesh_of(w, id, &r);
    if (!m) return r;
    if (!out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "out is NULL");
    uint32_t active = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (uint32_t k = 0; k < 3; k++) active += (m->flags[t] >> k) & 1u;
    *out = (tb_mesh_info){
        .vertex_count = m->vertex_count, .triangle_count = m->triangle_count,
        .degenerate_count = m->degenerate_count, .active_edge_count = active,
        .aabb_min = { m->bvh.lo[0], m->bvh.lo[1], m->bvh.lo[2] },
        .aabb_max = { m->bvh.hi[0], m->bvh.hi[1], m->bvh.hi[2] },
    };
    return TB_OK;
}

tb_result tb_shape_get_mesh_geometry(const tb_world* cw, tb_shape_id id, tb_vec3* vertices,
                                     uint32_t vertex_capacity, uint32_t* indices,
                                     uint32_t triangle_capacity, uint32_t* vertex_count,
                                     uint32_t* triangle_count)
{
    tb_world* w = (tb_world*)cw;
    tb_result r;
    const tb_mesh* m = mesh_of(w, id, &r);
    if (!m) return r;
    if (!vertex_count || !triangle_count || (!vertices && vertex_capacity) ||
        (!indices && triangle_capacity))
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "a count is NULL, or an array is "
                       "NULL with a capacity");
    for (uint32_t i = 0; i < m->vertex_count && i < vertex_capacity; i++)
        vertices[i] = (tb_vec3){ m->xyz[3 * i], m->xyz[3 * i + 1], m->xyz[3 * i + 2] };
    for (uint32_t t = 0; t < m->triangle_count && t < triangle_capacity; t++)
        for (uint32_t k = 0; k < 3; k++) indices[3 * t + k] = m->indices[3 * t + k];
    *vertex_count = m->vertex_count;
    *triangle_count = m->triangle_count;
    return TB_OK;
}
