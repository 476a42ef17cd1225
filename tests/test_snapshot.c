/* Snapshots (tb_world_snapshot, tb_world_restore): a world restored continues bit for bit
 * as it did after the snapshot, in the same world, in a new world and in a new process;
 * bodies made or destroyed after the snapshot are undone; bad bytes and mismatched worlds
 * are refused and change nothing. */
#include "harness.h"

#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define DT (1.0f / 60.0f)
#define PILE 60
#define BEFORE 40    /* steps before the snapshot */
#define AFTER 500    /* steps after it */

extern char** environ;

typedef struct pile {
    tb_body_id ids[PILE];
    tb_shape_id extra;   /* a shape no body uses (worlds must make it too) */
} pile;

/* A world of the given broadphase with the pile's shapes, its bodies not yet made. */
static tb_world* pile_world(tb_broadphase broadphase, int shapes_differ)
{
    tb_world_def def = tb_default_world_def();
    def.broadphase = broadphase;
    return th_world_create_ex(&def, shapes_differ);
}

static void make_pile(tb_world* w, pile* p, int shapes_differ)
{
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shapes[4] = { th_box(w, th_v3(0.3f, 0.2f, shapes_differ ? 0.3f : 0.25f)),
                              th_sphere(w, 0.25f), th_rock(w) };
    th_assert_ok(tb_shape_create_capsule(w, &sd, 0.15f, 0.2f, &shapes[3]));
    p->extra = th_sphere(w, 1.0f);
    th_rng rng = th_rng_seed(77);
    for (int i = 0; i < PILE; i++) {
        tb_body_def d = th_dynamic_def(shapes[i % 4], th_v3(th_rng_range(&rng, -1.2f, 1.2f),
                                       0.4f + 0.45f * (float)(i / 8), th_rng_range(&rng, -1.2f, 1.2f)));
        d.rotation = th_rng_quat(&rng);
        p->ids[i] = th_body(w, &d);
    }
}

/* FNV-1a of every pile body's pose and velocities. */
static uint64_t pile_hash(tb_world* w, const pile* p)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (int i = 0; i < PILE; i++) {
        tb_vec3 pos, v, av;
        tb_quat q;
        th_read_pose(w, p->ids[i], &pos, &q);
        th_assert_ok(tb_body_get_velocity(w, p->ids[i], &v, &av));
        const void* parts[4] = { &pos, &q, &v, &av };
        size_t sizes[4] = { sizeof pos, sizeof q, sizeof v, sizeof av };
        for (int k = 0; k < 4; k++)
            for (size_t b = 0; b < sizes[k]; b++)
                h = (h ^ ((const unsigned char*)parts[k])[b]) * 0x100000001b3ull;
    }
    return h;
}

static void* take_snapshot(tb_world* w, size_t* size)
{
    th_assert_ok(tb_world_snapshot(w, NULL, 0, size));
    void* bytes = malloc(*size);
    assert_non_null(bytes);
    size_t written = 0;
    th_assert_ok(tb_world_snapshot(w, bytes, *size, &written));
    assert_true(written == *size);
    return bytes;
}

/* A pile world stepped BEFORE times, its snapshot (returned, its size in *size), then
 * `after` steps more, whose end state's hash goes to *first. */
static void* snapshot_and_run(tb_broadphase broadphase, int after, tb_world** w, pile* p,
                              size_t* size, uint64_t* first)
{
    *w = pile_world(broadphase, 0);
    make_pile(*w, p, 0);
    th_assert_ok(tb_world_step_n(*w, DT, BEFORE));
    void* snapshot = take_snapshot(*w, size);
    th_assert_ok(tb_world_step_n(*w, DT, after));
    *first = pile_hash(*w, p);
    return snapshot;
}

/* Snapshot, `after` steps, restore, `after` steps: the same state bit for bit, and a new
 * world given the snapshot ends there too. */
static void continues_identically(tb_broadphase broadphase, int after)
{
    tb_world* w;
    pile p;
    size_t size;
    uint64_t first;
    void* snapshot = snapshot_and_run(broadphase, after, &w, &p, &size, &first);
    tb_body_def late = th_dynamic_def(p.extra, th_v3(0, 8, 0));   /* undone by the restore */
    tb_body_id extra = th_body(w, &late);
    th_assert_ok(tb_body_destroy(w, p.ids[3]));                   /* brought back by it */
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_world_restore(w, snapshot, size));
    assert_false(tb_body_is_valid(w, extra));
    assert_true(tb_body_is_valid(w, p.ids[3]));
    assert_int_equal(th_stats(w).body_count, PILE + 1);
    th_assert_ok(tb_world_step_n(w, DT, after));
    assert_true(pile_hash(w, &p) == first);
    assert_int_equal(th_stats(w).steps, BEFORE + after);
    th_world_destroy(w);

    tb_world* other = pile_world(broadphase, 0);
    pile q;
    make_pile(other, &q, 0);
    th_assert_ok(tb_world_restore(other, snapshot, size));
    th_assert_ok(tb_world_step_n(other, DT, after));
    assert_true(pile_hash(other, &q) == first);
    th_world_destroy(other);
    free(snapshot);
}

