/* bench-distance: distance queries per second (tb_world_query_distances) at several sizes.
 *
 *   bench-distance [--sizes N,N,...] [--reps R]
 *
 * Random pairs of the six convex kinds (spheres, boxes, hulls of 16 points, capsules,
 * cylinders, cones; sizes 0.1 to 1 m, random rotations) in three sets: apart (GJK alone),
 * overlapping (GJK, then EPA) and mixed (half each). Each size runs R times; the median
 * wall time of the call is reported, which includes checking and packing the queries on
 * the host and their way to and from the GPU through host-visible memory. Prints one line
 * per set and size: queries, median ms, millions of queries per second.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tumble.h"

#define MAX_SIZES 16
#define MAX_REPS 32
#define SHAPES 24

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
    fprintf(stderr, "bench-distance: %s: %s\n", what, tb_world_last_error(w));
    exit(1);
}

static tb_shape_id make_shape(tb_world* w, int kind, float size)
{
    tb_shape_def def = tb_default_shape_def();
    tb_shape_id s;
    tb_result r;
    float a = size * (float)uniform(0.5, 1), b = size * (float)uniform(0.3, 1);
    if (kind == 0) r = tb_shape_create_sphere(w, &def, a, &s);
    else if (kind == 1) r = tb_shape_create_box(w, &def, (tb_vec3){ a, b, size }, &s);
    else if (kind == 2) {
        tb_vec3 p[16];
        for (int k = 0; k < 16; k++)
            p[k] = (tb_vec3){ a * (float)uniform(-1, 1), b * (float)uniform(-1, 1),
                              size * (float)uniform(-1, 1) };
        r = tb_shape_create_hull(w, &def, p, 16, &s);
    } else if (kind == 3) r = tb_shape_create_capsule(w, &def, a, b, &s);
    else if (kind == 4) r = tb_shape_create_cylinder(w, &def, a, b, &s);
    else r = tb_shape_create_cone(w, &def, a, b, &s);
    if (r) die(w, "shape");
    return s;
}

/* `overlap`: 0 apart (centres 2.2 to 4 m apart, beyond any two shapes' reach), 1 centres
 * within 0.3 m (overlapping), 2 either at random. */
static void fill(tb_distance_query* q, uint32_t n, const tb_shape_id* shapes, int overlap)
{
    for (uint32_t i = 0; i < n; i++) {
        int close = overlap == 2 ? (int)(i & 1u) : overlap;
        double reach = close ? uniform(0, 0.3) : uniform(2.2, 4.0);
        double d[3] = { uniform(-1, 1), uniform(-1, 1), uniform(-1, 1) };
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-9;
        tb_vec3 o = { (float)uniform(-50, 50), (float)uniform(-50, 50), (float)uniform(-50, 50) };
        q[i] = (tb_distance_query){
            shapes[i % SHAPES], shapes[(i / SHAPES + 7 * i) % SHAPES], o, random_rotation(),
            { o.x + (float)(reach * d[0] / len), o.y + (float)(reach * d[1] / len),
              o.z + (float)(reach * d[2] / len) }, random_rotation(),
        };
    }
}

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

int main(int argc, char** argv)
{
    uint32_t sizes[MAX_SIZES] = { 10000, 100000, 1000000 }, count = 3, reps = 5;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--reps")) reps = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--sizes")) {
            count = 0;
            for (char* s = strtok(argv[i + 1], ","); s && count < MAX_SIZES; s = strtok(NULL, ","))
                sizes[count++] = (uint32_t)strtoul(s, NULL, 10);
        }
    }
    if (reps < 1 || reps > MAX_REPS) reps = 5;
    tb_world_def def = tb_default_world_def();
    tb_world* w;
    if (tb_world_create(&def, &w)) die(NULL, "world");
    tb_shape_id shapes[SHAPES];
    for (int s = 0; s < SHAPES; s++) shapes[s] = make_shape(w, s % 6, (float)uniform(0.1, 1.0));
    uint32_t most = 0;
    for (uint32_t k = 0; k < count; k++) most = sizes[k] > most ? sizes[k] : most;
    tb_distance_query* q = malloc((size_t)most * sizeof *q);
    tb_distance_result* out = malloc((size_t)most * sizeof *out);
    if (!q || !out) die(w, "out of memory");
    const char* sets[3] = { "apart", "overlapping", "mixed" };
    printf("set,queries,median_ms,mqueries_per_s,overlapping_share\n");
    for (int set = 0; set < 3; set++) {
        for (uint32_t k = 0; k < count; k++) {
            fill(q, sizes[k], shapes, set == 0 ? 0 : (set == 1 ? 1 : 2));
            if (tb_world_query_distances(w, q, sizes[k], out)) die(w, "query");  /* warm */
            double ms[MAX_REPS];
            for (uint32_t r = 0; r < reps; r++) {
                double t0 = now_ms();
                if (tb_world_query_distances(w, q, sizes[k], out)) die(w, "query");
                ms[r] = now_ms() - t0;
            }
            qsort(ms, reps, sizeof *ms, by_value);
            uint32_t overlapping = 0;
            for (uint32_t i = 0; i < sizes[k]; i++) overlapping += out[i].distance < 0;
            printf("%s,%u,%.3f,%.2f,%.3f\n", sets[set], sizes[k], ms[reps / 2],
                   sizes[k] / ms[reps / 2] / 1e3, (double)overlapping / sizes[k]);
        }
    }
    free(q);
    free(out);
    tb_world_destroy(w);
    return 0;
}
