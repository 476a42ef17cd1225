/* Convex hulls on the host: checks the input, runs quickhull (quickhull.c), finds the mass
 * properties and principal frame (hull_mass.c) and writes the tb_hull the GPU data is
 * made from: float vertices and planes, polygon faces and the unique edges. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "geom/hull_mesh.h"
#include "layout.h"

#define NO_FACE UINT16_MAX

void tb_hull_free(tb_hull* hull)
{
    if (!hull) return;
    free(hull->vertices);
    free(hull->planes);
    free(hull->faces);
    free(hull->indices);
    free(hull->edges);
    memset(hull, 0, sizeof *hull);
}

static int check_limits(const tb_hull_mesh* m, char* error, size_t error_size)
{
    if (m->vertex_count > TB_HULL_MAX_VERTICES) {
        snprintf(error, error_size, "the hull has %u vertices, more than the GPU limit "
                 "TB_HULL_MAX_VERTICES (%d)", m->vertex_count, TB_HULL_MAX_VERTICES);
        return -1;
    }
    if (m->face_count > TB_HULL_MAX_FACES) {
        snprintf(error, error_size, "the hull has %u faces, more than the GPU limit "
                 "TB_HULL_MAX_FACES (%d)", m->face_count, TB_HULL_MAX_FACES);
        return -1;
    }
    for (uint32_t f = 0; f < m->face_count; f++)
        if (m->faces[f].count > TB_HULL_MAX_FACE_VERTICES) {
            snprintf(error, error_size, "hull face %u has %u vertices, more than the GPU limit "
                     "TB_HULL_MAX_FACE_VERTICES (%d)", f, m->faces[f].count,
                     TB_HULL_MAX_FACE_VERTICES);
            return -1;
        }
    return 0;
}

/* The unit plane of face f (tb_hull_mesh_face_normal) in floats. */
static void face_plane(const tb_hull_mesh* m, uint32_t f, float plane[4])
{
    double n[3], c[3];
    tb_hull_mesh_face_normal(m, f, n, c);
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) plane[k] = (float)(n[k] / len);
    plane[3] = (float)((n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / len);
}

/* Each undirected edge once: made when met as v0 < v1 (that face is `left`), completed
 * when met reversed (`right`). Fails if the faces do not pair every edge exactly. */
static int build_edges(const tb_hull_mesh* m, tb_hull_edge* edges, uint32_t* count)
{
    uint32_t e = 0;
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t f = 0; f < m->face_count; f++)
            for (uint32_t i = 0; i < m->faces[f].count; i++) {
                const uint32_t* loop = m->indices + m->faces[f].first;
                uint32_t a = loop[i], b = loop[(i + 1) % m->faces[f].count];
                if (pass == 0 && a < b)
                    edges[e++] = (tb_hull_edge){ (uint16_t)a, (uint16_t)b, (uint16_t)f, NO_FACE };
                if (pass == 1 && a > b) {
                    uint32_t j = 0;
                    while (j < e && !(edges[j].v0 == b && edges[j].v1 == a)) j++;
                    if (j == e || edges[j].right != NO_FACE) return -1;
                    edges[j].right = (uint16_t)f;
                }
            }
    for (uint32_t j = 0; j < e; j++)
        if (edges[j].right == NO_FACE) return -1;
    *count = e;
    return 0;
}

static void hull_aabb(tb_hull* h)
{
    glm_vec3_copy(h->vertices[0], h->aabb_min);
    glm_vec3_copy(h->vertices[0], h->aabb_max);
    for (uint32_t i = 1; i < h->vertex_count; i++) {
        glm_vec3_minv(h->aabb_min, h->vertices[i], h->aabb_min);
        glm_vec3_maxv(h->aabb_max, h->vertices[i], h->aabb_max);
    }
}

