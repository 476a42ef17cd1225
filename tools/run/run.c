/* tumble-run: what `make run` runs. Builds the default scene on the best device, steps it
 * in chunks with a progress line each (and a progress bar when stdout is a terminal), then
 * prints speed, stage times, checks and a few bodies' positions.
 *
 *   tumble-run [--scene NAME] [--n N] [--steps S] [--png PATH] [--window] [--contacts]
 *
 * --png writes a picture of the final frame (tools/render); --window shows the run live
 * when Tumble was built with GLFW and a display exists; --contacts draws the last step's
 * contact points and normals in either.
 * The device is the library's choice: TUMBLE_DEVICE if set, else the best GPU.
 */
#include "progress.h"
#include "render.h"
#include "scenes.h"
#include "tumble.h"
#include "tumble_vulkan.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CHUNKS 10
#define SHOWN_BODIES 3

typedef struct options {
    const char* scene_name; /* NULL: scene_default() */
    uint32_t n;             /* 0: the scene's default */
    uint32_t steps;         /* 0: the scene's default */
    const char* png;        /* NULL: no picture */
    int window;             /* show the run in a window */
    int contacts;           /* draw contact points and normals in the picture or window */
} options;

static void print_usage(FILE* f)
{
    fprintf(f, "usage: tumble-run [--scene NAME] [--n N] [--steps S] [--png PATH] [--window] "
               "[--contacts]\n");
    scene_print_list(f);
}

/* Returns -1 to go on, else the exit code (0 for --help, 2 for a bad command line). */
static int parse_args(int argc, char** argv, options* o)
{
    for (int i = 1; i < argc; i++) {
        const char* a = argv[i];
        const char* v = (i + 1 < argc) ? argv[i + 1] : NULL;
        int ok = v != NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            print_usage(stdout);
            return 0;
        } else if (strcmp(a, "--scene") == 0) {
            o->scene_name = v;
        } else if (strcmp(a, "--n") == 0) {
            ok = ok && scene_parse_u32(v, &o->n);
        } else if (strcmp(a, "--steps") == 0) {
            ok = ok && scene_parse_u32(v, &o->steps);
        } else if (strcmp(a, "--png") == 0) {
            o->png = v;
        } else if (strcmp(a, "--window") == 0) {
            o->window = 1;
            continue; /* takes no value */
        } else if (strcmp(a, "--contacts") == 0) {
            o->contacts = 1;
            continue; /* takes no value */
        } else {
            fprintf(stderr, "tumble-run: unknown option '%s'\n", a);
            print_usage(stderr);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "tumble-run: option '%s' needs a non-negative integer or name\n", a);
            return 2;
        }
        i++;
    }
    return -1;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int fail(const tb_world* world, const char* call, tb_result r)
{
    fprintf(stderr, "tumble-run: %s failed: %s: %s\n", call, tb_result_string(r),
            tb_world_last_error(world));
    return 1;
}

static int print_device(const tb_world* world)
{
    tb_device_info dev;
    tb_result r = tb_world_device_info(world, &dev);
    if (r != TB_OK) return fail(world, "tb_world_device_info", r);
    printf("device: %s\ndriver: %s\nsubgroup size: %u%s\n", dev.name, dev.driver,
           dev.subgroup_size, dev.is_cpu ? " (CPU device)" : "");
    return 0;
}

/* Steps in CHUNKS pieces with a progress line each (on a terminal, ten times as many
 * pieces, a bar redrawn after each and the lines above it); *wall_s gets the time spent
 * stepping (read-backs for the progress lines excluded). */
