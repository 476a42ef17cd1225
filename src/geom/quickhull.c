/* Quickhull in three dimensions, after Barber, Dobkin and Huhdanpaa, "The Quickhull
 * Algorithm for Convex Hulls" (1996), with the robustness advice of Dirk Gregorius's GDC
 * 2014 talk "Implementing Quickhull": one distance tolerance for every plane test, only
 * points clearly outside the hull are ever added, and nearly coplanar faces are merged.
 *
 * The hull grows as a triangle mesh. Each face keeps a list of the points outside it (its
 * conflict list); the farthest such point (the eye) is added by removing the faces it sees
 * and joining their boundary (the horizon) to the eye. A point is outside a face only when
 * it is more than eps above its plane, so every new triangle stands more than eps above its
 * horizon edge and is never a sliver whose normal would be noise. Because points within eps
 * are not added, the finished triangle mesh is convex up to eps; triangles that lie within
 * eps of a common plane are then merged into polygons, and vertices that are corners of
 * fewer than three polygons (inside a face, or in the middle of a straight edge) dropped.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geom/hull_mesh.h"

#define NONE UINT32_MAX

typedef struct qh_face {
    uint32_t v[3];     /* point indices, counter-clockwise seen from outside */
    uint32_t adj[3];   /* the face across edge v[i] -> v[(i + 1) % 3] */
    double n[3], d;    /* outward unit normal and offset */
    double area;       /* twice the area: merging starts from the largest faces */
    uint32_t conflict; /* first point of the conflict list, NONE when empty */
    uint32_t mark;     /* == stamp: in the region the current eye sees (or current cluster) */
    uint32_t seen;     /* == stamp: tested and found not visible */
    uint32_t cluster;  /* the merged polygon this triangle belongs to */
    int alive;
} qh_face;

typedef struct qh {
    const double (*p)[3];
    uint32_t n;
    double eps;
    qh_face* f;
    uint32_t nf, cap, stamp;
    uint32_t* queue;   /* faces to visit, 3 * cap + 3 */
    uint32_t* region;  /* faces the eye sees, cap */
    uint32_t* next;    /* per point: next point of the same conflict list */
    uint32_t* vmark;   /* per point: == stamp when a vertex of the visible region */
    uint32_t* hnext;   /* per point: the horizon edge that starts there */
    uint32_t* hz;      /* horizon edges (region face * 3 + edge), then their order */
    uint32_t* corner;  /* per point: up to two polygons it is on, and how many (max 3) */
} qh;

/* Small double-precision vector helpers: cglm, the project's vector library, works in
 * float, and the plane tests here need double to stay far below the tolerance. */
static void v3_sub(const double a[3], const double b[3], double r[3])
{
    r[0] = a[0] - b[0]; r[1] = a[1] - b[1]; r[2] = a[2] - b[2];
}

