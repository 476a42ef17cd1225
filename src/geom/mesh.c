/* Triangle meshes: input checks, degenerate triangles, active edges, the GPU image (see
 * mesh.h).
 *
 * Edges are matched by a counting sort on each edge's lower vertex index, then a sort of
 * each vertex's few edges by the higher index: O(n) for meshes of bounded vertex degree,
 * O(n log n) at worst (a fan of a million triangles round one vertex), and the same
 * result on every run. Geometry is computed in double from the float input, so the flags
 * depend on the mesh only, never on rounding along the way.
 */
#include "geom/mesh.h"
#include "geom/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* How far in front of a triangle's plane the other triangle's far vertex must be, per metre
 * of their shared edge, for the fold to count as concave: float input is only this exact,
 * and an edge left active where the fold is in doubt costs a small bump at worst, while
 * one wrongly inactive on a convex crease lets a body sink past it. */
#define CONCAVE_TOLERANCE 1.0e-6

/* Header size in uvec4: the nodes start right after it. */
#define HEADER_UVEC4 (sizeof(tb_gpu_mesh_header) / sizeof(tb_gpu_uvec4))

/* ---- input ---------------------------------------------------------------------------- */

/* The image is addressed in uvec4 by 32-bit offsets (tb_gpu_mesh_header.sections), so the
 * header, the 2n - 1 nodes, the n triangles and the vertices must all fit in 2^32 - 1. */
static uint64_t max_vertices(uint32_t triangle_count)
{
    uint64_t before = HEADER_UVEC4 + 3 * (uint64_t)triangle_count - 1;
    return UINT32_MAX - before;
}

static int check_counts(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                        uint32_t triangle_count, char* error, size_t error_size)
{
    if (!xyz || !indices)
        return tb_geom_fail(error, error_size, "a mesh needs its vertices and its triangles' indices, "
                    "not NULL");
    if (triangle_count == 0)
        return tb_geom_fail(error, error_size, "a mesh needs at least one triangle");
    if (triangle_count > TB_BVH_MAX_TRIANGLES)
        return tb_geom_fail(error, error_size, "a mesh has at most %u triangles, not %u",
                    (unsigned)TB_BVH_MAX_TRIANGLES, triangle_count);
    if (vertex_count > max_vertices(triangle_count))
        return tb_geom_fail(error, error_size, "a mesh of %u triangles has at most %llu vertices (its "
                    "GPU image is addressed by 32-bit offsets), not %u", triangle_count,
                    (unsigned long long)max_vertices(triangle_count), vertex_count);
    return 0;
}

static int check_values(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                        uint32_t triangle_count, char* error, size_t error_size)
{
    for (uint64_t i = 0; i < 3 * (uint64_t)triangle_count; i++)
        if (indices[i] >= vertex_count)
            return tb_geom_fail(error, error_size, "triangle %u's index %u is vertex %u, but the mesh "
                        "has %u vertices", (unsigned)(i / 3), (unsigned)(i % 3), indices[i],
                        vertex_count);
    for (uint32_t v = 0; v < vertex_count; v++)
        for (int a = 0; a < 3; a++) {
            float c = xyz[3 * (size_t)v + a];
            if (!isfinite(c))
                return tb_geom_fail(error, error_size, "vertex %u is not finite", v);
            if (fabs(c) > TB_MESH_MAX_COORDINATE)
                return tb_geom_fail(error, error_size, "vertex %u has a coordinate of %g m, beyond "
                            "the %g m a mesh vertex may lie from its origin", v, c,
                            TB_MESH_MAX_COORDINATE);
        }
    return 0;
}

/* ---- geometry, in double -------------------------------------------------------------- */

static void corner(const tb_mesh* m, uint32_t vertex, double p[3])
{
    const float* v = m->xyz + 3 * (size_t)vertex;
    p[0] = v[0];
    p[1] = v[1];
    p[2] = v[2];
}

static void sub(const double a[3], const double b[3], double r[3])
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Triangle t's corners and its normal cross(v1 - v0, v2 - v0), not normalized. */
static void triangle(const tb_mesh* m, uint32_t t, double v[3][3], double n[3])
{
    for (int k = 0; k < 3; k++) corner(m, m->indices[3 * (size_t)t + k], v[k]);
    double e1[3], e2[3];
    sub(v[1], v[0], e1);
    sub(v[2], v[0], e2);
    cross(e1, e2, n);
}

static int degenerate(const tb_mesh* m, uint32_t t)
{
    const uint32_t* i = m->indices + 3 * (size_t)t;
    if (i[0] == i[1] || i[1] == i[2] || i[2] == i[0]) return 1;
    double v[3][3], n[3], longest = 0;
    triangle(m, t, v, n);
    for (int k = 0; k < 3; k++) {
        double e[3];
        sub(v[(k + 1) % 3], v[k], e);
        longest = fmax(longest, dot(e, e));
    }
    return sqrt(dot(n, n)) < TB_MESH_DEGENERATE_RATIO * longest;
}

