/* The mesh BVH: median splits on the host, depth-first nodes with skip indices, boxes
 * quantized outward to 16 bits (see bvh.h). */
#include "geom/bvh.h"
#include "geom/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define QUANT_MAX 65535.0

typedef struct build {
    const float* xyz;
    const uint32_t* indices;
    float (*box)[6];          /* per triangle: min xyz, max xyz */
    float (*centre)[3];       /* per triangle */
    uint32_t* order;          /* triangles, permuted by the splits */
    tb_bvh* bvh;
    double scale[3];          /* quantization steps per metre, per axis */
    uint32_t next;            /* next free node */
} build;

void tb_bvh_steps_per_metre(const tb_bvh* bvh, double scale[3])
{
    for (int a = 0; a < 3; a++) {
        double extent = (double)bvh->hi[a] - bvh->lo[a];
        scale[a] = extent > 0 ? QUANT_MAX / extent : 0.0;
    }
}

/* The box [lo, hi] in quantized coordinates, outward: floor of the low side, ceiling of the
 * high side, both clamped into 0..65535. */
static void quantize(const tb_bvh* bvh, const double scale[3], const float lo[3],
                     const float hi[3], uint32_t q[6])
{
    for (int a = 0; a < 3; a++) {
        double from = bvh->lo[a];
        double l = floor(((double)lo[a] - from) * scale[a]);
        double h = ceil(((double)hi[a] - from) * scale[a]);
        q[a] = (uint32_t)fmin(fmax(l, 0.0), QUANT_MAX);
        q[3 + a] = (uint32_t)fmin(fmax(h, 0.0), QUANT_MAX);
    }
}

static void write_node(build* b, uint32_t node, const float lo[3], const float hi[3],
                       uint32_t w)
{
    uint32_t q[6];
    quantize(b->bvh, b->scale, lo, hi, q);
    b->bvh->nodes[node].q = (tb_gpu_uvec4){ q[0] | q[1] << 16, q[2] | q[3] << 16,
                                            q[4] | q[5] << 16, w };
}

/* Box of the triangles order[first .. first + count) and of their centres. */
static void bounds(const build* b, uint32_t first, uint32_t count, float box[6], float cbox[6])
{
    for (int a = 0; a < 3; a++) {
        box[a] = cbox[a] = INFINITY;
        box[3 + a] = cbox[3 + a] = -INFINITY;
    }
    for (uint32_t i = first; i < first + count; i++) {
        const float* t = b->box[b->order[i]];
        const float* c = b->centre[b->order[i]];
        for (int a = 0; a < 3; a++) {
            box[a] = fminf(box[a], t[a]);
            box[3 + a] = fmaxf(box[3 + a], t[3 + a]);
            cbox[a] = fminf(cbox[a], c[a]);
            cbox[3 + a] = fmaxf(cbox[3 + a], c[a]);
        }
    }
}

/* Partially order order[first .. first + count) along `axis` so that the `k`-th smallest
 * centre is at first + k, smaller (or equal) ones before it, larger (or equal) after
 * (quickselect; ties broken by triangle index so the result is the same on every run). */
static int before(const build* b, uint32_t x, uint32_t y, int axis)
{
    float cx = b->centre[x][axis], cy = b->centre[y][axis];
    return cx < cy || (cx == cy && x < y);
}