static void test_restore_continues_identically(void** state)
{
    (void)state;
    continues_identically(TB_BROADPHASE_LBVH, AFTER);
}

/* The grid and sap (which keeps the axis it chose for the next step) and isap (which a
 * restore starts afresh); on one of lavapipe's widths, the new process on the other. */
static void test_restore_under_every_broadphase(void** state)
{
    (void)state;
    if (!th_large_scene_runs("every broadphase's restore", "256")) return;
    continues_identically(TB_BROADPHASE_GRID, 150);
    continues_identically(TB_BROADPHASE_SAP, 150);
    continues_identically(TB_BROADPHASE_ISAP, 150);
}

/* In a new process (this binary again, told to restore the file and print its hash). */
static void test_restore_in_a_new_process(void** state)
{
    (void)state;
    if (!th_large_scene_runs("the restore in a new process", "128")) return;
    tb_world* w;
    pile p;
    size_t size;
    uint64_t first;
    void* snapshot = snapshot_and_run(TB_BROADPHASE_LBVH, AFTER, &w, &p, &size, &first);
    th_world_destroy(w);
    char path[] = "/tmp/tumble-snapshot-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_true(write(fd, snapshot, size) == (ssize_t)size);
    close(fd);
    free(snapshot);
    char out[] = "/tmp/tumble-snapshot-hash-XXXXXX";
    int out_fd = mkstemp(out);
    assert_true(out_fd >= 0);
    close(out_fd);
    char* argv[] = { "test_snapshot", "--restore", path, out, NULL };
    pid_t pid;
    assert_int_equal(posix_spawn(&pid, "/proc/self/exe", NULL, NULL, argv, environ), 0);
    int status = 0;
    pid_t waited = waitpid(pid, &status, 0);
    unsigned long long there = 0;
    FILE* f = fopen(out, "r");
    int read = f ? fscanf(f, "%llx", &there) : 0;
    if (f) fclose(f);
    unlink(path);
    unlink(out);
    assert_true(waited == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0);
    assert_int_equal(read, 1);
    assert_true(there == first);
}

/* The child of test_restore_in_a_new_process: restore `path`, step, write the hash to `out`. */
static int restore_child(const char* path, const char* out)
{
    FILE* f = fopen(path, "rb");
    if (!f) return 2;
    static unsigned char bytes[1 << 24];
    size_t size = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    tb_world_def def = tb_default_world_def();
    def.broadphase = TB_BROADPHASE_LBVH;
    def.validation = 1;
    tb_world* w = NULL;
    if (tb_world_create(&def, &w)) return 3;
    pile p;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id plane, shapes[4];
    tb_vec3 rock[8];
    for (int i = 0; i < 8; i++)
        rock[i] = th_v3(i & 1 ? 0.1f : -0.1f, i & 2 ? 0.12f : -0.1f, i & 4 ? 0.1f : -0.08f);
    if (tb_shape_create_plane(w, &sd, th_v3(0, 1, 0), 0, &plane) ||
        tb_shape_create_box(w, &sd, th_v3(0.3f, 0.2f, 0.25f), &shapes[0]) ||
        tb_shape_create_sphere(w, &sd, 0.25f, &shapes[1]) ||
        tb_shape_create_hull(w, &sd, rock, 8, &shapes[2]) ||
        tb_shape_create_capsule(w, &sd, 0.15f, 0.2f, &shapes[3]) ||
        tb_shape_create_sphere(w, &sd, 1.0f, &p.extra))
        return 4;
    if (tb_world_restore(w, bytes, size)) {
        fprintf(stderr, "restore: %s\n", tb_world_last_error(w));
        return 5;
    }
    tb_body_id all[PILE + 1];
    if (tb_world_body_ids(w, all, PILE + 1) != PILE + 1) return 6;
    memcpy(p.ids, all + 1, sizeof p.ids);   /* slot order: the ground, then the pile */
    if (tb_world_step_n(w, DT, AFTER)) return 7;
    tb_world_stats st;
    tb_world_get_stats(w, &st);
    uint64_t h = pile_hash(w, &p);
    tb_world_destroy(w);
    if (st.validation_messages) return 8;
    f = fopen(out, "w");
    if (!f) return 9;
    fprintf(f, "%llx\n", (unsigned long long)h);
    fclose(f);
    return 0;
}

/* Refused with a sentence, the world unchanged: not a snapshot, cut short, damaged (in its
 * sections or its header), another world's shapes, another broadphase; NULL arguments; too
 * small a buffer. */
