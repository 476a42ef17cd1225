/* Shader hot-reload: a world runs the step's shaders from a copy of glsl/; an edit of the
 * substep shader (and then of a file it includes) changes the fall of a body within a step
 * or two, without a restart; a syntax error is reported as file:line: message while the
 * world steps on with the last good pipeline; fixing it is picked up again. A plugin stage
 * given as GLSL is watched the same way. */
#define _XOPEN_SOURCE 700 /* mkdtemp, setenv */
#include "harness.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/plugins/blast.h"

#define DT (1.0f / 60.0f)
#define MAX_STEPS_TO_SEE 3

static char shader_dir[64];

static int copy_shaders(void** state)
{
    (void)state;
    snprintf(shader_dir, sizeof shader_dir, "/tmp/tumble-shaders-XXXXXX");
    char command[4096];
    if (!mkdtemp(shader_dir)) return -1;
    snprintf(command, sizeof command, "cp -R '%s/glsl/.' '%s'", TB_SOURCE_DIR, shader_dir);
    return system(command) == 0 ? 0 : -1;
}

static int remove_shaders(void** state)
{
    (void)state;
    char command[256];
    snprintf(command, sizeof command, "rm -rf '%s'", shader_dir);
    return system(command) == 0 ? 0 : -1;
}

static char* read_text(const char* path)
{
    FILE* f = fopen(path, "rb");
    assert_non_null(f);
    static char text[1 << 16];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    return text;
}

static void write_text(const char* path, const char* text)
{
    FILE* f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, strlen(text), f), strlen(text));
    assert_int_equal(fclose(f), 0);
}

/* Replace the one occurrence of `from` in the shader file `name` (under the copy). */
static void edit(const char* name, const char* from, const char* to)
{
    char path[256], edited[1 << 16];
    snprintf(path, sizeof path, "%s/%s", shader_dir, name);
    const char* text = read_text(path);
    const char* at = strstr(text, from);
    assert_non_null(at);
    snprintf(edited, sizeof edited, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    write_text(path, edited);
}

/* The change of a falling body's vertical velocity over one step, from rest. */
static double fall_in_one_step(tb_world* w, tb_body_id body)
{
    tb_vec3 v, spin;
    th_assert_ok(tb_body_set_velocity(w, body, th_v3(0, 0, 0), th_v3(0, 0, 0)));
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_body_get_velocity(w, body, &v, &spin));
    return v.y;
}

/* Step until the fall over one step is `factor` times `base`; asserts it comes within
 * MAX_STEPS_TO_SEE steps. */
static void expect_fall(tb_world* w, tb_body_id body, double base, double factor)
{
    double fall = 0;
    for (int i = 0; i < MAX_STEPS_TO_SEE; i++) {
        fall = fall_in_one_step(w, body);
        if (th_near(fall, factor * base, 1e-6, 1e-3)) return;
    }
    fail_msg("after %d steps the fall per step is %g, not %g x %g", MAX_STEPS_TO_SEE, fall,
             factor, base);
}

static const char* const GRAVITY_TERM = "params.gravity.xyz * (s.angular.w * h)";
static const char* const INCLUDE_GUARD = "#define TB_MOTION_GLSL\n";

