/* bench: times a scene step by step on one device and prints a table plus one JSON line.
 *
 *   bench --scene NAME --n N --steps S [--warmup W] [--seed K] [--device D]
 *         [--broadphase grid|sap|lbvh|isap] [--plugin FILE] [--csv FILE] [--json-only]
 *         [--help]
 *
 * N or S of 0 mean the scene's defaults (`make bench` passes 0 when they are unset).
 * The last line of stdout is always the JSON record, so scripts can take `tail -n 1`.
 * Progress of the timed steps goes before it (to stderr with --json-only): a bar redrawn in
 * place on a terminal, else a line every tenth of the steps.
 */
#include "progress.h"
#include "render.h"
#include "scenes.h"
#include "tumble.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>

#define STAGE_NAME_MAX 128

typedef struct options {
    const char* scene_name;
    uint32_t n;
    uint32_t steps;
    uint32_t warmup;
    uint32_t seed;
    const char* device;   /* NULL: the library's choice (TUMBLE_DEVICE, else best GPU) */
    tb_broadphase broadphase; /* TB_BROADPHASE_DEFAULT: the library's choice */
    const char* csv_path; /* NULL: no CSV row */
    int json_only;
    const char* frames;   /* NULL: no pictures; else a folder for frame_NNNNN.png */
    uint32_t every;       /* with frames: a picture every this many timed steps */
    int contacts;         /* with frames: draw contact points and normals */
    const char* plugin;   /* NULL: none; else a plugin loaded before the scene is built */
    uint32_t substeps, iterations; /* 0: the world's defaults */
    float hertz, damping;          /* < 0: the world's defaults */
    float reuse, reuse_angle;      /* < 0: the world's contact reuse bounds (m, rad) */
} options;

/* Pictures of the timed steps. Rendering happens between steps, outside the timings. */
typedef struct frame_writer {
    tr_renderer* renderer;  /* NULL: no frames */
    tr_options options;     /* the renderer's; the camera fixed after the first frame */
    const char* dir;
    uint32_t every, written;
} frame_writer;

/* Per-step samples of the timed steps. Stages are matched by name, not index, so a
 * stage that appears in only some steps still gets a correct median. */
typedef struct samples {
    uint32_t steps;
    double* gpu_ms;
    double* wall_ms;
    uint32_t stage_count;
    char stage_names[TB_MAX_STAGES][STAGE_NAME_MAX];
    double* stage_ms[TB_MAX_STAGES];
    uint32_t stage_samples[TB_MAX_STAGES];
} samples;

typedef struct summary {
    double gpu_median, gpu_p90, wall_median;
    double stage_median[TB_MAX_STAGES];
} summary;

/* ---- command line ---- */

static void print_usage(FILE* f)
{
    fprintf(f,
            "usage: bench --scene NAME [--n N] [--steps S] [--warmup W] [--seed K]\n"
            "             [--device D] [--broadphase B] [--plugin FILE] [--csv FILE] [--json-only]\n"
            "             [--frames DIR [--every K] [--contacts]]\n"
            "             [--substeps S] [--iterations I] [--hertz H] [--damping Z]\n"
            "             [--reuse D[,A]] [--help]\n"
            "  --n, --steps  0 or absent: the scene's default\n"
            "  --warmup      untimed steps before timing (default 10)\n"
            "  --seed        seed of the scene's jitter (default 1)\n"
            "  --device      device index or name substring (default: TUMBLE_DEVICE, else "
            "the best GPU)\n"
            "  --broadphase  grid, sap, lbvh or isap (default: TUMBLE_BROADPHASE, else the\n"
            "                library's choice)\n"
            "  --plugin      load this plugin (its default parameters) before the scene\n"
            "  --csv         append one result row to FILE (header written if new)\n"
            "  --json-only   print only the JSON line\n"
            "  --frames      write a PNG of every K-th timed step into DIR (tools/render/video\n"
            "                makes a video of them); --every defaults to 1\n"
            "  --contacts    draw contact points and normals in the frames\n"
            "  --substeps, --iterations, --hertz, --damping\n"
            "                the world's substeps, solver_iterations, contact_hertz and\n"
            "                contact_damping_ratio (default: tb_default_world_def's)\n"
            "  --reuse D[,A] tb_world_set_contact_reuse's distance in m and angle in rad (0: no\n"
            "                reuse; default: the world's, 0.001 and 2 degrees)\n");
    scene_print_list(f);
}