int tb_hull_fill(const tb_hull_mesh* m, tb_hull* h, char* error, size_t error_size)
{
    if (check_limits(m, error, error_size)) return -1;
    memset(h, 0, sizeof *h);
    h->vertices = malloc(m->vertex_count * sizeof *h->vertices);
    h->planes = malloc(m->face_count * sizeof *h->planes);
    h->faces = malloc(m->face_count * sizeof *h->faces);
    h->indices = malloc(m->index_count * sizeof *h->indices);
    h->edges = malloc(m->index_count * sizeof *h->edges); /* twice what a closed hull needs */
    if (!h->vertices || !h->planes || !h->faces || !h->indices || !h->edges) {
        tb_hull_free(h);
        snprintf(error, error_size, "out of memory while building a convex hull");
        return -1;
    }
    if (build_edges(m, h->edges, &h->edge_count)) {
        tb_hull_free(h);
        snprintf(error, error_size, "could not build a consistent convex hull from these "
                 "points (faces do not pair up along edges)");
        return -1;
    }
    h->vertex_count = m->vertex_count;
    h->face_count = m->face_count;
    h->index_count = m->index_count;
    for (uint32_t i = 0; i < m->vertex_count; i++)
        for (int k = 0; k < 3; k++) h->vertices[i][k] = (float)m->vertices[i][k];
    for (uint32_t f = 0; f < m->face_count; f++) face_plane(m, f, h->planes[f]);
    memcpy(h->faces, m->faces, m->face_count * sizeof *h->faces);
    for (uint32_t i = 0; i < m->index_count; i++) h->indices[i] = (uint16_t)m->indices[i];
    hull_aabb(h);
    return 0;
}

/* ---- hull of a point cloud ------------------------------------------------------------ */

static int check_points(const float* xyz, uint32_t count, char* error, size_t error_size)
{
    if (count < 4) {
        snprintf(error, error_size, "a convex hull needs at least 4 points, got %u", count);
        return -1;
    }
    if (!xyz) {
        snprintf(error, error_size, "no points given for the convex hull");
        return -1;
    }
    for (uint32_t i = 0; i < count; i++)
        if (!isfinite(xyz[3 * i]) || !isfinite(xyz[3 * i + 1]) || !isfinite(xyz[3 * i + 2])) {
            snprintf(error, error_size, "hull point %u is not finite (%g, %g, %g)", i,
                     (double)xyz[3 * i], (double)xyz[3 * i + 1], (double)xyz[3 * i + 2]);
            return -1;
        }
    return 0;
}

/* The points in double, moved so that their bounding box is centred on the origin (mid),
 * and the plane tolerance. The input and the output are float, so detail finer than a few
 * float roundings of the cloud's extent is not there to keep: a point within
 * eps = 3 * FLT_EPSILON * (max|x| + max|y| + max|z|) of a plane (Gregorius's bound, with
 * float's epsilon because floats are what the points were and will be) counts as on it.
 * Centring first makes that tolerance follow the cloud's size, not its distance from the
 * origin. */
static double centred_points(const float* xyz, uint32_t count, double (*p)[3], double mid[3])
{
    double lo[3], hi[3], ext[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; k++) lo[k] = hi[k] = xyz[k];
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], xyz[3 * i + k]);
            hi[k] = fmax(hi[k], xyz[3 * i + k]);
        }
    for (int k = 0; k < 3; k++) mid[k] = 0.5 * (lo[k] + hi[k]);
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            p[i][k] = xyz[3 * i + k] - mid[k];
            ext[k] = fmax(ext[k], fabs(p[i][k]));
        }
    return 3 * FLT_EPSILON * (ext[0] + ext[1] + ext[2]);
}

typedef struct hull_mass { double volume, center[3], rotation[4], unit_inertia[3]; } hull_mass;

/* Mass properties of the mesh, then the mesh moved into its principal frame: translated by
 * minus the centre of mass and rotated by the inverse of the eigenbasis of the inertia. */