static void test_bad_snapshots_are_refused(void** state)
{
    (void)state;
    tb_world* w = pile_world(TB_BROADPHASE_LBVH, 1);
    pile p;
    make_pile(w, &p, 0);
    th_assert_ok(tb_world_step_n(w, DT, 5));
    size_t size;
    unsigned char* snapshot = take_snapshot(w, &size);
    size_t small = 0;
    unsigned char tiny[16];
    th_assert_result(tb_world_snapshot(w, tiny, sizeof tiny, &small), TB_ERROR_CAPACITY);
    assert_true(small == size);
    th_assert_result(tb_world_snapshot(w, NULL, 0, NULL), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_world_snapshot(w, NULL, 8, &small), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_world_restore(w, NULL, size), TB_ERROR_INVALID_ARGUMENT);
    th_assert_ok(tb_world_step_n(w, DT, 5));
    uint64_t before = pile_hash(w, &p);
    struct { const char* what; size_t size; size_t flip; const char* says; } bad[] = {
        { "garbage", 64, 0, "not a Tumble snapshot" },
        { "cut short", size - 16, size, "size does not match" },
        { "one byte flipped", size, size / 2, "checksum" },
        /* The header's step count, 40 bytes in: restored, it made the next step count more
         * steps done than it submitted (found by the fuzz target). */
        { "the header's step count flipped", size, 40, "checksum" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        unsigned char* copy = malloc(size);
        memcpy(copy, snapshot, size);
        if (i == 0) memset(copy, 0x5a, 64);
        if (bad[i].flip < size) copy[bad[i].flip] ^= 0x10;
        th_assert_result(tb_world_restore(w, copy, bad[i].size), TB_ERROR_INVALID_ARGUMENT);
        assert_non_null(strstr(tb_world_last_error(w), bad[i].says));
        free(copy);
    }
    assert_true(pile_hash(w, &p) == before);
    tb_world* differs = pile_world(TB_BROADPHASE_LBVH, 1);
    pile q;
    make_pile(differs, &q, 1);
    th_assert_result(tb_world_restore(differs, snapshot, size), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(differs), "shapes differ"));
    th_world_destroy(differs);
    tb_world* grid = pile_world(TB_BROADPHASE_GRID, 1);
    make_pile(grid, &q, 0);
    th_assert_result(tb_world_restore(grid, snapshot, size), TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(grid), "broadphase"));
    th_world_destroy(grid);
    th_assert_ok(tb_world_step(w, DT));
    free(snapshot);
    th_world_destroy(w);
}

/* A restore hands the shapes' bodies over and leaves their compounds: a compound's child
 * stays in use, and a shape stays in use by the bodies the snapshot has (found by the fuzz
 * target: a restore forgot the compounds, and destroying one then wrapped its child's
 * count of users around). */
static void test_restore_keeps_shape_users(void** state)
{
    (void)state;
    tb_world* w = pile_world(TB_BROADPHASE_LBVH, 0);
    tb_shape_id ball = th_sphere(w, 0.5f);
    tb_compound_child child = { ball, th_v3(0, 0, 0), { 0, 0, 0, 1 } };
    tb_shape_id compound, box = th_box(w, th_v3(0.5f, 0.5f, 0.5f));
    th_assert_ok(tb_shape_create_compound(w, &child, 1, &compound));
    tb_body_def d = th_dynamic_def(box, th_v3(0, 2, 0));
    tb_body_id body = th_body(w, &d);
    size_t size;
    unsigned char* snapshot = take_snapshot(w, &size);
    th_assert_ok(tb_body_destroy(w, body));
    th_assert_ok(tb_world_restore(w, snapshot, size));
    th_assert_result(tb_shape_destroy(w, ball), TB_ERROR_IN_USE);   /* its compound's */
    th_assert_result(tb_shape_destroy(w, box), TB_ERROR_IN_USE);    /* the restored body's */
    th_assert_ok(tb_world_restore(w, snapshot, size));              /* twice: no double count */
    th_assert_ok(tb_shape_destroy(w, compound));
    th_assert_ok(tb_shape_destroy(w, ball));
    th_assert_ok(tb_body_destroy(w, body));
    th_assert_ok(tb_shape_destroy(w, box));
    free(snapshot);
    th_world_destroy(w);
}

int main(int argc, char** argv)
{
    if (argc == 4 && strcmp(argv[1], "--restore") == 0) return restore_child(argv[2], argv[3]);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_restore_continues_identically),
        cmocka_unit_test(test_restore_under_every_broadphase),
        cmocka_unit_test(test_restore_in_a_new_process),
        cmocka_unit_test(test_bad_snapshots_are_refused),
        cmocka_unit_test(test_restore_keeps_shape_users),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