static int parse_broadphase(const char* text, tb_broadphase* out)
{
    for (int k = TB_BROADPHASE_GRID; tb_broadphase_name((tb_broadphase)k); k++)
        if (strcmp(text, tb_broadphase_name((tb_broadphase)k)) == 0) {
            *out = (tb_broadphase)k;
            return 1;
        }
    return 0;
}

/* Returns -1 to go on, else the exit code (0 for --help, 2 for a bad command line). */
static int parse_args(int argc, char** argv, options* o)
{
    for (int i = 1; i < argc; i++) {
        const char* a = argv[i];
        const char* v = (i + 1 < argc) ? argv[i + 1] : NULL;
        int ok = 1, takes_value = 1;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            print_usage(stdout);
            return 0;
        } else if (strcmp(a, "--json-only") == 0) {
            o->json_only = 1;
            takes_value = 0;
        } else if (strcmp(a, "--contacts") == 0) {
            o->contacts = 1;
            takes_value = 0;
        } else if (!v) {
            ok = 0;
        } else if (strcmp(a, "--scene") == 0) {
            o->scene_name = v;
        } else if (strcmp(a, "--device") == 0) {
            o->device = v;
        } else if (strcmp(a, "--broadphase") == 0) {
            ok = parse_broadphase(v, &o->broadphase);
        } else if (strcmp(a, "--plugin") == 0) {
            o->plugin = v;
        } else if (strcmp(a, "--csv") == 0) {
            o->csv_path = v;
        } else if (strcmp(a, "--n") == 0) {
            ok = scene_parse_u32(v, &o->n);
        } else if (strcmp(a, "--steps") == 0) {
            ok = scene_parse_u32(v, &o->steps);
        } else if (strcmp(a, "--warmup") == 0) {
            ok = scene_parse_u32(v, &o->warmup);
        } else if (strcmp(a, "--seed") == 0) {
            ok = scene_parse_u32(v, &o->seed);
        } else if (strcmp(a, "--frames") == 0) {
            o->frames = v;
        } else if (strcmp(a, "--substeps") == 0) {
            ok = scene_parse_u32(v, &o->substeps);
        } else if (strcmp(a, "--iterations") == 0) {
            ok = scene_parse_u32(v, &o->iterations);
        } else if (strcmp(a, "--reuse") == 0) {
            int got = sscanf(v, "%f,%f", &o->reuse, &o->reuse_angle);
            ok = got >= 1 && o->reuse >= 0 && (got == 1 || o->reuse_angle >= 0);
        } else if (strcmp(a, "--hertz") == 0 || strcmp(a, "--damping") == 0) {
            char* end = NULL;
            double x = strtod(v, &end);
            ok = end != v && *end == 0 && x >= 0;
            if (ok) *(a[2] == 'h' ? &o->hertz : &o->damping) = (float)x;
        } else if (strcmp(a, "--every") == 0) {
            ok = scene_parse_u32(v, &o->every) && o->every > 0;
        } else {
            fprintf(stderr, "bench: unknown option '%s'\n", a);
            print_usage(stderr);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "bench: option '%s' needs a value%s\n", a,
                    !v ? "" : strcmp(a, "--broadphase") == 0 ? ": grid, sap, lbvh or isap"
                                                             : " that is a non-negative number");
            return 2;
        }
        i += takes_value;
    }
    return -1;
}

/* ---- statistics ---- */