static hull_mass principal_frame(tb_hull_mesh* m, const double mid[3])
{
    hull_mass r;
    double c[3], cov[3][3], inertia[3][3], axes[3][3], moments[3];
    tb_hull_mass(m, &r.volume, c, cov);
    double trace = cov[0][0] + cov[1][1] + cov[2][2];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) inertia[i][j] = (i == j ? trace : 0) - cov[i][j];
    tb_sym3_eigen(inertia, axes, moments);
    tb_mat3_to_quat(axes, r.rotation);
    for (int i = 0; i < 3; i++) {
        r.center[i] = mid[i] + c[i];
        r.unit_inertia[i] = moments[i] / r.volume;
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        double d[3], *x = m->vertices[v];
        for (int k = 0; k < 3; k++) d[k] = x[k] - c[k];
        for (int k = 0; k < 3; k++)
            x[k] = axes[0][k] * d[0] + axes[1][k] * d[1] + axes[2][k] * d[2];
    }
    return r;
}

static void set_mass(tb_hull* h, const hull_mass* m)
{
    h->volume = m->volume;
    memcpy(h->center, m->center, sizeof h->center);
    memcpy(h->rotation, m->rotation, sizeof h->rotation);
    memcpy(h->unit_inertia, m->unit_inertia, sizeof h->unit_inertia);
}

int tb_hull_build(const float* xyz, uint32_t count, tb_hull* out, char* error, size_t error_size)
{
    if (check_points(xyz, count, error, error_size)) return -1;
    double (*p)[3] = malloc(count * sizeof *p), mid[3];
    if (!p) {
        snprintf(error, error_size, "out of memory while building a convex hull");
        return -1;
    }
    double eps = centred_points(xyz, count, p, mid);
    tb_hull_mesh mesh;
    /* Points noisy at about the tolerance can make regions flat within it yet not convex;
     * a coarser tolerance (up to 16 times, still under 2e-5 of the cloud's extent) merges the
     * noise into the faces instead of refusing the cloud. */
    int rc = TB_QUICKHULL_NOISY;
    for (double scale = 1; rc == TB_QUICKHULL_NOISY && scale <= 16; scale *= 4)
        rc = tb_quickhull((const double (*)[3])p, count, eps * scale, &mesh, error, error_size);
    free(p);
    if (rc) return -1;
    hull_mass mass = principal_frame(&mesh, mid);
    tb_hull h;
    rc = tb_hull_fill(&mesh, &h, error, error_size);
    tb_hull_mesh_free(&mesh);
    if (rc) return -1;
    set_mass(&h, &mass);
    *out = h;
    return 0;
}

/* ---- box ------------------------------------------------------------------------------ */

/* Corner i has sign bit k set where its coordinate k is +h[k]; each face lists its
 * corners counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z. */
static const uint32_t box_loops[6][4] = {
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 },
};

int tb_hull_box(const float h[3], tb_hull* out, char* error, size_t error_size)
{
    for (int k = 0; k < 3; k++)
        if (!h || !isfinite(h[k]) || !(h[k] > 0)) {
            snprintf(error, error_size, "box half extents must be finite and positive");
            return -1;
        }
    double v[8][3];
    tb_hull_face faces[6];
    uint32_t indices[24];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) v[i][k] = (i >> k & 1) ? h[k] : -(double)h[k];
    for (int f = 0; f < 6; f++) {
        faces[f] = (tb_hull_face){ 4 * (uint32_t)f, 4 };
        memcpy(indices + 4 * f, box_loops[f], sizeof box_loops[f]);
    }
    tb_hull_mesh mesh = { 8, 6, 24, v, faces, indices };
    tb_hull hull;
    if (tb_hull_fill(&mesh, &hull, error, error_size)) return -1;
    double x2 = (double)h[0] * h[0], y2 = (double)h[1] * h[1], z2 = (double)h[2] * h[2];
    hull_mass m = { 8.0 * h[0] * h[1] * h[2], { 0, 0, 0 }, { 0, 0, 0, 1 },
                    { (y2 + z2) / 3, (x2 + z2) / 3, (x2 + y2) / 3 } };
    set_mass(&hull, &m);
    *out = hull;
    return 0;
}
