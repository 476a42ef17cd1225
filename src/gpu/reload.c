/* Shader hot-reload (DESIGN.md §5). With a shader directory set, every pipeline of an
 * embedded shader is compiled from <dir>/<name>.comp instead (includes from <dir>/common),
 * and the directories of every file a pipeline was compiled from are watched. Between
 * steps, the pipelines whose files were written are compiled again; those whose SPIR-V
 * changed are built and swapped in where their owners keep them, and the caller records
 * the step again. A shader that does not compile keeps its pipeline running and its
 * error, file:line: message, goes to the log. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "gpu/glsl.h"
#include "gpu/pipeline.h"
#include "gpu/shaders.h"

#define SPIRV_HEADER_WORDS 5   /* magic, version, generator, id bound, schema */

/* FNV-1a over the instructions: the header's generator differs between the build's
 * glslangValidator and the library's libshaderc, so it is left out. */
static uint64_t hash_code(const uint32_t* code, size_t size)
{
    uint64_t h = 0xcbf29ce484222325ull;
    size_t words = size / sizeof(uint32_t);
    for (size_t i = SPIRV_HEADER_WORDS; i < words; i++) {
        h ^= code[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

/* The source no longer knows what it was compiled from. */
static void forget_files(tb_pipeline_source* s)
{
    for (uint32_t i = 0; i < s->file_count; i++) free(s->files[i]);
    free(s->files);
    s->files = NULL;
    s->file_count = 0;
}

void tb_pipeline_source_free(tb_pipeline_source* s)
{
    forget_files(s);
    free(s->name);
    free(s->glsl_path);
    memset(s, 0, sizeof *s);
}

static void watch_files(tb_pipelines* p, const tb_pipeline_source* s)
{
    for (uint32_t i = 0; i < s->file_count; i++)
        if (p->watch.fd >= 0 && !tb_watch_add_file(&p->watch, s->files[i]))
            tb_log(p->gpu->diag, TB_LOG_WARNING, "shader reload: cannot watch %s", s->files[i]);
}

/* The files a compile read become the source's, and are watched. */
static void keep_files(tb_pipelines* p, tb_pipeline_source* s, tb_spirv* spirv)
{
    forget_files(s);
    s->files = spirv->files;
    s->file_count = spirv->file_count;
    spirv->files = NULL;
    spirv->file_count = 0;
    watch_files(p, s);
}

static int source_path(const tb_pipelines* p, const tb_pipeline_source* s, char* path)
{
    if (s->glsl_path) return snprintf(path, PATH_MAX, "%s", s->glsl_path) < PATH_MAX;
    return snprintf(path, PATH_MAX, "%s/%s.comp", p->shader_dir, s->name) < PATH_MAX;
}

/* A shader that never compiled is still watched, so that fixing it is seen. */
static void keep_main_file(tb_pipelines* p, tb_pipeline_source* s)
{
    char path[PATH_MAX], canonical[PATH_MAX];
    char** files = NULL;
    if (s->file_count || !source_path(p, s, path) || !realpath(path, canonical)) return;
    if (!(files = malloc(sizeof *files)) || !(files[0] = strdup(canonical))) {
        free(files);
        return;
    }
    s->files = files;
    s->file_count = 1;
    watch_files(p, s);
}

static tb_result compile_source(tb_pipelines* p, const tb_pipeline_source* s, tb_spirv* out)
{
    char path[PATH_MAX], common[PATH_MAX];
    const char* dirs[] = { common };
    if (!source_path(p, s, path))
        return tb_fail(p->gpu->diag, TB_ERROR_INVALID_ARGUMENT, "shader path too long");
    if (s->glsl_path) return tb_glsl_compile(p->gpu->diag, path, NULL, 0, out);
    snprintf(common, sizeof common, "%s/common", p->shader_dir);
    return tb_glsl_compile(p->gpu->diag, path, dirs, 1, out);
}

static tb_result build_embedded(tb_pipelines* p, tb_pipeline_source* s, VkPipeline* out)
{
    const tb_shader_blob* blob = tb_shader_find(s->name);
    if (!blob) return tb_fail(p->gpu->diag, TB_ERROR_DEVICE, "no embedded shader named %s", s->name);
    tb_result r = tb_pipeline_create_from(p, s->name, blob->code, blob->size, s->workgroup_size, out);
    if (!r) s->code_hash = hash_code(blob->code, blob->size);
    return r;
}

/* Compile the source and build a pipeline of it; *out stays null when the SPIR-V is the
 * one in use already. */
static tb_result build_compiled(tb_pipelines* p, tb_pipeline_source* s, VkPipeline* out)
{
    tb_spirv spirv;
    *out = VK_NULL_HANDLE;
    tb_result r = compile_source(p, s, &spirv);
    /* Compiled from files anyone may have written: checked before the driver sees it (a
     * buffer at a binding the world's set lacks crashed the driver, or ran against another). */
    tb_spirv_check* check = s->check ? s->check : tb_spirv_check_module;
    if (!r) r = check(p->gpu->diag, s->name, spirv.code, spirv.size);
    uint64_t hash = r ? 0 : hash_code(spirv.code, spirv.size);
    if (!r && (!s->pipeline || hash != s->code_hash))
        r = tb_pipeline_create_from(p, s->name, spirv.code, spirv.size, s->workgroup_size, out);
    if (!r) {
        s->code_hash = hash;
        keep_files(p, s, &spirv);
    }
    tb_spirv_free(&spirv);
    return r;
}

tb_result tb_pipeline_source_build(tb_pipelines* p, tb_pipeline_source* s, VkPipeline* out)
{
    if (!s->glsl_path && !p->shader_dir) return build_embedded(p, s, out);
    tb_result r = build_compiled(p, s, out);
    if (!r || s->glsl_path) return r;
    tb_log(p->gpu->diag, TB_LOG_ERROR, "shader reload: %s; %s runs the built-in shader",
           p->gpu->diag->message, s->name);
    keep_main_file(p, s);
    return build_embedded(p, s, out);
}

/* ---- swapping ---------------------------------------------------------------------------- */

/* What a poll saw written: canonical paths, or everything. */
typedef struct change_list {
    char** files;
    uint32_t count;
    int everything;
} change_list;

static void note_change(void* user, const char* file)
{
    change_list* c = user;
    char** files = file ? realloc(c->files, (c->count + 1) * sizeof *files) : NULL;
    if (files) c->files = files;
    if (!files || !(files[c->count] = strdup(file))) c->everything = 1;
    else c->count++;
}

static int source_changed(const tb_pipeline_source* s, const change_list* c)
{
    if (c->everything) return 1;
    for (uint32_t i = 0; i < s->file_count; i++)
        for (uint32_t j = 0; j < c->count; j++)
            if (strcmp(s->files[i], c->files[j]) == 0) return 1;
    return 0;
}

/* Replace the pipelines in use by the new ones (null: keep) once the GPU is done with
 * the old. */
static uint32_t swap_in(tb_pipelines* p, VkPipeline* fresh)
{
    uint32_t swapped = 0;
    for (uint32_t i = 0; i < p->source_count; i++) swapped += fresh[i] != VK_NULL_HANDLE;
    if (!swapped) return 0;
    vkDeviceWaitIdle(p->gpu->device);
    for (uint32_t i = 0; i < p->source_count; i++) {
        tb_pipeline_source* s = &p->sources[i];
        if (!fresh[i]) continue;
        vkDestroyPipeline(p->gpu->device, s->pipeline, NULL);
        s->pipeline = *s->slot = fresh[i];
        tb_log(p->gpu->diag, TB_LOG_INFO, "shader reload: %s rebuilt", s->name);
    }
    return swapped;
}

/* Compile again the sources `changes` touch (NULL: every embedded shader's) and swap in
 * those that compiled to new code. */
static uint32_t rebuild(tb_pipelines* p, const change_list* changes)
{
    VkPipeline* fresh = calloc(p->source_count ? p->source_count : 1, sizeof *fresh);
    if (!fresh) {
        tb_log(p->gpu->diag, TB_LOG_ERROR, "shader reload: out of host memory");
        return 0;
    }
    for (uint32_t i = 0; i < p->source_count; i++) {
        tb_pipeline_source* s = &p->sources[i];
        int wanted = changes ? source_changed(s, changes) : !s->glsl_path;
        if (!wanted) continue;
        if (build_compiled(p, s, &fresh[i]) == TB_OK) continue;
        tb_log(p->gpu->diag, TB_LOG_ERROR, "shader reload: %s; %s keeps its last good pipeline",
               p->gpu->diag->message, s->name);
        keep_main_file(p, s);
    }
    uint32_t swapped = swap_in(p, fresh);
    free(fresh);
    return swapped;
}

uint32_t tb_pipelines_reload(tb_pipelines* p)
{
    change_list changes = { 0 };
    if (!p->shader_dir || !tb_watch_poll(&p->watch, note_change, &changes)) return 0;
    uint32_t swapped = rebuild(p, &changes);
    for (uint32_t i = 0; i < changes.count; i++) free(changes.files[i]);
    free(changes.files);
    return swapped;
}

/* Watch from `dir` (canonical) on; the embedded shaders' files are those compiled next. */
static tb_result start_watching(tb_pipelines* p, const char* dir)
{
    char* copy = strdup(dir);
    if (!copy) return tb_fail(p->gpu->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    free(p->shader_dir);
    p->shader_dir = copy;
    for (uint32_t i = 0; i < p->source_count; i++)
        if (!p->sources[i].glsl_path) forget_files(&p->sources[i]);
    tb_watch_close(&p->watch);
    if (!tb_watch_open(&p->watch))
        tb_log(p->gpu->diag, TB_LOG_WARNING, "shader reload: no inotify instance; shaders are "
               "compiled from %s but changes are not seen", dir);
    for (uint32_t i = 0; i < p->source_count; i++) watch_files(p, &p->sources[i]);
    return TB_OK;
}

tb_result tb_pipelines_set_shader_dir(tb_pipelines* p, const char* dir, uint32_t* swapped)
{
    char canonical[PATH_MAX];
    struct stat info;
    *swapped = 0;
    if (!dir) {
        free(p->shader_dir);
        p->shader_dir = NULL;
        tb_watch_close(&p->watch);
        return TB_OK;
    }
    if (!realpath(dir, canonical) || stat(canonical, &info) != 0 || !S_ISDIR(info.st_mode))
        return tb_fail(p->gpu->diag, TB_ERROR_INVALID_ARGUMENT,
                       "shader directory %s is not a readable directory", dir);
    tb_result r = start_watching(p, canonical);
    if (!r) *swapped = rebuild(p, NULL);
    return r;
}