static int cmp_double(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

/* Nearest-rank percentile (p in (0, 1]) of n values; sorts a copy. NAN when n is 0. */
static double percentile(const double* values, uint32_t n, double p)
{
    if (n == 0) return NAN;
    double* sorted = malloc(n * sizeof *sorted);
    if (!sorted) return NAN;
    memcpy(sorted, values, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, cmp_double);
    uint32_t rank = (uint32_t)ceil(p * n);
    double v = sorted[rank ? rank - 1 : 0];
    free(sorted);
    return v;
}

static double median(const double* values, uint32_t n)
{
    if (n == 0) return NAN;
    double* sorted = malloc(n * sizeof *sorted);
    if (!sorted) return NAN;
    memcpy(sorted, values, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, cmp_double);
    double v = (n % 2) ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    free(sorted);
    return v;
}

/* ---- samples ---- */

static int samples_init(samples* s, uint32_t steps)
{
    memset(s, 0, sizeof *s);
    s->steps = steps;
    size_t n = steps ? steps : 1;
    s->gpu_ms = malloc(n * sizeof *s->gpu_ms);
    s->wall_ms = malloc(n * sizeof *s->wall_ms);
    return s->gpu_ms && s->wall_ms;
}

static void samples_free(samples* s)
{
    free(s->gpu_ms);
    free(s->wall_ms);
    for (uint32_t i = 0; i < s->stage_count; i++) free(s->stage_ms[i]);
}

/* Index of the stage named `name`, adding it if new; -1 when out of room. */
static int samples_stage(samples* s, const char* name)
{
    for (uint32_t i = 0; i < s->stage_count; i++)
        if (strcmp(s->stage_names[i], name) == 0) return (int)i;
    if (s->stage_count == TB_MAX_STAGES) return -1;
    uint32_t i = s->stage_count;
    s->stage_ms[i] = malloc((s->steps ? s->steps : 1) * sizeof(double));
    if (!s->stage_ms[i]) return -1;
    snprintf(s->stage_names[i], STAGE_NAME_MAX, "%s", name);
    s->stage_count++;
    return (int)i;
}

static void samples_add(samples* s, uint32_t step, double wall_ms, const tb_world_stats* st)
{
    s->wall_ms[step] = wall_ms;
    s->gpu_ms[step] = st->gpu_ms;
    for (uint32_t i = 0; i < st->stage_count && i < TB_MAX_STAGES; i++) {
        int k = samples_stage(s, st->stages[i].name ? st->stages[i].name : "?");
        if (k < 0) continue;
        s->stage_ms[k][s->stage_samples[k]++] = st->stages[i].ms;
    }
}

static void summarise(const samples* s, summary* out)
{
    out->gpu_median = median(s->gpu_ms, s->steps);
    out->gpu_p90 = percentile(s->gpu_ms, s->steps, 0.9);
    out->wall_median = median(s->wall_ms, s->steps);
    for (uint32_t i = 0; i < s->stage_count; i++)
        out->stage_median[i] = median(s->stage_ms[i], s->stage_samples[i]);
}

/* ---- running ---- */

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int fail(const tb_world* world, const char* call, tb_result r)
{
    fprintf(stderr, "bench: %s failed: %s: %s\n", call, tb_result_string(r),
            tb_world_last_error(world));
    return 1;
}

/* The first frame frames the scene automatically; later ones keep that camera so the
 * video does not swim. */
static tb_result write_frame(frame_writer* f)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/frame_%05u.png", f->dir, f->written);
    tb_result r = tr_render(f->renderer);
    if (r == TB_OK && f->written == 0) {
        f->options.camera = tr_last_camera(f->renderer);
        f->options.camera.automatic = 0;
        r = tr_set_options(f->renderer, &f->options);
    }
    if (r == TB_OK) r = tr_write_png(f->renderer, path);
    if (r != TB_OK) fprintf(stderr, "bench: frame %s: %s\n", path, tr_last_error(f->renderer));
    f->written++;
    return r;
}

/* Progress of the timed steps between them, outside the timings: a bar on a terminal, a
 * line every tenth otherwise; on stderr with --json-only (stdout is the JSON alone). */
