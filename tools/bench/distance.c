/* bench-distance: distance queries per second (tb_world_query_distances) at several sizes,
 * and the depths of the two penetration methods, EPA and MPR, on the same pairs.
 *
 *   bench-distance [--sizes N,N,...] [--reps R] [--penetration epa|mpr|both]
 *
 * Random pairs of the six convex kinds (spheres, boxes, hulls of 16 points, capsules,
 * cylinders, cones; sizes 0.1 to 1 m, random rotations) in three sets: apart (GJK alone),
 * overlapping (GJK, then EPA or MPR) and mixed (half each). Each size runs R times; the
 * median wall time of the call is reported, which includes checking and packing the queries
 * on the host and their way to and from the GPU through host-visible memory. The
 * overlapping and mixed sets run once for each method asked for (default both), on the same
 * pairs; the apart set runs once (its queries never reach a penetration method).
 *
 * Depths are measured where the shapes' cores overlap (either method's status OVERLAP or
 * FAILED), against a reference on the host in double precision: the penetration depth of
 * two convex shapes is their least overlap over all unit axes, and the reference is the
 * least overlap found by a local search on the sphere of directions (least_overlap) from
 * EPA's normal and from MPR's (both methods run for it, the one not asked for untimed).
 * That reference is an overlap along some axis, so it is at least the true depth.
 *
 * Prints CSV, one line per set, size and method: set, queries, median ms, millions of
 * queries per second, the share of overlapping answers (distance < 0); then the method
 * (epa, mpr, or - for the apart set), the pairs measured for depth, the median and 99th
 * percentile of the relative depth error |depth - reference| / (reference + 1e-3 of the
 * smaller shape), the share of those pairs with an error over 1 %, and the median and 99th
 * percentile of the angle between the method's normal and the reference's axis, degrees.
 * The depth columns are empty for the apart set.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tumble.h"
#include "convex_reference.h"

#define MAX_SIZES 16
#define MAX_REPS 32
#define SHAPES 24
#define HULL_POINTS 16

/* The kinds in turn: sphere, box, hull, capsule, cylinder, cone. */
static const tb_shape_type kinds[6] = { TB_SHAPE_SPHERE, TB_SHAPE_BOX, TB_SHAPE_HULL,
                                        TB_SHAPE_CAPSULE, TB_SHAPE_CYLINDER, TB_SHAPE_CONE };

static uint64_t state = 88172645463325252ull;