static void test_edits_take_effect_while_stepping(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);   /* the syntax error is logged on purpose */
    th_assert_ok(tb_world_set_shader_dir(w, shader_dir));
    tb_body_def def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 100, 0));
    tb_body_id body = th_body(w, &def);
    double base = fall_in_one_step(w, body);
    th_assert_near(base, -9.81 * DT, 1e-4, 1e-3);
    uint64_t records = th_stats(w).records;

    /* A factor defined in motion.glsl: no code uses it yet, nothing changes. */
    edit("integrate/motion.glsl", INCLUDE_GUARD,
         "#define TB_MOTION_GLSL\n#define GRAVITY_FACTOR 3.0\n");
    expect_fall(w, body, base, 1.0);
    /* The substep shader scales gravity by it. */
    edit("integrate/substep.comp", GRAVITY_TERM,
         "params.gravity.xyz * (GRAVITY_FACTOR * s.angular.w * h)");
    expect_fall(w, body, base, 3.0);
    assert_true(th_stats(w).records > records);   /* the step was recorded again */
    /* An edit of the included file alone rebuilds its includer. */
    edit("integrate/motion.glsl", "GRAVITY_FACTOR 3.0", "GRAVITY_FACTOR 0.5");
    expect_fall(w, body, base, 0.5);

    /* A syntax error: reported with file and line, the last good pipeline keeps running. */
    edit("integrate/substep.comp", "void main()", "void main() { not glsl }\nvoid broken()");
    th_assert_ok(tb_world_step(w, DT));
    const char* error = th_world_log(w)->last_warning;
    char where[128];
    snprintf(where, sizeof where, "%s/integrate/substep.comp:", shader_dir);
    assert_non_null(strstr(error, where));
    int line = atoi(strstr(error, where) + strlen(where));
    assert_true(line > 10);
    assert_non_null(strstr(error, "error"));
    assert_non_null(strstr(error, "keeps its last good pipeline"));
    expect_fall(w, body, base, 0.5);
    expect_fall(w, body, base, 0.5);

    /* Fixed: the shader as it was runs again. */
    edit("integrate/substep.comp", "void main() { not glsl }\nvoid broken()", "void main()");
    edit("integrate/substep.comp", "(GRAVITY_FACTOR * s.angular.w * h)", "(s.angular.w * h)");
    expect_fall(w, body, base, 1.0);
    th_world_destroy(w);
}

/* TUMBLE_SHADER_DIR at creation compiles every shader from the directory; a shader that
 * does not compile then runs built in, and the world still steps as it should. */
static void test_environment_and_broken_start(void** state)
{
    (void)state;
    edit("step/begin.comp", "void main()", "void main() { not glsl }\nvoid broken()");
    setenv("TUMBLE_SHADER_DIR", shader_dir, 1);
    tb_world* w = th_world_create_ex(NULL, 1);
    unsetenv("TUMBLE_SHADER_DIR");
    assert_non_null(strstr(th_world_log(w)->last_warning, "step/begin.comp:"));
    assert_non_null(strstr(th_world_log(w)->last_warning, "runs the built-in shader"));
    tb_body_def def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 100, 0));
    tb_body_id body = th_body(w, &def);
    th_assert_near(fall_in_one_step(w, body), -9.81 * DT, 1e-4, 1e-3);
    /* Fixing it swaps the compiled one in; the world steps on. */
    edit("step/begin.comp", "void main() { not glsl }\nvoid broken()", "void main()");
    th_assert_near(fall_in_one_step(w, body), -9.81 * DT, 1e-4, 1e-3);
    th_assert_near(fall_in_one_step(w, body), -9.81 * DT, 1e-4, 1e-3);
    th_world_destroy(w);
}

/* A world made with TUMBLE_SHADER_DIR whose step/begin.comp in the copy is refused: the last
 * warning says `why` and that step/begin runs built in, and a body falls as it should. */
static void expect_begin_built_in(const char* why)
{
    setenv("TUMBLE_SHADER_DIR", shader_dir, 1);
    tb_world* w = th_world_create_ex(NULL, 1);
    unsetenv("TUMBLE_SHADER_DIR");
    const char* warning = th_world_log(w)->last_warning;
    assert_non_null(strstr(warning, why));
    assert_non_null(strstr(warning, "step/begin runs the built-in shader"));
    tb_body_def def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 100, 0));
    tb_body_id body = th_body(w, &def);
    th_assert_near(fall_in_one_step(w, body), -9.81 * DT, 1e-4, 1e-3);
    th_world_destroy(w);
}

/* Shader files that include each other without guards are refused with a sentence (the
 * compiler recursed without end), and the built-in shader runs. */
static void test_include_cycle_is_refused(void** state)
{
    (void)state;
    char path[256];
    snprintf(path, sizeof path, "%s/step/cycle_a.glsl", shader_dir);
    write_text(path, "#include \"cycle_b.glsl\"\n");
    snprintf(path, sizeof path, "%s/step/cycle_b.glsl", shader_dir);
    write_text(path, "#include \"cycle_a.glsl\"\n");
    edit("step/begin.comp", "void main()", "#include \"cycle_a.glsl\"\nvoid main()");
    expect_begin_built_in("include guards");
    edit("step/begin.comp", "#include \"cycle_a.glsl\"\nvoid main()", "void main()");
}