static tb_result timed_steps(tb_world* world, float dt, samples* s, frame_writer* frames,
                             FILE* progress_out)
{
    progress bar;
    progress_begin(&bar, progress_out, s->steps);
    const uint32_t tenth = s->steps / 10 ? s->steps / 10 : 1;
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < s->steps && r == TB_OK; i++) {
        double t0 = now_ms();
        r = tb_world_step(world, dt);
        double t1 = now_ms();
        if (r == TB_OK && frames->renderer && i % frames->every == 0) r = write_frame(frames);
        tb_world_stats st;
        if (r == TB_OK) r = tb_world_get_stats(world, &st);
        if (r != TB_OK) break;
        samples_add(s, i, t1 - t0, &st);
        uint32_t done = i + 1;
        if (frames->renderer)
            progress_update(&bar, done, "step %u/%u, %u frames", done, s->steps, frames->written);
        else
            progress_update(&bar, done, "step %u/%u", done, s->steps);
        if ((done % tenth == 0 || done == s->steps) && frames->renderer)
            progress_line(&bar, "step %6u/%u  %.3f ms GPU  %.3f ms wall  %u frames", done,
                          s->steps, st.gpu_ms, t1 - t0, frames->written);
        else if (done % tenth == 0 || done == s->steps)
            progress_line(&bar, "step %6u/%u  %.3f ms GPU  %.3f ms wall", done, s->steps,
                          st.gpu_ms, t1 - t0);
    }
    progress_end(&bar);
    return r;
}

/* ---- output ---- */

/* JSON numbers cannot be NaN or infinite; those become null. */
static void json_number(FILE* f, double v)
{
    if (isfinite(v)) fprintf(f, "%.9g", v);
    else fputs("null", f);
}

static void json_string(FILE* f, const char* text)
{
    fputc('"', f);
    for (const unsigned char* p = (const unsigned char*)text; *p; p++) {
        if (*p == '"' || *p == '\\') fprintf(f, "\\%c", *p);
        else if (*p == '\n') fputs("\\n", f);
        else if (*p == '\t') fputs("\\t", f);
        else if (*p < 0x20) fprintf(f, "\\u%04x", *p);
        else fputc(*p, f);
    }
    fputc('"', f);
}

static void json_key(FILE* f, const char* key)
{
    fputs(", ", f);
    json_string(f, key);
    fputs(": ", f);
}

typedef struct report {
    const tb_device_info* dev;
    const scene* sc;
    uint32_t n, steps, body_count;
    const char* broadphase;
    const samples* s;
    const summary* sum;
    const scene_checks* checks;
} report;

static void print_json(FILE* f, const report* r)
{
    fputs("{\"device\": ", f);
    json_string(f, r->dev->name);
    json_key(f, "driver");
    json_string(f, r->dev->driver);
    fprintf(f, ", \"subgroup_size\": %u", r->dev->subgroup_size);
    json_key(f, "scene");
    json_string(f, r->sc->name);
    fprintf(f, ", \"n\": %u, \"steps\": %u", r->n, r->steps);
    json_key(f, "broadphase");
    json_string(f, r->broadphase);
    json_key(f, "ms_step_median");
    json_number(f, r->sum->gpu_median);
    json_key(f, "ms_step_p90");
    json_number(f, r->sum->gpu_p90);
    json_key(f, "ms_wall_median");
    json_number(f, r->sum->wall_median);
    fputs(", \"stages\": {", f);
    for (uint32_t i = 0; i < r->s->stage_count; i++) {
        if (i) fputs(", ", f);
        json_string(f, r->s->stage_names[i]);
        fputs(": ", f);
        json_number(f, r->sum->stage_median[i]);
    }
    fprintf(f, "}, \"body_count\": %u", r->body_count);
    for (uint32_t i = 0; i < r->checks->count; i++) {
        json_key(f, r->checks->items[i].key);
        json_number(f, r->checks->items[i].value);
    }
    fputs("}\n", f);
}

static void print_table(FILE* f, const report* r)
{
    fprintf(f, "device         %s\n", r->dev->name);
    fprintf(f, "driver         %s\n", r->dev->driver);
    fprintf(f, "subgroup size  %u\n", r->dev->subgroup_size);
    fprintf(f, "scene          %s\n", r->sc->name);
    fprintf(f, "n              %u (bodies %u)\n", r->n, r->body_count);
    fprintf(f, "steps          %u\n", r->steps);
    fprintf(f, "broadphase     %s\n", r->broadphase);
    fprintf(f, "gpu ms/step    median %.4f  p90 %.4f\n", r->sum->gpu_median, r->sum->gpu_p90);
    fprintf(f, "wall ms/step   median %.4f\n", r->sum->wall_median);
    fprintf(f, "stages (median ms)\n");
    for (uint32_t i = 0; i < r->s->stage_count; i++)
        fprintf(f, "  %-32s %.4f\n", r->s->stage_names[i], r->sum->stage_median[i]);
    fprintf(f, "checks\n");
    for (uint32_t i = 0; i < r->checks->count; i++)
        fprintf(f, "  %-32s %.6g\n", r->checks->items[i].key, r->checks->items[i].value);
}

