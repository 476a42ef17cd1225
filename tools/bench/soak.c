/* bench-soak: a long run of one scene, reporting at intervals what must not drift.
 *
 *   build/bench-soak [--scene NAME] [--n N] [--steps TOTAL] [--every K] [--device NAME]
 *                    [--restore FILE] [--save FILE]
 *
 * A long run can go in pieces: --save writes a snapshot of the world (tb_world_snapshot)
 * with every line, so a piece cut short by a time limit leaves its last one, and
 * --restore starts from one (the same scene and N); the step numbers then go on from the
 * snapshot's, and TOTAL counts the steps of this piece.
 *
 * Every K steps (one tb_world_step_n of K steps) a line: steps so far, wall ms a step over the
 * interval, the GPU ms of its last step, bodies whose pose or velocity is not finite,
 * bodies the guard isolated, the kinetic and potential energy of the dynamic bodies (J;
 * potential against gravity from y = 0), the fastest body, how far the bodies have slid
 * across gravity since this run's first line (mean and most, mm: a settled pile's creep),
 * the process's resident memory, the pairs, contact points and colours, and the GPU
 * buffers' capacities and growths. At the end: whether anything stopped being finite, how much the total energy
 * moved over the second half of the run, and how much the resident memory grew after the
 * first interval. Exits 1 when a body stopped being finite or a step failed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cglm/cglm.h>

#include "scenes.h"

typedef struct options {
    const char* scene;
    uint32_t n, every;
    uint64_t steps;
    const char* save;
    const char* restore;
} options;

typedef struct sample {
    uint32_t non_finite, isolated;
    double kinetic, potential, fastest;
    double slide_mean, slide_max;   /* sideways (across gravity) since the first line, m */
} sample;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static double resident_mb(void)
{
    FILE* f = fopen("/proc/self/statm", "r");
    long pages = 0, resident = 0;
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        fclose(f);
    }
    return (double)resident * (double)sysconf(_SC_PAGESIZE) / 1048576.0;
}