/* A shader in the directory that declares a buffer at a binding the world's set lacks is
 * refused before the driver sees it (it crashed the driver, or ran against another buffer),
 * and the built-in shader runs. */
static void test_unknown_binding_is_refused(void** state)
{
    (void)state;
    const char* bogus = "layout(set = 0, binding = 99, std430) buffer Bogus { uint bogus[]; };\n"
                        "void main() { bogus[0] = 1u; }\nvoid main_of_begin()";
    edit("step/begin.comp", "void main()", bogus);
    expect_begin_built_in("uses binding 99");
    edit("step/begin.comp", bogus, "void main()");
}

/* The blast plugin compiling blast.comp beside it, from a copy: with a shader directory
 * set, editing blast.comp turns the push into a pull. */
static void test_plugin_glsl_is_watched(void** state)
{
    (void)state;
    char command[4096], plugin[256];
    snprintf(command, sizeof command, "mkdir -p '%s/blast' && cp '%s/plugins/tb_blast_glsl.so' "
             "'%s/plugins/blast.comp' '%s/plugins/blast.h' '%s/blast'", shader_dir, TB_BUILD_DIR,
             TB_BUILD_DIR, TB_BUILD_DIR, shader_dir);
    assert_int_equal(system(command), 0);
    snprintf(plugin, sizeof plugin, "%s/blast/tb_blast_glsl.so", shader_dir);
    tb_world_def def = tb_default_world_def();
    def.gravity = th_v3(0, 0, 0);
    tb_world* w = th_world_create(&def);
    tb_plugin_id blast;
    th_assert_ok(tb_world_load_plugin(w, plugin, &blast));
    tb_blast_params params = { { 0, 0, 0, 12.0f }, { 4.0f, 0, 0, 0 } };
    th_assert_ok(tb_world_set_plugin_param(w, blast, 0, &params, sizeof params));
    th_assert_ok(tb_world_set_shader_dir(w, shader_dir));
    tb_body_def body_def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(2, 0, 0));
    tb_body_id body = th_body(w, &body_def);
    tb_vec3 v, spin;
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_body_get_velocity(w, body, &v, &spin));
    th_assert_near(v.x, 6.0 * DT, 1e-5, 1e-4);   /* half the strength at half the radius */

    edit("blast/blast.comp", "(acceleration * tb_plugin_dt())", "(-acceleration * tb_plugin_dt())");
    th_assert_ok(tb_body_set_velocity(w, body, th_v3(0, 0, 0), th_v3(0, 0, 0)));
    th_assert_ok(tb_world_step(w, DT));
    th_assert_ok(tb_body_get_velocity(w, body, &v, &spin));
    th_assert_near(v.x, -6.0 * DT, 1e-5, 2e-3);   /* it moved out a little */
    th_world_destroy(w);
}

static void test_bad_directory_is_refused(void** state)
{
    (void)state;
    tb_world* w = th_world_create_ex(NULL, 1);
    th_assert_result(tb_world_set_shader_dir(w, "/no/such/tumble/shaders"),
                     TB_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(tb_world_last_error(w), "/no/such/tumble/shaders"));
    th_assert_result(tb_world_set_shader_dir(NULL, shader_dir), TB_ERROR_INVALID_ARGUMENT);
    tb_body_def def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 100, 0));
    tb_body_id body = th_body(w, &def);
    th_assert_near(fall_in_one_step(w, body), -9.81 * DT, 1e-4, 1e-3);
    th_assert_ok(tb_world_set_shader_dir(w, NULL));
    th_world_destroy(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_edits_take_effect_while_stepping),
        cmocka_unit_test(test_environment_and_broken_start),
        cmocka_unit_test(test_include_cycle_is_refused),
        cmocka_unit_test(test_unknown_binding_is_refused),
        cmocka_unit_test(test_plugin_glsl_is_watched),
        cmocka_unit_test(test_bad_directory_is_refused),
    };
    return cmocka_run_group_tests(tests, copy_shaders, remove_shaders);
}