/* A CSV field, quoted because device names contain commas ("llvmpipe (LLVM 15, 256 bits)"). */
static void csv_string(FILE* f, const char* text)
{
    fputc('"', f);
    for (const char* p = text; *p; p++) {
        if (*p == '"') fputc('"', f);
        fputc(*p, f);
    }
    fputc('"', f);
}

static int append_csv(const char* path, const report* r)
{
    FILE* f = fopen(path, "a");
    if (!f) {
        fprintf(stderr, "bench: cannot open '%s' for appending: %s\n", path, strerror(errno));
        return 0;
    }
    /* "a" mode's initial position is implementation-defined; seek to learn the size. */
    fseek(f, 0, SEEK_END);
    if (ftell(f) == 0)
        fputs("device,scene,n,steps,ms_step_median,ms_step_p90,ms_wall_median,stages,checks,"
              "broadphase\n", f);
    csv_string(f, r->dev->name);
    fprintf(f, ",%s,%u,%u,%.6f,%.6f,%.6f,\"", r->sc->name, r->n, r->steps,
            r->sum->gpu_median, r->sum->gpu_p90, r->sum->wall_median);
    for (uint32_t i = 0; i < r->s->stage_count; i++)
        fprintf(f, "%s%s=%.6f", i ? ";" : "", r->s->stage_names[i], r->sum->stage_median[i]);
    fputs("\",\"", f);
    for (uint32_t i = 0; i < r->checks->count; i++)
        fprintf(f, "%s%s=%.10g", i ? ";" : "", r->checks->items[i].key, r->checks->items[i].value);
    fprintf(f, "\",%s\n", r->broadphase);
    int ok = !ferror(f);
    if (fclose(f) != 0) ok = 0;
    if (!ok) fprintf(stderr, "bench: writing '%s' failed\n", path);
    return ok;
}

/* ---- main ---- */

/* Dispatches in the step as last recorded: the library says so at TB_LOG_DEBUG. Warnings
 * and errors go to stderr, as without a log callback. */
static uint32_t recorded_dispatches;

static void bench_log(void* user, tb_log_level level, const char* message)
{
    (void)user;
    unsigned stages, dispatches;
    if (sscanf(message, "step recorded: %u stages, %u dispatches", &stages, &dispatches) == 2)
        recorded_dispatches = dispatches;
    if (level >= TB_LOG_WARNING)
        fprintf(stderr, "tumble %s: %s\n", level == TB_LOG_ERROR ? "error" : "warning", message);
}

static tb_world* create_world(const options* o)
{
    tb_world_def def = tb_default_world_def();
    /* Room beyond n so the timed steps never grow buffers (growth re-records). */
    def.initial_body_capacity = o->n <= UINT32_MAX - 16 ? o->n + 16 : o->n;
    def.device = o->device;
    def.broadphase = o->broadphase;
    if (o->substeps) def.substeps = o->substeps;
    if (o->iterations) def.solver_iterations = o->iterations;
    if (o->hertz >= 0) def.contact_hertz = o->hertz;
    if (o->damping >= 0) def.contact_damping_ratio = o->damping;
    def.log = bench_log;
    tb_world* world = NULL;
    tb_result r = tb_world_create(&def, &world);
    if (r != TB_OK) fail(NULL, "tb_world_create", r);
    float angle;
    tb_world_get_contact_reuse(world, NULL, &angle);
    if (o->reuse_angle >= 0) angle = o->reuse_angle;
    if (o->reuse >= 0 && (r = tb_world_set_contact_reuse(world, o->reuse, angle)) != TB_OK)
        fail(world, "tb_world_set_contact_reuse", r);
    return world;
}