/* Flag the degenerate triangles, every other one with all its edges active for now;
 * returns how many are degenerate. */
static uint32_t flag_triangles(tb_mesh* m)
{
    uint32_t count = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        int bad = degenerate(m, t);
        m->flags[t] = bad ? TB_MESH_DEGENERATE
                          : TB_MESH_EDGE_ACTIVE_0 | TB_MESH_EDGE_ACTIVE_1 | TB_MESH_EDGE_ACTIVE_2;
        count += (uint32_t)bad;
    }
    return count;
}

/* Whether the edge triangles t and u share (t's edge k, run the other way by u) may be
 * inactive: the two are coplanar within TB_MESH_FLAT_COSINE, or u's far vertex lies in
 * front of t (a concave fold, which a body cannot touch from outside the faces). */
static int fold_hides_edge(const tb_mesh* m, uint32_t t, uint32_t k, uint32_t u, uint32_t j)
{
    double vt[3][3], vu[3][3], nt[3], nu[3];
    triangle(m, t, vt, nt);
    triangle(m, u, vu, nu);
    double lt = sqrt(dot(nt, nt)), lu = sqrt(dot(nu, nu));
    if (dot(nt, nu) >= TB_MESH_FLAT_COSINE * lt * lu) return 1;
    double edge[3], far[3];
    sub(vt[(k + 1) % 3], vt[k], edge);
    sub(vu[(j + 2) % 3], vt[k], far);
    return dot(nt, far) > CONCAVE_TOLERANCE * sqrt(dot(edge, edge)) * lt;
}

/* ---- adjacency ------------------------------------------------------------------------ */

/* An edge as sorted within its lower vertex's bucket: the higher vertex index above, the
 * edge's id (3 * triangle + k) below. */
static uint64_t edge_entry(const tb_mesh* m, uint32_t id, uint32_t* lower)
{
    uint32_t a = m->indices[id], b = m->indices[id - id % 3 + (id % 3 + 1) % 3];
    *lower = a < b ? a : b;
    return (uint64_t)(a < b ? b : a) << 32 | id;
}

static int compare_entries(const void* x, const void* y)
{
    uint64_t a = *(const uint64_t*)x, b = *(const uint64_t*)y;
    return (a > b) - (a < b);
}

/* Sort a bucket: insertion for the few edges most vertices have, qsort for big fans. */
static void sort_bucket(uint64_t* e, uint32_t n)
{
    if (n > 16) {
        qsort(e, n, sizeof *e, compare_entries);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        uint64_t x = e[i];
        uint32_t j = i;
        for (; j > 0 && e[j - 1] > x; j--) e[j] = e[j - 1];
        e[j] = x;
    }
}

/* A run of entries with the same two vertices: its edge stays active unless it is exactly
 * two triangles' edge, run in opposite directions, over a flat or concave fold. */
static void settle_edge(tb_mesh* m, const uint64_t* run, uint32_t n)
{
    if (n != 2) return;
    uint32_t e0 = (uint32_t)run[0], e1 = (uint32_t)run[1];
    uint32_t t = e0 / 3, k = e0 % 3, u = e1 / 3, j = e1 % 3;
    if (m->indices[e0] == m->indices[e1]) return;     /* same winding */
    if (!fold_hides_edge(m, t, k, u, j)) return;
    m->flags[t] &= ~(TB_MESH_EDGE_ACTIVE_0 << k);
    m->flags[u] &= ~(TB_MESH_EDGE_ACTIVE_0 << j);
}

/* Bucket the non-degenerate triangles' edges by their lower vertex (a counting sort),
 * sort each bucket by the higher vertex, and settle each run of equal edges. */
static int find_inactive_edges(tb_mesh* m)
{
    size_t edges = 3 * (size_t)(m->triangle_count - m->degenerate_count);
    uint32_t* start = calloc((size_t)m->vertex_count + 1, sizeof *start);
    uint64_t* entry = malloc(edges * sizeof *entry);
    if (!start || !entry) {
        free(start);
        free(entry);
        return -1;
    }
    for (uint32_t id = 0; id < 3 * m->triangle_count; id++) {
        uint32_t lower;
        if (m->flags[id / 3] & TB_MESH_DEGENERATE) continue;
        edge_entry(m, id, &lower);
        start[lower + 1]++;
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) start[v + 1] += start[v];
    for (uint32_t id = 0; id < 3 * m->triangle_count; id++) {
        uint32_t lower;
        if (m->flags[id / 3] & TB_MESH_DEGENERATE) continue;
        uint64_t e = edge_entry(m, id, &lower);
        entry[start[lower]++] = e;
    }
    /* start[v] is now where bucket v + 1 begins. */
    for (uint32_t v = 0, first = 0; v < m->vertex_count; first = start[v++]) {
        uint64_t* bucket = entry + first;
        uint32_t n = start[v] - first;
        sort_bucket(bucket, n);
        for (uint32_t i = 0, end; i < n; i = end) {
            for (end = i + 1; end < n && bucket[end] >> 32 == bucket[i] >> 32; end++) {}
            settle_edge(m, bucket + i, end - i);
        }
    }
    free(start);
    free(entry);
    return 0;
}