static double uniform(double lo, double hi)
{
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

static tb_quat random_rotation(void)
{
    double u = uniform(0, 1), a = uniform(0, 6.283185307), b = uniform(0, 6.283185307);
    double s = sqrt(1 - u), t = sqrt(u);
    return (tb_quat){ (float)(s * sin(a)), (float)(s * cos(a)), (float)(t * sin(b)),
                      (float)(t * cos(b)) };
}

static void die(tb_world* w, const char* what)
{
    if (w) fprintf(stderr, "bench-distance: %s: %s\n", what, tb_world_last_error(w));
    else fprintf(stderr, "bench-distance: %s\n", what);
    exit(1);
}

static void make_shape(tb_world* w, int kind, float size, ref_shape* s)
{
    tb_shape_def def = tb_default_shape_def();
    tb_result r;
    float a = size * (float)uniform(0.5, 1), b = size * (float)uniform(0.3, 1);
    memset(s, 0, sizeof *s);
    s->type = kinds[kind], s->radius = a, s->half = b, s->size = size;
    s->box[0] = a, s->box[1] = b, s->box[2] = size;
    if (kind == 0) r = tb_shape_create_sphere(w, &def, a, &s->id);
    else if (kind == 1) r = tb_shape_create_box(w, &def, (tb_vec3){ a, b, size }, &s->id);
    else if (kind == 2) {
        tb_vec3 p[HULL_POINTS], v[256];
        for (int k = 0; k < HULL_POINTS; k++)
            p[k] = (tb_vec3){ a * (float)uniform(-1, 1), b * (float)uniform(-1, 1),
                              size * (float)uniform(-1, 1) };
        r = tb_shape_create_hull(w, &def, p, HULL_POINTS, &s->id);
        if (!r) r = tb_shape_get_hull_vertices(w, s->id, v, 256, &s->point_count);
        s->points = malloc(256 * sizeof *s->points);
        if (!s->points) die(NULL, "out of memory");
        for (uint32_t k = 0; !r && k < s->point_count; k++)
            s->points[k][0] = v[k].x, s->points[k][1] = v[k].y, s->points[k][2] = v[k].z;
    } else if (kind == 3) r = tb_shape_create_capsule(w, &def, a, b, &s->id);
    else if (kind == 4) r = tb_shape_create_cylinder(w, &def, a, b, &s->id);
    else r = tb_shape_create_cone(w, &def, a, b, &s->id);
    if (r) die(w, "shape");
}

/* `overlap`: 0 apart (centres 2.2 to 4 m apart, beyond any two shapes' reach), 1 centres
 * within 0.3 m (overlapping), 2 either at random. */
static void fill(tb_distance_query* q, const ref_shape** pick, uint32_t n,
                 const ref_shape* shapes, int overlap)
{
    for (uint32_t i = 0; i < n; i++) {
        int close = overlap == 2 ? (int)(i & 1u) : overlap;
        double reach = close ? uniform(0, 0.3) : uniform(2.2, 4.0);
        double d[3] = { uniform(-1, 1), uniform(-1, 1), uniform(-1, 1) };
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-9;
        tb_vec3 o = { (float)uniform(-50, 50), (float)uniform(-50, 50), (float)uniform(-50, 50) };
        pick[2 * i] = &shapes[i % SHAPES];
        pick[2 * i + 1] = &shapes[(i / SHAPES + 7 * i) % SHAPES];
        q[i] = (tb_distance_query){
            pick[2 * i]->id, pick[2 * i + 1]->id, o, random_rotation(),
            { o.x + (float)(reach * d[0] / len), o.y + (float)(reach * d[1] / len),
              o.z + (float)(reach * d[2] / len) }, random_rotation(), TB_PENETRATION_DEFAULT,
        };
    }
}

/* ---- measuring ------------------------------------------------------------------------ */

enum { EPA, MPR, METHODS };
static const tb_penetration method_enum[METHODS] = { TB_PENETRATION_EPA, TB_PENETRATION_MPR };
static const char* method_name[METHODS] = { "epa", "mpr" };

typedef struct depths {
    uint32_t pairs;
    double err_median, err_p99, over_1pct, deg_median, deg_p99;
} depths;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int by_value(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return x < y ? -1 : x > y;
}

/* The median wall time of `reps` calls, after one to warm up. */
static double time_queries(tb_world* w, const tb_distance_query* q, uint32_t n, uint32_t reps,
                           tb_distance_result* out)
{
    if (tb_world_query_distances(w, q, n, out)) die(w, "query");
    double ms[MAX_REPS];
    for (uint32_t r = 0; r < reps; r++) {
        double t0 = now_ms();
        if (tb_world_query_distances(w, q, n, out)) die(w, "query");
        ms[r] = now_ms() - t0;
    }
    qsort(ms, reps, sizeof *ms, by_value);
    return ms[reps / 2];
}

static int cores_overlap(const tb_distance_result* r)
{
    return r->status == TB_DISTANCE_OVERLAP || r->status == TB_DISTANCE_FAILED;
}

static double percentile(double* v, uint32_t n, double p)
{
    return n ? v[(uint32_t)(p * (n - 1) + 0.5)] : NAN;
}

/* Each method's depth errors on the pairs whose cores overlap, against the reference from
 * both methods' normals. */
static void measure_depths(const tb_distance_query* q, const ref_shape** pick, uint32_t n,
                           tb_distance_result* const out[METHODS], depths d[METHODS])
{
    double* err[METHODS];
    double* deg[METHODS];
    for (int m = 0; m < METHODS; m++) {
        err[m] = malloc((size_t)n * sizeof(double));
        deg[m] = malloc((size_t)n * sizeof(double));
        if (!err[m] || !deg[m]) die(NULL, "out of memory");
        memset(&d[m], 0, sizeof d[m]);
    }
    uint32_t k = 0, over[METHODS] = { 0 };
    for (uint32_t i = 0; i < n; i++) {
        if (!cores_overlap(&out[EPA][i]) && !cores_overlap(&out[MPR][i])) continue;
        posed a = posed_of(pick[2 * i], q[i].position_a, q[i].rotation_a);
        posed b = posed_of(pick[2 * i + 1], q[i].position_b, q[i].rotation_b);
        double axis[METHODS][3], depth[METHODS];
        for (int m = 0; m < METHODS; m++) {
            tb_vec3 nv = out[m][i].normal;
            axis[m][0] = nv.x, axis[m][1] = nv.y, axis[m][2] = nv.z;
            depth[m] = least_overlap(&a, &b, axis[m]);
        }
        int best = depth[MPR] < depth[EPA];
        double ref = depth[best], scale = 1e-3 * fmin(a.s->size, b.s->size);
        for (int m = 0; m < METHODS; m++) {
            tb_vec3 nv = out[m][i].normal;
            double c = (nv.x * axis[best][0] + nv.y * axis[best][1] + nv.z * axis[best][2]) /
                       sqrt(nv.x * nv.x + nv.y * nv.y + nv.z * nv.z);
            err[m][k] = fabs(-out[m][i].distance - ref) / (ref + scale);
            deg[m][k] = acos(fmax(-1.0, fmin(1.0, c))) * 57.29577951308232;
            over[m] += err[m][k] > 0.01;
        }
        k++;
    }
    for (int m = 0; m < METHODS; m++) {
        qsort(err[m], k, sizeof(double), by_value);
        qsort(deg[m], k, sizeof(double), by_value);
        d[m] = (depths){ k, percentile(err[m], k, 0.5), percentile(err[m], k, 0.99),
                         k ? (double)over[m] / k : NAN, percentile(deg[m], k, 0.5),
                         percentile(deg[m], k, 0.99) };
        free(err[m]);
        free(deg[m]);
    }
}

static void print_line(const char* set, uint32_t n, double ms, const tb_distance_result* out,
                       const char* method, const depths* d)
{
    uint32_t overlapping = 0;
    for (uint32_t i = 0; i < n; i++) overlapping += out[i].distance < 0;
    printf("%s,%u,%.3f,%.2f,%.3f,%s", set, n, ms, n / ms / 1e3, (double)overlapping / n, method);
    if (d) printf(",%u,%.3g,%.3g,%.4f,%.3g,%.3g\n", d->pairs, d->err_median, d->err_p99,
                  d->over_1pct, d->deg_median, d->deg_p99);
    else printf(",,,,,,\n");
}

int main(int argc, char** argv)
{
    uint32_t sizes[MAX_SIZES] = { 10000, 100000, 1000000 }, count = 3, reps = 5;
    int asked[METHODS] = { 1, 1 };
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--reps")) reps = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--sizes")) {
            count = 0;
            for (char* s = strtok(argv[i + 1], ","); s && count < MAX_SIZES; s = strtok(NULL, ","))
                sizes[count++] = (uint32_t)strtoul(s, NULL, 10);
        } else if (!strcmp(argv[i], "--penetration")) {
            asked[EPA] = !strcmp(argv[i + 1], "epa") || !strcmp(argv[i + 1], "both");
            asked[MPR] = !strcmp(argv[i + 1], "mpr") || !strcmp(argv[i + 1], "both");
            if (!asked[EPA] && !asked[MPR]) die(NULL, "--penetration takes epa, mpr or both");
        }
    }
    if (reps < 1 || reps > MAX_REPS) reps = 5;
    tb_world_def def = tb_default_world_def();
    tb_world* w;
    if (tb_world_create(&def, &w)) die(NULL, "world");
    static ref_shape shapes[SHAPES];
    for (int s = 0; s < SHAPES; s++) make_shape(w, s % 6, (float)uniform(0.1, 1.0), &shapes[s]);
    uint32_t most = 0;
    for (uint32_t k = 0; k < count; k++) most = sizes[k] > most ? sizes[k] : most;
    tb_distance_query* q = malloc((size_t)most * sizeof *q);
    const ref_shape** pick = malloc(2 * (size_t)most * sizeof *pick);
    tb_distance_result* out[METHODS];
    for (int m = 0; m < METHODS; m++) out[m] = malloc((size_t)most * sizeof *out[m]);
    if (!q || !pick || !out[EPA] || !out[MPR]) die(w, "out of memory");
    const char* sets[3] = { "apart", "overlapping", "mixed" };
    printf("set,queries,median_ms,mqueries_per_s,overlapping_share,method,depth_pairs,"
           "depth_err_median,depth_err_p99,depth_over_1pct,normal_deg_median,normal_deg_p99\n");
    for (int set = 0; set < 3; set++) {
        for (uint32_t k = 0; k < count; k++) {
            uint32_t n = sizes[k];
            fill(q, pick, n, shapes, set);
            if (set == 0) {
                print_line(sets[set], n, time_queries(w, q, n, reps, out[EPA]), out[EPA], "-",
                           NULL);
                continue;
            }
            double ms[METHODS] = { 0, 0 };
            for (int m = 0; m < METHODS; m++) {
                for (uint32_t i = 0; i < n; i++) q[i].penetration = method_enum[m];
                if (asked[m]) ms[m] = time_queries(w, q, n, reps, out[m]);
                else if (tb_world_query_distances(w, q, n, out[m])) die(w, "query");
            }
            depths d[METHODS];
            measure_depths(q, pick, n, out, d);
            for (int m = 0; m < METHODS; m++)
                if (asked[m]) print_line(sets[set], n, ms[m], out[m], method_name[m], &d[m]);
        }
    }
    free(q);
    free(pick);
    for (int m = 0; m < METHODS; m++) free(out[m]);
    tb_world_destroy(w);
    return 0;
}