/* Builds, warms up, times and checks; fills what the report needs. Returns the exit code. */
static int run_bench(tb_world* world, const scene* sc, const options* o, samples* s,
                     tb_device_info* dev, scene_checks* checks, uint32_t* body_count,
                     const char** broadphase)
{
    tb_result r = tb_world_device_info(world, dev);
    if (r != TB_OK) return fail(world, "tb_world_device_info", r);
    tb_plugin_id plugin;
    if (o->plugin && (r = tb_world_load_plugin(world, o->plugin, &plugin)) != TB_OK)
        return fail(world, "tb_world_load_plugin", r);
    scene_params params = { o->n, o->seed };
    scene_instance* inst = NULL;
    r = sc->build(world, &params, &inst);
    if (r != TB_OK) return fail(world, "scene build", r);
    tb_world_stats st;
    frame_writer frames = { NULL, tr_default_options(), o->frames, o->every, 0 };
    frames.options.show_contacts = o->contacts;
    int code = 0;
    if (o->frames) mkdir(o->frames, 0777); /* an existing folder is fine */
    if (o->frames && (r = tr_create(world, &frames.options, &frames.renderer)) != TB_OK)
        code = fail(world, "tr_create", r);
    else if (o->warmup && (r = tb_world_step_n(world, sc->dt, o->warmup)) != TB_OK)
        code = fail(world, "tb_world_step_n (warm-up)", r);
    else if ((r = timed_steps(world, sc->dt, s, &frames, o->json_only ? stderr : stdout)) != TB_OK)
        code = fail(world, "tb_world_step", r);
    else if ((r = sc->check(world, inst, o->warmup + o->steps, sc->dt, checks)) != TB_OK)
        code = fail(world, "scene check", r);
    else if ((r = tb_world_get_stats(world, &st)) != TB_OK)
        code = fail(world, "tb_world_get_stats", r);
    else
        *body_count = st.body_count, *broadphase = st.broadphase;
    if (!code && checks->count < SCENE_MAX_CHECKS) {   /* the step's dependent dispatches */
        checks->items[checks->count].key = "dispatches";
        checks->items[checks->count++].value = recorded_dispatches;
    }
    if (!code && checks->count < SCENE_MAX_CHECKS) {   /* colours the last step's sweeps ran */
        checks->items[checks->count].key = "colours";
        checks->items[checks->count++].value = st.colour_count;
    }
    if (!code && checks->count < SCENE_MAX_CHECKS) {   /* steps run again (a buffer grew, or
                                                          more colours were needed) */
        checks->items[checks->count].key = "redone";
        checks->items[checks->count++].value = (double)st.steps_redone;
    }
    tr_destroy(frames.renderer);
    sc->destroy(inst);
    return code;
}

int main(int argc, char** argv)
{
    options o = { NULL, 0, 0, 10, 1, NULL, TB_BROADPHASE_DEFAULT, NULL, 0, NULL, 1, 0, NULL,
                  0, 0, -1.0f, -1.0f, -1.0f, -1.0f };
    setvbuf(stdout, NULL, _IOLBF, 0);   /* progress shows line by line, piped too */
    int code = parse_args(argc, argv, &o);
    if (code >= 0) return code;
    const scene* sc = scene_find(o.scene_name ? o.scene_name : scene_default()->name);
    if (!sc) {
        fprintf(stderr, "bench: unknown scene '%s'\n", o.scene_name);
        scene_print_list(stderr);
        return 2;
    }
    if (o.n == 0) o.n = sc->default_n;
    if (o.steps == 0) o.steps = sc->default_steps;

    samples s;
    if (!samples_init(&s, o.steps)) {
        fprintf(stderr, "bench: out of host memory for %u samples\n", o.steps);
        return 1;
    }
    tb_world* world = create_world(&o);
    if (!world) {
        samples_free(&s);
        return 1;
    }
    tb_device_info dev;
    scene_checks checks = { 0 };
    uint32_t body_count = 0;
    const char* broadphase = "";   /* the library's static name: valid after the world */
    code = run_bench(world, sc, &o, &s, &dev, &checks, &body_count, &broadphase);
    tb_world_destroy(world);
    if (code == 0) {
        summary sum;
        summarise(&s, &sum);
        report rep = { &dev, sc, o.n, o.steps, body_count, broadphase, &s, &sum, &checks };
        if (!o.json_only) print_table(stdout, &rep);
        print_json(stdout, &rep);
        if (o.csv_path && !append_csv(o.csv_path, &rep)) code = 1;
    }
    samples_free(&s);
    return code;
}