static double v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void v3_cross(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static double qh_dist(const qh* q, const qh_face* f, uint32_t point)
{
    return v3_dot(f->n, q->p[point]) - f->d;
}

/* The plane of a triangle from its two shorter edges: their cross product has the smallest
 * rounding error relative to the area (the angle between them is the largest). */
static void qh_plane(const qh* q, qh_face* f)
{
    double e[3][3], len[3], c[3];
    for (int i = 0; i < 3; i++) {
        v3_sub(q->p[f->v[(i + 1) % 3]], q->p[f->v[i]], e[i]);
        len[i] = v3_dot(e[i], e[i]);
    }
    int longest = len[0] > len[1] ? (len[0] > len[2] ? 0 : 2) : (len[1] > len[2] ? 1 : 2);
    v3_cross(e[(longest + 1) % 3], e[(longest + 2) % 3], c);
    f->area = sqrt(v3_dot(c, c));
    for (int i = 0; i < 3; i++) f->n[i] = f->area > 0 ? c[i] / f->area : 0;
    double mid[3];
    for (int i = 0; i < 3; i++)
        mid[i] = (q->p[f->v[0]][i] + q->p[f->v[1]][i] + q->p[f->v[2]][i]) / 3;
    f->d = v3_dot(f->n, mid);
}

static int qh_reserve(qh* q, uint32_t extra)
{
    if (q->nf + extra <= q->cap) return 0;
    uint32_t cap = 2 * (q->nf + extra);
    qh_face* f = realloc(q->f, cap * sizeof *f);
    if (f) q->f = f;
    uint32_t* queue = f ? realloc(q->queue, (3 * (size_t)cap + 3) * sizeof *queue) : NULL;
    if (queue) q->queue = queue;
    uint32_t* region = queue ? realloc(q->region, cap * sizeof *region) : NULL;
    if (!region) return -1;
    q->region = region;
    q->cap = cap;
    return 0;
}

static uint32_t qh_add_face(qh* q, uint32_t a, uint32_t b, uint32_t c)
{
    qh_face* f = &q->f[q->nf];
    memset(f, 0, sizeof *f);
    f->v[0] = a; f->v[1] = b; f->v[2] = c;
    f->adj[0] = f->adj[1] = f->adj[2] = NONE;
    f->conflict = NONE;
    f->alive = 1;
    qh_plane(q, f);
    return q->nf++;
}

/* Give a point to the first face in [first, last) it is clearly outside of; a point
 * outside none of them is inside the hull (or within eps of it) and is dropped for good. */
static void qh_assign(qh* q, uint32_t point, uint32_t first, uint32_t last)
{
    for (uint32_t i = first; i < last; i++) {
        qh_face* f = &q->f[i];
        if (f->alive && qh_dist(q, f, point) > q->eps) {
            q->next[point] = f->conflict;
            f->conflict = point;
            return;
        }
    }
}

/* ---- the first tetrahedron ------------------------------------------------------------ */

static double line_dist(const double a[3], const double b[3], const double p[3])
{
    double ab[3], ap[3], c[3];
    v3_sub(b, a, ab);
    v3_sub(p, a, ap);
    v3_cross(ab, ap, c);
    return sqrt(v3_dot(c, c) / v3_dot(ab, ab));
}

/* The two farthest apart of the six points extreme along an axis. */
static void extreme_pair(const qh* q, uint32_t* a, uint32_t* b)
{
    uint32_t ext[6] = { 0, 0, 0, 0, 0, 0 };
    for (uint32_t i = 1; i < q->n; i++)
        for (int k = 0; k < 3; k++) {
            if (q->p[i][k] < q->p[ext[2 * k]][k]) ext[2 * k] = i;
            if (q->p[i][k] > q->p[ext[2 * k + 1]][k]) ext[2 * k + 1] = i;
        }
    double best = -1;
    for (int i = 0; i < 6; i++)
        for (int j = i + 1; j < 6; j++) {
            double d[3];
            v3_sub(q->p[ext[i]], q->p[ext[j]], d);
            if (v3_dot(d, d) > best) { best = v3_dot(d, d); *a = ext[i]; *b = ext[j]; }
        }
}

/* Pick four points spanning the largest volume we can find cheaply; fails, saying why,
 * when the cloud is (within eps) a point, a line or a plane. */
static int qh_simplex(qh* q, uint32_t t[4], char* error, size_t error_size)
{
    extreme_pair(q, &t[0], &t[1]);
    double d[3];
    v3_sub(q->p[t[0]], q->p[t[1]], d);
    if (sqrt(v3_dot(d, d)) <= q->eps) {
        snprintf(error, error_size, "the points span no volume: they are all (nearly) identical");
        return -1;
    }
    double best = -1;
    for (uint32_t i = 0; i < q->n; i++) {
        double l = line_dist(q->p[t[0]], q->p[t[1]], q->p[i]);
        if (l > best) { best = l; t[2] = i; }
    }
    if (best <= q->eps) {
        snprintf(error, error_size, "the points span no volume: they are all (nearly) collinear");
        return -1;
    }
    qh_face tri = { .v = { t[0], t[1], t[2] } };
    qh_plane(q, &tri);
    best = -1;
    for (uint32_t i = 0; i < q->n; i++) {
        double h = fabs(qh_dist(q, &tri, i));
        if (h > best) { best = h; t[3] = i; }
    }
    if (best <= q->eps) {
        snprintf(error, error_size, "the points span no volume: they are all (nearly) coplanar");
        return -1;
    }
    if (qh_dist(q, &tri, t[3]) > 0) { uint32_t s = t[1]; t[1] = t[2]; t[2] = s; }
    return 0;
}

/* Link each face's edges to the faces that hold the same edge reversed (small meshes). */
static void qh_link(qh* q, uint32_t first, uint32_t last)
{
    for (uint32_t i = first; i < last; i++)
        for (int k = 0; k < 3; k++)
            for (uint32_t j = first; j < last; j++)
                for (int m = 0; m < 3; m++)
                    if (q->f[j].v[m] == q->f[i].v[(k + 1) % 3] &&
                        q->f[j].v[(m + 1) % 3] == q->f[i].v[k])
                        q->f[i].adj[k] = j;
}

/* The tetrahedron t (t[3] below the plane of t[0], t[1], t[2]), every other point given to
 * a face it is outside of. */
static int qh_start(qh* q, const uint32_t t[4])
{
    if (qh_reserve(q, 4)) return -1;
    qh_add_face(q, t[0], t[1], t[2]);
    qh_add_face(q, t[1], t[0], t[3]);
    qh_add_face(q, t[2], t[1], t[3]);
    qh_add_face(q, t[0], t[2], t[3]);
    qh_link(q, 0, 4);
    for (uint32_t i = 0; i < q->n; i++)
        if (i != t[0] && i != t[1] && i != t[2] && i != t[3]) qh_assign(q, i, 0, 4);
    return 0;
}

/* ---- adding one point ----------------------------------------------------------------- */

static void qh_join(qh* q, uint32_t face, uint32_t* r, uint32_t* tail)
{
    qh_face* f = &q->f[face];
    f->mark = q->stamp;
    q->region[(*r)++] = face;
    for (int k = 0; k < 3; k++) {
        q->vmark[f->v[k]] = q->stamp;
        if (q->f[f->adj[k]].mark != q->stamp) q->queue[(*tail)++] = f->adj[k];
    }
}

/* Grow the set of faces the eye sees from one it surely sees, keeping the set a disc so
 * that its boundary is one simple loop even when tolerance makes visibility inconsistent:
 * a face touching the set along one edge joins only if its third vertex is not already on
 * the set (that would pinch the boundary); it may join later, through a second edge. */
static uint32_t qh_region(qh* q, uint32_t start, uint32_t eye)
{
    uint32_t r = 0, head = 0, tail = 0;
    qh_join(q, start, &r, &tail);
    while (head < tail) {
        uint32_t g = q->queue[head++];
        qh_face* f = &q->f[g];
        if (f->mark == q->stamp || f->seen == q->stamp) continue;
        if (qh_dist(q, f, eye) <= q->eps) { f->seen = q->stamp; continue; }
        int shared = 0, edge = 0;
        for (int k = 0; k < 3; k++)
            if (q->f[f->adj[k]].mark == q->stamp) { shared++; edge = k; }
        if (shared == 3) continue;
        if (shared == 1 && q->vmark[f->v[(edge + 2) % 3]] == q->stamp) continue;
        qh_join(q, g, &r, &tail);
    }
    return r;
}

/* Whether the triangle (a, b, eye) would fold over the face across edge a -> b of region
 * face r: the eye above that face's plane, and its far corner above the new triangle's. */
static int qh_folds(const qh* q, const qh_face* r, int k, uint32_t eye)
{
    const qh_face* out = &q->f[r->adj[k]];
    if (qh_dist(q, out, eye) <= 0) return 0;
    qh_face tri = { .v = { r->v[k], r->v[(k + 1) % 3], eye } };
    qh_plane(q, &tri);
    for (int m = 0; m < 3; m++)
        if (qh_dist(q, &tri, out->v[m]) > q->eps) return 1;
    return 0;
}

/* Faces the eye sees within tolerance only (so qh_region left them) but which the new
 * faces would fold over: they join the region too, as long as it stays a disc. Without
 * this, thin triangles along a noisy edge can end up facing inwards. */
static uint32_t qh_unfold(qh* q, uint32_t r, uint32_t eye)
{
    for (int grew = 1; grew;) {
        grew = 0;
        for (uint32_t i = 0; i < r; i++) {
            const qh_face* f = &q->f[q->region[i]];
            for (int k = 0; k < 3; k++) {
                qh_face* g = &q->f[f->adj[k]];
                if (g->mark == q->stamp || !qh_folds(q, f, k, eye)) continue;
                int shared = 0, edge = 0;
                for (int m = 0; m < 3; m++)
                    if (q->f[g->adj[m]].mark == q->stamp) { shared++; edge = m; }
                if (shared == 3 || (shared == 1 && q->vmark[g->v[(edge + 2) % 3]] == q->stamp))
                    continue;
                uint32_t tail = 0;
                qh_join(q, f->adj[k], &r, &tail);
                grew = 1;
                break;
            }
        }
    }
    return r;
}

/* The region's boundary edges in loop order, into q->hz (as face * 3 + edge). Returns their
 * number, or 0 when they do not form one loop (never expected: qh_region keeps a disc). */
static uint32_t qh_horizon(qh* q, uint32_t r)
{
    uint32_t h = 0;
    for (uint32_t i = 0; i < r; i++) {
        const qh_face* f = &q->f[q->region[i]];
        for (int k = 0; k < 3; k++)
            if (q->f[f->adj[k]].mark != q->stamp) {
                q->hnext[f->v[k]] = h;
                q->hz[h++] = q->region[i] * 3 + (uint32_t)k;
            }
    }
    uint32_t* order = q->hz + h, e = 0;
    for (uint32_t i = 0; i < h; i++) {
        order[i] = q->hz[e];
        const qh_face* f = &q->f[q->hz[e] / 3];
        uint32_t end = f->v[(q->hz[e] % 3 + 1) % 3];
        e = q->hnext[end];
        if (e >= h || q->f[q->hz[e] / 3].v[q->hz[e] % 3] != end) return 0;
    }
    if (e != 0) return 0;
    memmove(q->hz, order, h * sizeof *order);
    return h;
}

/* A fan of triangles from the eye to each horizon edge, stitched to each other and to the
 * faces across the horizon. */
static void qh_fan(qh* q, uint32_t h, uint32_t eye)
{
    uint32_t base = q->nf;
    for (uint32_t j = 0; j < h; j++) {
        const qh_face* old = &q->f[q->hz[j] / 3];
        uint32_t k = q->hz[j] % 3, a = old->v[k], b = old->v[(k + 1) % 3];
        uint32_t out = old->adj[k], nf = qh_add_face(q, a, b, eye);
        qh_face* f = &q->f[nf];
        f->adj[0] = out;
        f->adj[1] = base + (j + 1) % h;
        f->adj[2] = base + (j + h - 1) % h;
        for (int m = 0; m < 3; m++)
            if (q->f[out].v[m] == b && q->f[out].v[(m + 1) % 3] == a) q->f[out].adj[m] = nf;
    }
}

/* Returns 0, -1 when out of memory, -2 when the horizon is broken. */
static int qh_add_point(qh* q, uint32_t start, uint32_t eye)
{
    q->stamp++;
    uint32_t r = qh_unfold(q, qh_region(q, start, eye), eye), h = qh_horizon(q, r);
    if (h < 3) return -2;
    if (qh_reserve(q, h)) return -1;
    uint32_t base = q->nf;
    qh_fan(q, h, eye);
    for (uint32_t i = 0; i < r; i++) {
        qh_face* f = &q->f[q->region[i]];
        f->alive = 0;
        for (uint32_t p = f->conflict, nx; p != NONE; p = nx) {
            nx = q->next[p];
            if (p != eye) qh_assign(q, p, base, q->nf);
        }
        f->conflict = NONE;
    }
    return 0;
}

static uint32_t qh_farthest(const qh* q, const qh_face* f)
{
    uint32_t best = f->conflict;
    for (uint32_t p = f->conflict; p != NONE; p = q->next[p])
        if (qh_dist(q, f, p) > qh_dist(q, f, best)) best = p;
    return best;
}

/* Add conflict points until no face has any. Points only ever move to the faces just
 * made, which are appended, so one pass over the growing face array sees them all. */
static int qh_grow(qh* q)
{
    for (uint32_t i = 0; i < q->nf; i++) {
        if (!q->f[i].alive || q->f[i].conflict == NONE) continue;
        int rc = qh_add_point(q, i, qh_farthest(q, &q->f[i]));
        if (rc) return rc;
    }
    return 0;
}

/* ---- merging coplanar triangles into polygons ----------------------------------------- */

/* Grow polygon c from a seed triangle across edges to triangles whose vertices all lie
 * within eps of the seed's plane (and that face the same way). The seed is the largest
 * triangle left, whose plane is the most accurate. */
static void qh_cluster_from(qh* q, uint32_t seed, uint32_t c)
{
    const double n[3] = { q->f[seed].n[0], q->f[seed].n[1], q->f[seed].n[2] };
    const double d = q->f[seed].d;
    uint32_t head = 0, tail = 0;
    q->f[seed].cluster = c;
    q->queue[tail++] = seed;
    while (head < tail) {
        const qh_face* f = &q->f[q->queue[head++]];
        for (int k = 0; k < 3; k++) {
            qh_face* g = &q->f[f->adj[k]];
            if (g->cluster != NONE || v3_dot(g->n, n) <= 0) continue;
            int flat = 1;
            for (int m = 0; m < 3; m++) flat &= fabs(v3_dot(n, q->p[g->v[m]]) - d) <= q->eps;
            if (!flat) continue;
            g->cluster = c;
            q->queue[tail++] = f->adj[k];
        }
    }
}

typedef struct qh_by_area { double area; uint32_t face; } qh_by_area;

static int qh_larger_first(const void* a, const void* b)
{
    double x = ((const qh_by_area*)a)->area, y = ((const qh_by_area*)b)->area;
    return (x < y) - (x > y);
}

/* Assign every live triangle to a polygon; returns their number, or NONE when out of
 * memory. */
static uint32_t qh_clusters(qh* q)
{
    qh_by_area* order = malloc((q->nf + 1) * sizeof *order);
    if (!order) return NONE;
    uint32_t t = 0, nc = 0;
    for (uint32_t i = 0; i < q->nf; i++) {
        q->f[i].cluster = NONE;
        if (q->f[i].alive) order[t++] = (qh_by_area){ q->f[i].area, i };
    }
    qsort(order, t, sizeof *order, qh_larger_first);
    for (uint32_t i = 0; i < t; i++)
        if (q->f[order[i].face].cluster == NONE) qh_cluster_from(q, order[i].face, nc++);
    free(order);
    return nc;
}

/* Count, for every point, the polygons it is a vertex of (up to three: a corner). */
static void qh_count_corners(qh* q)
{
    uint32_t* c = q->corner;
    for (uint32_t i = 0; i < 3 * q->n; i++) c[i] = i % 3 == 2 ? 0 : NONE;
    for (uint32_t i = 0; i < q->nf; i++) {
        if (!q->f[i].alive) continue;
        for (int k = 0; k < 3; k++) {
            uint32_t* pc = &c[3 * q->f[i].v[k]], cl = q->f[i].cluster;
            if (pc[2] == 0) { pc[0] = cl; pc[2] = 1; }
            else if (pc[2] == 1 && pc[0] != cl) { pc[1] = cl; pc[2] = 2; }
            else if (pc[2] == 2 && pc[0] != cl && pc[1] != cl) pc[2] = 3;
        }
    }
}

/* The corners of polygon c, counter-clockwise, appended to idx: its triangles' edges that
 * border other polygons, chained into a loop. Returns how many, or NONE when the boundary
 * is not one simple loop. */
static uint32_t qh_loop(qh* q, const uint32_t* tris, uint32_t count, uint32_t c, uint32_t* idx)
{
    uint32_t m = 0, first = NONE, out = 0;
    q->stamp++;
    for (uint32_t i = 0; i < count; i++) {
        const qh_face* f = &q->f[tris[i]];
        for (int k = 0; k < 3; k++) {
            if (q->f[f->adj[k]].cluster == c) continue;
            first = f->v[k];
            if (q->vmark[first] == q->stamp) return NONE;
            q->vmark[first] = q->stamp;
            q->hnext[first] = f->v[(k + 1) % 3];
            m++;
        }
    }
    uint32_t v = first;
    for (uint32_t i = 0; i < m; i++) {
        if (q->corner[3 * v + 2] >= 3) idx[out++] = v;
        v = q->hnext[v];
        if (q->vmark[v] != q->stamp || (v == first) != (i == m - 1)) return NONE;
    }
    return out;
}

/* Sort the live triangles by polygon into q->region; ends[c] is where polygon c's end. */
static void qh_group(qh* q, uint32_t* ends, uint32_t nc)
{
    memset(ends, 0, (nc + 1) * sizeof *ends);
    for (uint32_t i = 0; i < q->nf; i++)
        if (q->f[i].alive) ends[q->f[i].cluster + 1]++;
    for (uint32_t c = 0; c < nc; c++) ends[c + 1] += ends[c];
    for (uint32_t i = 0; i < q->nf; i++)
        if (q->f[i].alive) q->region[ends[q->f[i].cluster]++] = i;
}

/* Keep only the points the polygons use, numbered in order of first use. */
static int qh_compact(qh* q, tb_hull_mesh* mesh)
{
    uint32_t* map = q->hnext;
    for (uint32_t i = 0; i < q->n; i++) map[i] = NONE;
    uint32_t nv = 0;
    for (uint32_t i = 0; i < mesh->index_count; i++) {
        uint32_t* v = &mesh->indices[i];
        if (map[*v] == NONE) { map[*v] = nv; q->vmark[nv++] = *v; }
        *v = map[*v];
    }
    mesh->vertices = malloc(nv * sizeof *mesh->vertices);
    if (!mesh->vertices) return -1;
    for (uint32_t i = 0; i < nv; i++) memcpy(mesh->vertices[i], q->p[q->vmark[i]], sizeof(double[3]));
    memset(q->vmark, 0, q->n * sizeof *q->vmark); /* borrowed above: no stale stamps */
    mesh->vertex_count = nv;
    return 0;
}

/* Give every triangle of polygon c but the first a polygon of its own (ids from *nc on). */
static void qh_dissolve(qh* q, const uint32_t* ends, uint32_t c, uint32_t* nc)
{
    for (uint32_t i = (c ? ends[c - 1] : 0) + 1; i < ends[c]; i++)
        q->f[q->region[i]].cluster = (*nc)++;
}

/* A polygon whose boundary is not one loop (noise about as large as eps can make a merged
 * region ring-shaped or pinched) is split back into its triangles, or, when it is a single
 * triangle, its merged neighbours are. The hull stays valid, only less merged there.
 * Returns 0 when it split something, -4 when nothing was left to split. */
static int qh_split(qh* q, const uint32_t* ends, uint32_t c, uint32_t* nc)
{
    uint32_t begin = c ? ends[c - 1] : 0, before = *nc;
    if (ends[c] - begin > 1) {
        qh_dissolve(q, ends, c, nc);
        return 0;
    }
    const qh_face* f = &q->f[q->region[begin]];
    for (int k = 0; k < 3; k++) {
        uint32_t g = q->f[f->adj[k]].cluster;
        if (g < before) qh_dissolve(q, ends, g, nc);
    }
    return *nc > before ? 0 : -4;
}

/* The polygons' corner loops into the mesh; when one is not a simple loop, split it and
 * try again (every split adds polygons, so this ends). Without merge, every triangle is a
 * face of its own. Returns 0, -1 out of memory, -4 when a polygon cannot be made simple. */
static int qh_polygons(qh* q, tb_hull_mesh* mesh, int merge)
{
    uint32_t nc = 0, total = 0;
    if (merge) nc = qh_clusters(q);
    else
        for (uint32_t i = 0; i < q->nf; i++) q->f[i].cluster = q->f[i].alive ? nc++ : NONE;
    if (nc == NONE) return -1;
    uint32_t* ends = malloc((q->nf + 1) * sizeof *ends);
    mesh->faces = malloc(q->nf * sizeof *mesh->faces);
    mesh->indices = malloc(3 * (size_t)q->nf * sizeof *mesh->indices);
    if (!ends || !mesh->faces || !mesh->indices) { free(ends); return -1; }
    for (uint32_t c = 0; c < nc; c++) {
        if (c == 0) { qh_count_corners(q); qh_group(q, ends, nc); total = 0; }
        uint32_t begin = c ? ends[c - 1] : 0;
        uint32_t k = qh_loop(q, q->region + begin, ends[c] - begin, c, mesh->indices + total);
        if (k == NONE || k < 3) {
            if (qh_split(q, ends, c, &nc)) { free(ends); return -4; }
            c = (uint32_t)-1; /* start over with the new polygons */
            continue;
        }
        mesh->faces[c] = (tb_hull_face){ total, k };
        total += k;
    }
    free(ends);
    mesh->face_count = nc;
    mesh->index_count = total;
    return qh_compact(q, mesh);
}

void tb_hull_mesh_face_normal(const tb_hull_mesh* m, uint32_t f, double n[3], double c[3])
{
    const uint32_t* loop = m->indices + m->faces[f].first;
    uint32_t count = m->faces[f].count;
    for (int k = 0; k < 3; k++) c[k] = n[k] = 0;
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) c[k] += m->vertices[loop[i]][k] / count;
    for (uint32_t i = 0; i < count; i++) {
        double a[3], b[3], x[3];
        v3_sub(m->vertices[loop[i]], c, a);
        v3_sub(m->vertices[loop[(i + 1) % count]], c, b);
        v3_cross(a, b, x);
        for (int k = 0; k < 3; k++) n[k] += x[k];
    }
}