static int step_in_chunks(tb_world* world, const scene* sc, const tb_body_id* sample,
                          uint32_t steps, double* wall_s)
{
    progress bar;
    progress_begin(&bar, stdout, steps);
    const uint32_t per_line = bar.bar ? 10 : 1;
    const uint32_t pieces = CHUNKS * per_line;
    uint32_t done = 0;
    *wall_s = 0.0;
    progress_update(&bar, 0, "step 0/%u", steps);
    for (uint32_t c = 0; c < pieces && done < steps; c++) {
        /* Spread the remainder over the first pieces so the total is exactly `steps`. */
        uint32_t chunk = steps / pieces + (c < steps % pieces ? 1 : 0);
        if (chunk == 0) continue;
        double t0 = now_s();
        tb_result r = tb_world_step_n(world, sc->dt, chunk);
        *wall_s += now_s() - t0;
        if (r != TB_OK) {
            progress_end(&bar);
            return fail(world, "tb_world_step_n", r);
        }
        done += chunk;
        progress_update(&bar, done, "step %u/%u", done, steps);
        if ((c + 1) % per_line != 0 && done < steps) continue;
        char line[256];
        int len = snprintf(line, sizeof line, "step %6u  t = %7.3f s", done,
                           (double)done * sc->dt);
        if (sample) {
            tb_vec3 p;
            r = tb_world_read_transforms(world, sample, 1, &p, NULL);
            if (r != TB_OK) {
                progress_end(&bar);
                return fail(world, "tb_world_read_transforms", r);
            }
            len += snprintf(line + len, sizeof line - (size_t)len, "  body 0 height %.4f m", p.y);
        }
        tb_world_stats st;
        if (tb_world_get_stats(world, &st) == TB_OK)
            snprintf(line + len, sizeof line - (size_t)len,
                     "  pairs %u contacts %u colours %u  %.3f ms/step GPU", st.pair_count,
                     st.contact_count, st.colour_count, st.gpu_ms);
        progress_line(&bar, "%s", line);
    }
    progress_end(&bar);
    return 0;
}

/* The window's frame callback: one step per shown frame, progress every tenth (and a bar
 * on a terminal). */
typedef struct live_run {
    tb_world* world;
    const scene* sc;
    uint32_t steps, done;
    tb_result result;
    progress bar;
} live_run;

static int live_frame(void* user)
{
    live_run* run = user;
    if (run->done >= run->steps || run->result != TB_OK) return 0;
    run->result = tb_world_step(run->world, run->sc->dt);
    run->done++;
    progress_update(&run->bar, run->done, "step %u/%u", run->done, run->steps);
    if (run->done % (run->steps / CHUNKS ? run->steps / CHUNKS : 1) == 0)
        progress_line(&run->bar, "step %6u  t = %7.3f s", run->done,
                      (double)run->done * run->sc->dt);
    return run->result == TB_OK;
}

static int step_in_window(tb_world* world, const scene* sc, uint32_t steps, int contacts,
                          double* wall_s)
{
    tr_options ro = tr_default_options();
    ro.show_contacts = contacts;
    tr_renderer* renderer = NULL;
    tb_result r = tr_create(world, &ro, &renderer);
    if (r != TB_OK) return fail(world, "tr_create", r);
    live_run run = { world, sc, steps, 0, TB_OK, { 0 } };
    progress_begin(&run.bar, stdout, steps);
    const char* why = "";
    double t0 = now_s();
    r = tr_window_run(renderer, world, ro.width, ro.height, "Tumble", live_frame, &run, &why);
    *wall_s = now_s() - t0;
    progress_end(&run.bar);
    tr_destroy(renderer);
    if (r != TB_OK) fprintf(stderr, "tumble-run: window: %s\n", why);
    if (run.result != TB_OK) return fail(world, "tb_world_step", run.result);
    return r != TB_OK;
}

/* A picture of the world as it is now, framed automatically. */
static int write_picture(tb_world* world, const char* path, int contacts)
{
    tr_options ro = tr_default_options();
    ro.show_contacts = contacts;
    tr_renderer* renderer = NULL;
    tb_result r = tr_create(world, &ro, &renderer);
    if (r == TB_OK) r = tr_render(renderer);
    if (r == TB_OK) r = tr_write_png(renderer, path);
    if (r != TB_OK) {
        fprintf(stderr, "tumble-run: picture failed: %s\n",
                renderer ? tr_last_error(renderer) : tb_world_last_error(world));
        tr_destroy(renderer);
        return 1;
    }
    tr_destroy(renderer);
    printf("picture of the final frame: %s\n", path);
    return 0;
}

static int print_stats(const tb_world* world)
{
    tb_world_stats st;
    tb_result r = tb_world_get_stats(world, &st);
    if (r != TB_OK) return fail(world, "tb_world_get_stats", r);
    printf("bodies %u, steps %llu, submits %llu, records %llu, buffer growths %llu\n",
           st.body_count, (unsigned long long)st.steps, (unsigned long long)st.submits,
           (unsigned long long)st.records, (unsigned long long)st.buffer_growths);
    printf("last step GPU time %.4f ms\n", st.gpu_ms);
    for (uint32_t i = 0; i < st.stage_count && i < TB_MAX_STAGES; i++)
        printf("  %-32s %.4f ms\n", st.stages[i].name ? st.stages[i].name : "?",
               st.stages[i].ms);
    return 0;
}

