/* Run-time GLSL compilation through libshaderc. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "gpu/glsl.h"

#include "base/file.h"

#include <limits.h>
#include <shaderc/shaderc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct include_context {
    const char* const* dirs;
    uint32_t dir_count;
    tb_spirv* out;
    int out_of_memory;
} include_context;

/* A shader's text (at most 64 MiB, through #include too), or NULL. */
static char* read_text(const char* path, size_t* size)
{
    return (char*)tb_file_read(path, (size_t)64 << 20, size);
}

static char* copy_string(const char* s)
{
    size_t n = strlen(s) + 1;
    char* c = malloc(n);
    if (c) memcpy(c, s, n);
    return c;
}

/* Remember a file the module is made of (its canonical path, once). */
static int note_file(tb_spirv* out, const char* path)
{
    if (tb_spirv_uses(out, path)) return 1;
    char** files = realloc(out->files, (out->file_count + 1) * sizeof *files);
    if (!files) return 0;
    out->files = files;
    files[out->file_count] = copy_string(path);
    return files[out->file_count] ? (out->file_count++, 1) : 0;
}

/* The canonical path of `name` in `dir` (dir may be "" for `name` as it is), or 0. */
static int find_in(const char* dir, size_t dir_length, const char* name, char* found)
{
    char candidate[PATH_MAX];
    int n = dir_length ? snprintf(candidate, sizeof candidate, "%.*s/%s", (int)dir_length, dir, name)
                       : snprintf(candidate, sizeof candidate, "%s", name);
    return n > 0 && (size_t)n < sizeof candidate && realpath(candidate, found) != NULL;
}

static int resolve(const include_context* ctx, const char* requested, int type,
                   const char* requesting, char* found)
{
    const char* slash = strrchr(requesting, '/');
    if (type == shaderc_include_type_relative && slash &&
        find_in(requesting, (size_t)(slash - requesting), requested, found))
        return 1;
    for (uint32_t i = 0; i < ctx->dir_count; i++)
        if (find_in(ctx->dirs[i], strlen(ctx->dirs[i]), requested, found)) return 1;
    return 0;
}

static const tb_glsl_header* embedded_header(const char* name)
{
    for (uint32_t i = 0; i < tb_glsl_header_count; i++)
        if (strcmp(tb_glsl_headers[i].name, name) == 0) return &tb_glsl_headers[i];
    return NULL;
}

static void set_text(shaderc_include_result* result, const char* name, char* text, size_t size)
{
    result->source_name = copy_string(name);
    result->source_name_length = result->source_name ? strlen(name) : 0;
    result->content = text;
    result->content_length = text ? size : 0;
}

/* Includes nested deeper than this are refused: files without include guards that include
 * each other (a.glsl includes b.glsl includes a.glsl) would make the compiler recurse
 * without end. Tumble's own go 4 deep. */
#define MAX_INCLUDE_DEPTH 32

static shaderc_include_result* include_file(void* user, const char* requested, int type,
                                            const char* requesting, size_t depth)
{
    include_context* ctx = user;
    shaderc_include_result* result = calloc(1, sizeof *result);
    char found[PATH_MAX], name[PATH_MAX + 16];
    size_t size = 0;
    char* text = NULL;
    const tb_glsl_header* header = NULL;
    if (!result) return NULL;
    if (depth > MAX_INCLUDE_DEPTH) {
        snprintf(name, sizeof name, "includes nested more than %d deep at \"%s\" (files "
                 "that include each other without include guards?)", MAX_INCLUDE_DEPTH,
                 requested);
        set_text(result, "", copy_string(name), strlen(name));
    } else if (resolve(ctx, requested, type, requesting, found) &&
               (text = read_text(found, &size))) {
        set_text(result, found, text, size);
        if (!note_file(ctx->out, found)) ctx->out_of_memory = 1;
    } else if ((header = embedded_header(requested))) {
        snprintf(name, sizeof name, "<tumble>/%s", header->name);
        set_text(result, name, copy_string(header->text), strlen(header->text));
    } else {
        snprintf(name, sizeof name, "cannot find or read include file \"%s\"", requested);
        set_text(result, "", copy_string(name), strlen(name));
    }
    if (!result->source_name || !result->content) ctx->out_of_memory = 1;
    return result;
}