/* Whether the merged mesh is convex within 2 eps: every vertex on or below every face's
 * plane (Newell normal through the mean of the face's corners), on its own faces' planes,
 * and no face turning the wrong way at a corner. Merging can fail this where the
 * points are noisy at about the scale of eps (regions that are flat within eps yet not convex); the unmerged triangles never do. */
static int qh_valid(const tb_hull_mesh* m, double eps)
{
    for (uint32_t f = 0; f < m->face_count; f++) {
        const uint32_t* loop = m->indices + m->faces[f].first;
        uint32_t count = m->faces[f].count;
        double c[3], n[3];
        tb_hull_mesh_face_normal(m, f, n, c);
        double len = sqrt(v3_dot(n, n));
        if (!(len > 0)) return 0;
        for (int k = 0; k < 3; k++) n[k] /= len;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            double d[3];
            v3_sub(m->vertices[v], c, d);
            if (v3_dot(n, d) > 2 * eps) return 0;
        }
        for (uint32_t i = 0; i < count; i++) {
            const double* a = m->vertices[loop[i]];
            const double* b = m->vertices[loop[(i + 1) % count]];
            const double* e = m->vertices[loop[(i + 2) % count]];
            double d[3], ab[3], be[3], x[3];
            v3_sub(a, c, d);
            v3_sub(b, a, ab);
            v3_sub(e, b, be);
            v3_cross(ab, be, x);
            if (v3_dot(n, d) < -2 * eps || v3_dot(n, x) < -2 * eps * sqrt(v3_dot(ab, ab)))
                return 0;
        }
    }
    return 1;
}