static int finite3(tb_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* How far p has moved from `from` across gravity g (sideways on a level floor), m. */
static double sideways(tb_vec3 p, tb_vec3 from, tb_vec3 g)
{
    vec3 d = { p.x - from.x, p.y - from.y, p.z - from.z }, down = { g.x, g.y, g.z };
    if (glm_vec3_norm2(down) > 0.0f) {
        glm_vec3_normalize(down);
        vec3 along;
        glm_vec3_scale(down, glm_vec3_dot(d, down), along);
        glm_vec3_sub(d, along, d);
    }
    return glm_vec3_norm(d);
}

/* The figures of every body in ids; `first` holds each body's position at the first line
 * (written there, when *have_first is 0). */
static int measure(tb_world* w, const tb_body_id* ids, uint32_t count, tb_vec3* first,
                   int* have_first, sample* out)
{
    memset(out, 0, sizeof *out);
    tb_vec3 g = tb_world_get_gravity(w);
    uint32_t slid = 0;
    for (uint32_t i = 0; i < count; i++) {
        tb_vec3 p, v, av, inertia;
        tb_quat q;
        float mass;
        if (tb_body_get_pose(w, ids[i], &p, &q) || tb_body_get_velocity(w, ids[i], &v, &av) ||
            tb_body_get_mass(w, ids[i], &mass, &inertia))
            return 1;
        if (!finite3(p) || !finite3(v) || !finite3(av) || !isfinite(q.w)) {
            out->non_finite++;
            continue;
        }
        if (!*have_first) first[i] = p;
        double slide = sideways(p, first[i], g);
        out->slide_mean += slide;
        slid++;
        if (slide > out->slide_max) out->slide_max = slide;
        double speed = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
        if (speed > out->fastest) out->fastest = speed;
        /* Spin energy 1/2 w^T I w with w in the body's principal frame: R^T w. */
        versor turn = { q.x, q.y, q.z, q.w }, back;
        vec3 spin_world = { av.x, av.y, av.z }, local;
        glm_quat_inv(turn, back);
        glm_quat_rotatev(back, spin_world, local);
        double spin = (double)inertia.x * local[0] * local[0] +
                      (double)inertia.y * local[1] * local[1] +
                      (double)inertia.z * local[2] * local[2];
        out->kinetic += 0.5 * mass * speed * speed + 0.5 * spin;
        out->potential -= mass * ((double)g.x * p.x + (double)g.y * p.y + (double)g.z * p.z);
    }
    if (slid) out->slide_mean /= slid;
    *have_first = 1;
    out->isolated = tb_world_isolated_bodies(w, NULL, 0);
    return 0;
}

static int parse(int argc, char** argv, options* o)
{
    *o = (options){ "boxes", 1000, 1, 1000000, NULL, NULL };
    o->every = 10000;
    for (int i = 1; i < argc; i++) {
        const char* a = argv[i];
        const char* v = i + 1 < argc ? argv[i + 1] : NULL;
        uint32_t u = 0;
        if (strcmp(a, "--scene") == 0 && v) o->scene = v;
        else if (strcmp(a, "--device") == 0 && v) setenv("TUMBLE_DEVICE", v, 1);
        else if (strcmp(a, "--n") == 0 && v && scene_parse_u32(v, &u) && u) o->n = u;
        else if (strcmp(a, "--every") == 0 && v && scene_parse_u32(v, &u) && u) o->every = u;
        else if (strcmp(a, "--steps") == 0 && v && scene_parse_u32(v, &u) && u) o->steps = u;
        else if (strcmp(a, "--save") == 0 && v) o->save = v;
        else if (strcmp(a, "--restore") == 0 && v) o->restore = v;
        else {
            fprintf(stderr, "usage: bench-soak [--scene NAME] [--n N] [--steps TOTAL] "
                            "[--every K] [--device NAME] [--restore FILE] [--save FILE]\n");
            return 1;
        }
        i++;
    }
    return 0;
}

/* The world from the snapshot in `path` (0), or 1 with a sentence. */
static int restore_file(tb_world* w, const char* path)
{
    FILE* f = fopen(path, "rb");
    long size = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    void* bytes = size > 0 ? malloc((size_t)size) : NULL;
    int bad = !bytes || fseek(f, 0, SEEK_SET) != 0 || fread(bytes, 1, (size_t)size, f) != (size_t)size;
    if (f) fclose(f);
    if (!bad && tb_world_restore(w, bytes, (size_t)size) != TB_OK) {
        fprintf(stderr, "bench-soak: %s: %s\n", path, tb_world_last_error(w));
        bad = 1;
    } else if (bad) {
        fprintf(stderr, "bench-soak: cannot read %s\n", path);
    }
    free(bytes);
    return bad;
}

static int save_file(tb_world* w, const char* path)
{
    size_t size = 0;
    tb_world_snapshot(w, NULL, 0, &size);
    void* bytes = size ? malloc(size) : NULL;
    char part[4096];
    snprintf(part, sizeof part, "%s.part", path);   /* whole snapshots only, even if killed */
    FILE* f = bytes ? fopen(part, "wb") : NULL;
    int bad = !f || tb_world_snapshot(w, bytes, size, &size) != TB_OK ||
              fwrite(bytes, 1, size, f) != size;
    if (f && fclose(f) != 0) bad = 1;
    if (!bad && rename(part, path) != 0) bad = 1;
    if (bad) fprintf(stderr, "bench-soak: cannot save a snapshot to %s\n", path);
    free(bytes);
    return bad;
}

int main(int argc, char** argv)
{
    options o;
    if (parse(argc, argv, &o)) return 2;
    const scene* sc = scene_find(o.scene);
    if (!sc) {
        fprintf(stderr, "bench-soak: no scene %s\n", o.scene);
        return 2;
    }
    tb_world_def def = tb_default_world_def();
    tb_world* w = NULL;
    scene_instance* inst = NULL;
    scene_params params = { o.n, 1 };
    if (tb_world_create(&def, &w) || sc->build(w, &params, &inst)) {
        fprintf(stderr, "bench-soak: %s\n", tb_world_last_error(w));
        return 2;
    }
    uint32_t count = 0;
    const tb_body_id* all = scene_body_ids(inst, &count);
    tb_body_id* ids = malloc(count * sizeof *ids);
    uint32_t dynamic = 0;
    for (uint32_t i = 0; i < count; i++) {
        tb_body_type type;
        if (!tb_body_get_type(w, all[i], &type) && type == TB_BODY_DYNAMIC) ids[dynamic++] = all[i];
    }
    if (o.restore && restore_file(w, o.restore)) return 2;
    tb_world_stats start;
    tb_world_get_stats(w, &start);
    tb_device_info info;
    tb_world_device_info(w, &info);
    printf("bench-soak: scene %s, %u dynamic bodies, %llu steps of %g s from step %llu, a line "
           "every %u, on %s\n", sc->name, dynamic, (unsigned long long)o.steps, (double)sc->dt,
           (unsigned long long)start.steps, o.every, info.name);
    printf("%10s %8s %7s %6s %6s %14s %14s %10s %9s %9s %8s %8s %8s %7s %9s %9s %7s\n",
           "steps", "ms/step", "gpu ms", "nan", "isol", "kinetic J", "potential J", "fastest",
           "slide mm", "max mm", "RSS MB", "pairs", "points", "colours", "bodies", "pair cap",
           "grown");
    tb_vec3* first = malloc((dynamic ? dynamic : 1) * sizeof *first);
    int have_first = 0;
    double first_rss = 0, mid_energy = 0, last_energy = 0;
    int bad = 0;
    for (uint64_t done = 0; done < o.steps && !bad;) {
        uint32_t k = o.steps - done < o.every ? (uint32_t)(o.steps - done) : o.every;
        double t0 = now_ms();
        tb_result r = tb_world_step_n(w, sc->dt, k);
        double ms = (now_ms() - t0) / k;
        done += k;
        sample s;
        tb_world_stats st;
        if (r || measure(w, ids, dynamic, first, &have_first, &s) || tb_world_get_stats(w, &st)) {
            fprintf(stderr, "bench-soak: %s\n", tb_world_last_error(w));
            bad = 1;
            break;
        }
        double rss = resident_mb();
        if (first_rss == 0) first_rss = rss;
        double energy = s.kinetic + s.potential;
        if (done <= o.steps / 2 || mid_energy == 0) mid_energy = energy;
        last_energy = energy;
        printf("%10llu %8.3f %7.3f %6u %6u %14.2f %14.2f %10.4f %9.4f %9.4f %8.1f %8u %8u %7u "
               "%9u %9u %7llu\n",
               (unsigned long long)st.steps, ms, st.gpu_ms, s.non_finite, s.isolated, s.kinetic,
               s.potential, s.fastest, 1e3 * s.slide_mean, 1e3 * s.slide_max, rss, st.pair_count, st.contact_count, st.colour_count,
               st.body_capacity, st.pair_capacity, (unsigned long long)st.buffer_growths);
        fflush(stdout);
        if (s.non_finite) bad = 1;
        if (!bad && o.save && save_file(w, o.save)) bad = 1;
    }
    printf("summary: %s; total energy over the second half %+.3f J (%.4f %% of its size); "
           "resident memory after the first interval %+.1f MB\n",
           bad ? "FAILED (a body stopped being finite or a step failed)" : "every body finite",
           last_energy - mid_energy,
           mid_energy != 0 ? 100.0 * (last_energy - mid_energy) / fabs(mid_energy) : 0.0,
           resident_mb() - first_rss);
    sc->destroy(inst);
    tb_world_destroy(w);
    free(ids);
    free(first);
    return bad;
}