/* ---- build ---------------------------------------------------------------------------- */

int tb_mesh_flag_edges(tb_mesh* m)
{
    m->flags = malloc(((size_t)m->triangle_count + 1) * sizeof *m->flags);
    if (!m->flags) return -1;
    m->degenerate_count = flag_triangles(m);
    if (!find_inactive_edges(m)) return 0;
    free(m->flags);
    m->flags = NULL;
    return -1;
}

static void free_arrays(tb_mesh* m)
{
    free(m->xyz);
    free(m->indices);
    free(m->flags);
}

/* Copies of the input and room for the flags; -1 when memory runs out (nothing kept). */
static int copy_input(tb_mesh* m, const float* xyz, const uint32_t* indices)
{
    size_t coordinates = 3 * (size_t)m->vertex_count, corners = 3 * (size_t)m->triangle_count;
    m->xyz = malloc(coordinates * sizeof *m->xyz);
    m->indices = malloc(corners * sizeof *m->indices);
    m->flags = malloc(m->triangle_count * sizeof *m->flags);
    if (!m->xyz || !m->indices || !m->flags) {
        free_arrays(m);
        return -1;
    }
    memcpy(m->xyz, xyz, coordinates * sizeof *m->xyz);
    memcpy(m->indices, indices, corners * sizeof *m->indices);
    return 0;
}

int tb_mesh_build(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                  uint32_t triangle_count, tb_mesh* out, char* error, size_t error_size)
{
    if (check_counts(xyz, vertex_count, indices, triangle_count, error, error_size) ||
        check_values(xyz, vertex_count, indices, triangle_count, error, error_size))
        return -1;
    tb_mesh m = { .vertex_count = vertex_count, .triangle_count = triangle_count };
    if (copy_input(&m, xyz, indices))
        return tb_geom_fail(error, error_size, "no host memory for a mesh of %u triangles",
                    triangle_count);
    m.degenerate_count = flag_triangles(&m);
    if (m.degenerate_count == triangle_count) {
        free_arrays(&m);
        return tb_geom_fail(error, error_size, "every triangle of the mesh is degenerate (a repeated "
                    "vertex or no area), so nothing could touch it");
    }
    if (find_inactive_edges(&m)) {
        free_arrays(&m);
        return tb_geom_fail(error, error_size, "no host memory for the edges of a mesh of %u "
                    "triangles", triangle_count);
    }
    if (tb_bvh_build(m.xyz, vertex_count, m.indices, triangle_count, &m.bvh, error,
                     error_size)) {
        free_arrays(&m);
        return -1;
    }
    *out = m;
    return 0;
}

void tb_mesh_free(tb_mesh* mesh)
{
    tb_bvh_free(&mesh->bvh);
    free_arrays(mesh);
    memset(mesh, 0, sizeof *mesh);
}

/* ---- the GPU image -------------------------------------------------------------------- */

size_t tb_mesh_image_size(const tb_mesh* mesh)
{
    return HEADER_UVEC4 + (size_t)mesh->bvh.node_count + mesh->triangle_count +
           mesh->vertex_count;
}

static tb_gpu_mesh_header header(const tb_mesh* mesh)
{
    const tb_bvh* bvh = &mesh->bvh;
    double scale[3];
    tb_bvh_steps_per_metre(bvh, scale);
    uint32_t nodes = (uint32_t)HEADER_UVEC4, triangles = nodes + bvh->node_count;
    tb_gpu_mesh_header h = {
        .lo = { bvh->lo[0], bvh->lo[1], bvh->lo[2], tb_geom_bits_float(bvh->node_count) },
        .scale = { (float)scale[0], (float)scale[1], (float)scale[2],
                   tb_geom_bits_float(mesh->triangle_count) },
        .hi = { bvh->hi[0], bvh->hi[1], bvh->hi[2], tb_geom_bits_float(mesh->vertex_count) },
        .sections = { nodes, triangles, triangles + mesh->triangle_count, 0 },
    };
    return h;
}

void tb_mesh_pack(const tb_mesh* mesh, tb_gpu_uvec4* image)
{
    tb_gpu_mesh_header h = header(mesh);
    memcpy(image, &h, sizeof h);
    memcpy(image + h.sections.x, mesh->bvh.nodes, mesh->bvh.node_count * sizeof *mesh->bvh.nodes);
    tb_gpu_uvec4* triangles = image + h.sections.y;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        const uint32_t* i = mesh->indices + 3 * (size_t)t;
        triangles[t] = (tb_gpu_uvec4){ i[0], i[1], i[2], mesh->flags[t] };
    }
    tb_gpu_uvec4* vertices = image + h.sections.z;
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        const float* p = mesh->xyz + 3 * (size_t)v;
        vertices[v] = (tb_gpu_uvec4){ tb_geom_float_bits(p[0]), tb_geom_float_bits(p[1]), tb_geom_float_bits(p[2]), 0 };
    }
}