/* ---- entry ---------------------------------------------------------------------------- */

void tb_hull_mesh_free(tb_hull_mesh* mesh)
{
    free(mesh->vertices);
    free(mesh->faces);
    free(mesh->indices);
    memset(mesh, 0, sizeof *mesh);
}

static void qh_free(qh* q)
{
    free(q->f);
    free(q->queue);
    free(q->region);
    free(q->next);
    free(q->vmark);
    free(q->hnext);
    free(q->hz);
    free(q->corner);
}

static int qh_alloc(qh* q)
{
    size_t n = q->n;
    q->next = malloc(n * sizeof *q->next);
    q->vmark = calloc(n, sizeof *q->vmark);
    q->hnext = malloc(n * sizeof *q->hnext);
    q->hz = malloc((2 * n + 6) * sizeof *q->hz);
    q->corner = malloc(3 * n * sizeof *q->corner);
    return q->next && q->vmark && q->hnext && q->hz && q->corner ? qh_reserve(q, 64) : -1;
}

int tb_quickhull(const double (*points)[3], uint32_t n, double eps, tb_hull_mesh* mesh,
                 char* error, size_t error_size)
{
    qh q = { .p = points, .n = n, .eps = eps };
    uint32_t t[4] = { 0, 0, 0, 0 };
    memset(mesh, 0, sizeof *mesh);
    int rc = qh_alloc(&q);
    if (!rc && qh_simplex(&q, t, error, error_size)) rc = -3;
    if (!rc) rc = qh_start(&q, t);
    if (!rc) rc = qh_grow(&q);
    if (!rc) rc = qh_polygons(&q, mesh, 1);
    if (rc == -4 || (rc == 0 && !qh_valid(mesh, eps))) {
        tb_hull_mesh_free(mesh);
        rc = qh_polygons(&q, mesh, 0);
        if (rc == 0 && !qh_valid(mesh, eps)) rc = -2;
    }
    qh_free(&q);
    if (rc) tb_hull_mesh_free(mesh);
    if (rc == -1) snprintf(error, error_size, "out of memory while building a convex hull");
    if (rc == -2 || rc == -4)
        snprintf(error, error_size, "could not build a consistent convex hull from these points "
                 "(%s)", rc == -2 ? "the points are too noisy at the scale of the tolerance"
                                  : "coplanar faces do not merge into a simple polygon");
    return rc == -2 || rc == -4 ? TB_QUICKHULL_NOISY : rc ? -1 : 0;
}