static void select_median(build* b, uint32_t first, uint32_t count, uint32_t k, int axis)
{
    uint32_t lo = first, hi = first + count - 1, target = first + k;
    uint32_t* o = b->order;
    while (lo < hi) {
        uint32_t pivot = o[lo + (hi - lo) / 2], i = lo, j = hi;
        while (i <= j) {
            while (before(b, o[i], pivot, axis)) i++;
            while (before(b, pivot, o[j], axis)) j--;
            if (i <= j) {
                uint32_t t = o[i];
                o[i] = o[j];
                o[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (target <= j) hi = j;
        else if (target >= i) lo = i;
        else break;
    }
}

/* The subtree of order[first .. first + count) from node b->next on. Recursion depth is
 * about log2 of the triangle count: the split is always at the median. */
static void build_subtree(build* b, uint32_t first, uint32_t count)
{
    uint32_t node = b->next++;
    float box[6], cbox[6];
    bounds(b, first, count, box, cbox);
    if (count == 1) {
        write_node(b, node, box, box + 3, TB_BVH_LEAF | b->order[first]);
        return;
    }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (cbox[3 + a] - cbox[a] > cbox[3 + axis] - cbox[axis]) axis = a;
    uint32_t half = count / 2;
    select_median(b, first, count, half, axis);
    build_subtree(b, first, half);
    build_subtree(b, first + half, count - half);
    write_node(b, node, box, box + 3, b->next);
}

static int check_input(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                       uint32_t triangle_count, char* error, size_t error_size)
{
    if (!xyz || !indices || triangle_count == 0)
        return tb_geom_fail(error, error_size, "a mesh needs vertices and at least one triangle");
    if (triangle_count > TB_BVH_MAX_TRIANGLES)
        return tb_geom_fail(error, error_size, "a mesh has at most %u triangles, not %u",
                    (unsigned)TB_BVH_MAX_TRIANGLES, triangle_count);
    for (uint32_t v = 0; v < vertex_count; v++)
        for (int a = 0; a < 3; a++)
            if (!isfinite(xyz[3 * (size_t)v + a]))
                return tb_geom_fail(error, error_size, "vertex %u is not finite", v);
    for (uint64_t i = 0; i < 3 * (uint64_t)triangle_count; i++)
        if (indices[i] >= vertex_count)
            return tb_geom_fail(error, error_size, "triangle %u uses vertex %u of %u",
                        (unsigned)(i / 3), indices[i], vertex_count);
    return 0;
}

/* Each triangle's box and centre, and the mesh's box with its quantization steps. */
static void measure(build* b, uint32_t n)
{
    tb_bvh* bvh = b->bvh;
    for (int a = 0; a < 3; a++) {
        bvh->lo[a] = INFINITY;
        bvh->hi[a] = -INFINITY;
    }
    for (uint32_t t = 0; t < n; t++) {
        for (int a = 0; a < 3; a++) {
            float p[3];
            for (int k = 0; k < 3; k++) p[k] = b->xyz[3 * (size_t)b->indices[3 * (size_t)t + k] + a];
            b->box[t][a] = fminf(p[0], fminf(p[1], p[2]));
            b->box[t][3 + a] = fmaxf(p[0], fmaxf(p[1], p[2]));
            b->centre[t][a] = (float)(((double)p[0] + p[1] + p[2]) / 3.0);
            bvh->lo[a] = fminf(bvh->lo[a], b->box[t][a]);
            bvh->hi[a] = fmaxf(bvh->hi[a], b->box[t][3 + a]);
        }
        b->order[t] = t;
    }
    tb_bvh_steps_per_metre(bvh, b->scale);
}

int tb_bvh_build(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                 uint32_t triangle_count, tb_bvh* out, char* error, size_t error_size)
{
    if (check_input(xyz, vertex_count, indices, triangle_count, error, error_size)) return -1;
    tb_bvh bvh = { 0 };
    build b = { .xyz = xyz, .indices = indices, .bvh = &bvh };
    size_t n = triangle_count;
    bvh.node_count = (uint32_t)(2 * n - 1);
    bvh.triangle_count = triangle_count;
    bvh.nodes = malloc(bvh.node_count * sizeof *bvh.nodes);
    b.box = malloc(n * sizeof *b.box);
    b.centre = malloc(n * sizeof *b.centre);
    b.order = malloc(n * sizeof *b.order);
    int ok = bvh.nodes && b.box && b.centre && b.order;
    if (ok) {
        measure(&b, triangle_count);
        build_subtree(&b, 0, triangle_count);
    }
    free(b.box);
    free(b.centre);
    free(b.order);
    if (!ok) {
        free(bvh.nodes);
        return tb_geom_fail(error, error_size, "no host memory for a BVH of %u triangles", triangle_count);
    }
    *out = bvh;
    return 0;
}

void tb_bvh_free(tb_bvh* bvh)
{
    free(bvh->nodes);
    memset(bvh, 0, sizeof *bvh);
}

void tb_bvh_node_box(const tb_bvh* bvh, uint32_t node, float lo[3], float hi[3])
{
    const tb_gpu_uvec4 q = bvh->nodes[node].q;
    const uint32_t v[6] = { q.x & 0xffff, q.x >> 16, q.y & 0xffff, q.y >> 16, q.z & 0xffff, q.z >> 16 };
    for (int a = 0; a < 3; a++) {
        double step = ((double)bvh->hi[a] - bvh->lo[a]) / QUANT_MAX;
        lo[a] = (float)(bvh->lo[a] + v[a] * step);
        hi[a] = (float)(bvh->lo[a] + v[3 + a] * step);
    }
}

static int overlaps(const float alo[3], const float ahi[3], const float blo[3], const float bhi[3])
{
    for (int a = 0; a < 3; a++)
        if (alo[a] > bhi[a] || blo[a] > ahi[a]) return 0;
    return 1;
}

/* Node boxes are compared with the query box in quantized coordinates, the query rounded
 * outward: exact integer tests that never miss a triangle (the GPU walk does the same). */
uint32_t tb_bvh_query(const tb_bvh* bvh, const float lo[3], const float hi[3],
                      void (*visit)(void* user, uint32_t triangle), void* user)
{
    if (!overlaps(lo, hi, bvh->lo, bvh->hi)) return 0;
    double scale[3];
    uint32_t q[6], looked = 0;
    tb_bvh_steps_per_metre(bvh, scale);
    quantize(bvh, scale, lo, hi, q);
    for (uint32_t i = 0; i < bvh->node_count; looked++) {
        const tb_gpu_uvec4 n = bvh->nodes[i].q;
        const uint32_t nlo[3] = { n.x & 0xffff, n.x >> 16, n.y & 0xffff };
        const uint32_t nhi[3] = { n.y >> 16, n.z & 0xffff, n.z >> 16 };
        int hit = 1;
        for (int a = 0; a < 3; a++) hit &= nlo[a] <= q[3 + a] && q[a] <= nhi[a];
        int leaf = (n.w & TB_BVH_LEAF) != 0;
        if (hit && leaf) visit(user, n.w & ~TB_BVH_LEAF);
        i = hit || leaf ? i + 1 : n.w;
    }
    return looked;
}