static void release_include(void* user, shaderc_include_result* result)
{
    (void)user;
    if (!result) return;
    free((void*)result->source_name);
    free((void*)result->content);
    free(result);
}

/* The compiler's first error line, without the trailing newline. */
static tb_result compile_error(tb_diag* diag, shaderc_compilation_result_t result)
{
    const char* text = shaderc_result_get_error_message(result);
    const char* line = text ? strstr(text, "error") : NULL;
    while (line && line > text && line[-1] != '\n') line--;
    if (!line) line = text && *text ? text : "the compiler gave no message";
    int length = (int)strcspn(line, "\n");
    return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%.*s", length, line);
}

static shaderc_compile_options_t make_options(include_context* ctx)
{
    shaderc_compile_options_t options = shaderc_compile_options_initialize();
    if (!options) return NULL;
    shaderc_compile_options_set_source_language(options, shaderc_source_language_glsl);
    shaderc_compile_options_set_target_env(options, shaderc_target_env_vulkan,
                                           shaderc_env_version_vulkan_1_2);
    shaderc_compile_options_set_include_callbacks(options, include_file, release_include, ctx);
    return options;
}

static tb_result compile_text(tb_diag* diag, const char* path, const char* text, size_t size,
                              include_context* ctx)
{
    shaderc_compiler_t compiler = shaderc_compiler_initialize();
    shaderc_compile_options_t options = compiler ? make_options(ctx) : NULL;
    shaderc_compilation_result_t result =
        options ? shaderc_compile_into_spv(compiler, text, size, shaderc_compute_shader, path,
                                           "main", options) : NULL;
    tb_result r = TB_OK;
    if (!result || ctx->out_of_memory) {
        r = tb_fail(diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory compiling %s", path);
    } else if (shaderc_result_get_compilation_status(result) != shaderc_compilation_status_success) {
        r = compile_error(diag, result);
    } else {
        size_t bytes = shaderc_result_get_length(result);
        ctx->out->code = malloc(bytes);
        if (!ctx->out->code) r = tb_fail(diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        else memcpy(ctx->out->code, shaderc_result_get_bytes(result), bytes);
        ctx->out->size = bytes;
    }
    if (result) shaderc_result_release(result);
    if (options) shaderc_compile_options_release(options);
    if (compiler) shaderc_compiler_release(compiler);
    return r;
}

tb_result tb_glsl_compile(tb_diag* diag, const char* path, const char* const* include_dirs,
                          uint32_t include_dir_count, tb_spirv* out)
{
    memset(out, 0, sizeof *out);
    char canonical[PATH_MAX];
    size_t size = 0;
    char* text = realpath(path, canonical) ? read_text(canonical, &size) : NULL;
    if (!text) return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "cannot read shader %s", path);
    include_context ctx = { include_dirs, include_dir_count, out, 0 };
    tb_result r = note_file(out, canonical) ? TB_OK
                  : tb_fail(diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    if (!r) r = compile_text(diag, canonical, text, size, &ctx);
    free(text);
    if (r) tb_spirv_free(out);
    return r;
}

int tb_spirv_uses(const tb_spirv* spirv, const char* file)
{
    for (uint32_t i = 0; i < spirv->file_count; i++)
        if (strcmp(spirv->files[i], file) == 0) return 1;
    return 0;
}

void tb_spirv_free(tb_spirv* spirv)
{
    for (uint32_t i = 0; i < spirv->file_count; i++) free(spirv->files[i]);
    free(spirv->files);
    free(spirv->code);
    memset(spirv, 0, sizeof *spirv);
}