static int print_checks(tb_world* world, const scene* sc, const scene_instance* inst,
                        uint32_t steps)
{
    scene_checks checks = { 0 };
    tb_result r = sc->check(world, inst, steps, sc->dt, &checks);
    if (r != TB_OK) return fail(world, "scene check", r);
    printf("checks:\n");
    for (uint32_t i = 0; i < checks.count; i++)
        printf("  %-12s %.6g\n", checks.items[i].key, checks.items[i].value);
    return 0;
}

static int print_bodies(tb_world* world, const tb_body_id* ids, uint32_t count)
{
    uint32_t shown = count < SHOWN_BODIES ? count : SHOWN_BODIES;
    tb_vec3 pos[SHOWN_BODIES];
    tb_quat rot[SHOWN_BODIES];
    if (shown == 0) return 0;
    tb_result r = tb_world_read_transforms(world, ids, shown, pos, rot);
    if (r != TB_OK) return fail(world, "tb_world_read_transforms", r);
    for (uint32_t i = 0; i < shown; i++)
        printf("body %u: position (%.4f, %.4f, %.4f) rotation (%.4f, %.4f, %.4f, %.4f)\n", i,
               pos[i].x, pos[i].y, pos[i].z, rot[i].x, rot[i].y, rot[i].z, rot[i].w);
    return 0;
}

/* Everything after world creation. Returns the exit code. */
static int run_scene(tb_world* world, const scene* sc, uint32_t n, uint32_t steps,
                     const options* o)
{
    scene_params params = { n, 1 };
    scene_instance* inst = NULL;
    tb_result r = sc->build(world, &params, &inst);
    if (r != TB_OK) return fail(world, "scene build", r);
    uint32_t count;
    const tb_body_id* ids = scene_body_ids(inst, &count);
    printf("scene %s: %u bodies, %u steps of %.5f s\n", sc->name, count, steps, sc->dt);

    double wall_s = 0.0;
    int code = o->window ? step_in_window(world, sc, steps, o->contacts, &wall_s)
                         : step_in_chunks(world, sc, count ? ids : NULL, steps, &wall_s);
    if (!code) {
        printf("%.1f steps/s (%.3f s wall for %u steps)\n",
               wall_s > 0.0 ? steps / wall_s : 0.0, wall_s, steps);
        code = print_stats(world);
    }
    if (!code) code = print_checks(world, sc, inst, steps);
    if (!code) code = print_bodies(world, ids, count);
    if (!code && o->png) code = write_picture(world, o->png, o->contacts);
    sc->destroy(inst);
    return code;
}

/* A window needs its surface and swapchain extensions on the world's instance and device.
 * Returns the exit code. */
static int create_world(const tb_world_def* def, int window, tb_world** out)
{
    tr_window_extensions wext;
    memset(&wext, 0, sizeof wext);
    const char* why = "";
    if (window && tr_window_prepare(&wext, &why) != TB_OK) {
        fprintf(stderr, "tumble-run: --window: %s\n", why);
        return 1;
    }
    tb_vulkan_extensions ext = { wext.instance, wext.instance_count, wext.device, wext.device_count };
    tb_result r = window ? tb_world_create_vulkan(def, &ext, out) : tb_world_create(def, out);
    return r != TB_OK ? fail(NULL, "tb_world_create", r) : 0;
}

int main(int argc, char** argv)
{
    options o = { NULL, 0, 0, NULL, 0, 0 };
    setvbuf(stdout, NULL, _IOLBF, 0);   /* progress shows line by line, piped too */
    int code = parse_args(argc, argv, &o);
    if (code >= 0) return code;
    const scene* sc = o.scene_name ? scene_find(o.scene_name) : scene_default();
    if (!sc) {
        fprintf(stderr, "tumble-run: unknown scene '%s'\n", o.scene_name);
        print_usage(stderr);
        return 2;
    }
    uint32_t n = o.n ? o.n : sc->default_n;
    uint32_t steps = o.steps ? o.steps : sc->default_steps;

    tb_world_def def = tb_default_world_def();
    def.initial_body_capacity = n <= UINT32_MAX - 16 ? n + 16 : n; /* no growth mid-run */
    tb_world* world = NULL;
    code = create_world(&def, o.window, &world);
    if (code) return code;
    code = print_device(world);
    if (!code) code = run_scene(world, sc, n, steps, &o);
    tb_world_destroy(world);
    return code;
}
