/* Loading and unloading plugins, and their parameter blocks. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin.h"

#define PLUGIN_MIN_SIZE (offsetof(tb_plugin, stages) + sizeof(const tb_plugin_stage*))
#define STAGE_MIN_SIZE (offsetof(tb_plugin_stage, glsl_path) + sizeof(const char*))
/* Far beyond any version's tb_plugin_stage: a larger size field is wrong, and as the stages'
 * stride it would send the loader far past the plugin's array. */
#define STAGE_MAX_SIZE 4096u

static tb_diag* diag_of(const tb_plugins* pl)
{
    return pl->host.kit.diag;
}

/* A name of [a-z0-9_], 1 to TB_PLUGIN_MAX_NAME bytes. */
static int good_name(const char* name)
{
    size_t n = name ? strlen(name) : 0;
    if (n == 0 || n > TB_PLUGIN_MAX_NAME) return 0;
    for (size_t i = 0; i < n; i++)
        if (!((name[i] >= 'a' && name[i] <= 'z') || (name[i] >= '0' && name[i] <= '9') ||
              name[i] == '_'))
            return 0;
    return 1;
}

/* The plugin's description, fields of older versions' missing tail zeroed. */
static tb_result read_description(tb_plugins* pl, const char* path, const tb_plugin* given,
                                  tb_plugin* out)
{
    memset(out, 0, sizeof *out);
    if (!given) return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s refused to load "
                               "(its entry point returned NULL)", path);
    if (given->abi_version > TB_PLUGIN_ABI_VERSION || given->abi_version == 0)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s was built for plugin ABI "
                       "version %u; this library loads versions 1 to %u", path,
                       given->abi_version, TB_PLUGIN_ABI_VERSION);
    if (given->size < PLUGIN_MIN_SIZE)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s says its tb_plugin is %u "
                       "bytes, too small for any version", path, given->size);
    memcpy(out, given, given->size < sizeof *out ? given->size : sizeof *out);
    if (!good_name(out->name))
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s: its name must be 1 to %u "
                       "characters of a-z, 0-9 and _", path, TB_PLUGIN_MAX_NAME);
    if (out->param_bytes > TB_PLUGIN_MAX_PARAM_BYTES || out->stage_count > TB_PLUGIN_MAX_STAGES)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s: %u parameter bytes and %u "
                       "stages; at most %u and %u", path, out->param_bytes, out->stage_count,
                       TB_PLUGIN_MAX_PARAM_BYTES, TB_PLUGIN_MAX_STAGES);
    if (out->stage_count && (!out->stages || out->stages[0].size < STAGE_MIN_SIZE))
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s: its stages are missing "
                       "or their size field is wrong", path);
    if (out->stage_count && out->stages[0].size > STAGE_MAX_SIZE)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s: its stages say they "
                       "are %u bytes each; a tb_plugin_stage is at most %u", path,
                       out->stages[0].size, STAGE_MAX_SIZE);
    return TB_OK;
}

/* Stage i of the plugin (the array's stride is the size the plugin was built with). */
static tb_plugin_stage stage_of(const tb_plugin* desc, uint32_t i)
{
    tb_plugin_stage stage;
    memset(&stage, 0, sizeof stage);
    uint32_t stride = desc->stages[0].size;
    memcpy(&stage, (const char*)desc->stages + (size_t)i * stride,
           stride < sizeof stage ? stride : sizeof stage);
    return stage;
}

static tb_result check_stage(tb_plugins* pl, const tb_plugin_stage* s, const char* what)
{
    if (!good_name(s->name))
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s: a stage name must be 1 to %u "
                       "characters of a-z, 0-9 and _", what, TB_PLUGIN_MAX_NAME);
    if ((uint32_t)s->point >= TB_PLUGIN_POINT_COUNT)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s: %d names no point of the step",
                       what, (int)s->point);
    if ((uint32_t)s->dispatch > TB_PLUGIN_FIXED)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s: %d names no dispatch rule", what,
                       (int)s->dispatch);
    if (s->dispatch == TB_PLUGIN_PER_PAIR && s->point == TB_PLUGIN_PRE_STEP)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s: a per-pair stage cannot run at "
                       "the pre-step point, before the step has pairs", what);
    if (s->dispatch == TB_PLUGIN_FIXED && (s->groups < 1 || s->groups > TB_DISPATCH_MAX_X))
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s: a fixed stage needs 1 to %u "
                       "workgroups, not %u", what, TB_DISPATCH_MAX_X, s->groups);
    if (!s->spirv && !s->glsl_path)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s gives neither SPIR-V nor a GLSL "
                       "path", what);
    return TB_OK;
}

/* A GLSL path relative to the plugin file's directory, compiled. */
/* A stage's GLSL path; a relative one is relative to the plugin's file. */
static void stage_glsl_path(const char* plugin_path, const char* glsl_path, char* full,
                            size_t size)
{
    char resolved[PATH_MAX];
    snprintf(full, size, "%s", glsl_path);
    if (glsl_path[0] != '/' && realpath(plugin_path, resolved)) {
        char* slash = strrchr(resolved, '/');
        if (slash) *slash = 0;
        snprintf(full, size, "%s/%s", resolved, glsl_path);
    }
}

/* SPIR-V is checked and built as given; GLSL is compiled, and hot-reload (a shader
 * directory set) watches it like the step's own shaders. */
static tb_result build_stage(tb_plugins* pl, const char* path, const tb_plugin_stage* s,
                             tb_plugin_stage_record* rec)
{
    if (!s->spirv) {
        char full[2 * PATH_MAX];
        stage_glsl_path(path, s->glsl_path, full, sizeof full);
        return tb_pipeline_create_glsl(pl->host.kit.pipelines, rec->name, full, tb_spirv_check_module,
                                       TB_WORKGROUP_SIZE, &rec->pipeline);
    }
    tb_result r = tb_spirv_check_module(diag_of(pl), rec->name, s->spirv, s->spirv_size);
    if (!r) r = tb_pipeline_create_from(pl->host.kit.pipelines, rec->name, s->spirv, s->spirv_size,
                                        TB_WORKGROUP_SIZE, &rec->pipeline);
    return r;
}

static void destroy_stages(tb_plugins* pl, tb_plugin_record* p)
{
    for (uint32_t i = 0; i < p->stage_count; i++)
        tb_pipeline_destroy(pl->host.kit.pipelines, p->stages[i].pipeline);
    p->stage_count = 0;
}

static tb_result build_stages(tb_plugins* pl, const char* path, tb_plugin_record* p)
{
    if (pl->stage_total + p->desc.stage_count > TB_MAX_PLUGIN_STAGES)
        return tb_fail(diag_of(pl), TB_ERROR_CAPACITY, "plugin %s brings %u stages; the world runs "
                       "%u of its %u plugin stages already", path, p->desc.stage_count,
                       pl->stage_total, TB_MAX_PLUGIN_STAGES);
    for (uint32_t i = 0; i < p->desc.stage_count; i++) {
        tb_plugin_stage s = stage_of(&p->desc, i);
        tb_plugin_stage_record* rec = &p->stages[i];
        char what[sizeof rec->name + 16];
        snprintf(what, sizeof what, "plugin %s stage %u", p->desc.name, i);
        tb_result r = check_stage(pl, &s, what);
        if (r) return r;
        snprintf(rec->name, sizeof rec->name, "plugin/%s/%s", p->desc.name, s.name);
        rec->point = s.point;
        rec->dispatch = s.dispatch;
        rec->groups = s.groups;
        p->stage_count = i + 1;
        r = build_stage(pl, path, &s, rec);
        if (r) return r;
    }
    return TB_OK;
}

static tb_result open_plugin(tb_plugins* pl, const char* path, tb_plugin_record* p)
{
    p->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!p->handle) {
        const char* why = dlerror();
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "cannot load plugin %s: %s", path,
                       why ? why : "unknown reason");
    }
    tb_plugin_entry_fn* entry;
    void* symbol = dlsym(p->handle, TB_PLUGIN_ENTRY_NAME);
    memcpy(&entry, &symbol, sizeof entry);   /* object to function pointer, as POSIX allows */
    if (!entry)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "%s is no Tumble plugin: it exports "
                       "no %s", path, TB_PLUGIN_ENTRY_NAME);
    const tb_plugin* given = entry(TB_PLUGIN_ABI_VERSION);
    tb_result r = read_description(pl, path, given, &p->desc);
    if (r) {   /* refused after it was handed over: let the plugin free it */
        if (given && given->size >= offsetof(tb_plugin, on_unload) + sizeof given->on_unload &&
            given->on_unload)
            given->on_unload(given->user);
        memset(&p->desc, 0, sizeof p->desc);
    }
    return r;
}

static void close_plugin(tb_plugins* pl, tb_plugin_record* p)
{
    destroy_stages(pl, p);
    if (p->desc.on_unload) p->desc.on_unload(p->desc.user);
    if (p->handle) dlclose(p->handle);
    uint16_t generation = p->generation;
    memset(p, 0, sizeof *p);
    p->generation = generation;
}

tb_result tb_plugins_load(tb_plugins* pl, const char* path, tb_plugin_id* out)
{
    uint32_t slot = 0;
    while (slot < TB_MAX_PLUGINS && pl->slots[slot].alive) slot++;
    if (slot == TB_MAX_PLUGINS)
        return tb_fail(diag_of(pl), TB_ERROR_CAPACITY, "the world has %u plugins loaded, the most "
                       "it takes", TB_MAX_PLUGINS);
    tb_plugin_record* p = &pl->slots[slot];
    tb_result r = open_plugin(pl, path, p);
    if (!r) r = build_stages(pl, path, p);
    if (r) {
        if (p->handle && p->desc.name) close_plugin(pl, p);
        else if (p->handle) { dlclose(p->handle); p->handle = NULL; }
        return r;
    }
    if (p->desc.default_params) memcpy(p->params, p->desc.default_params, p->desc.param_bytes);
    p->alive = 1;
    p->generation++;
    pl->stage_total += p->stage_count;
    pl->params_dirty = 1;
    *out = (tb_plugin_id){ slot + 1, pl->host.serial, p->generation };
    return TB_OK;
}

static tb_plugin_record* lookup(tb_plugins* pl, tb_plugin_id id, tb_result* r)
{
    tb_plugin_record* p = id.index1 && id.index1 <= TB_MAX_PLUGINS && id.world == pl->host.serial
                          ? &pl->slots[id.index1 - 1] : NULL;
    *r = TB_OK;
    if (!p || !p->generation)
        *r = tb_fail(diag_of(pl), TB_ERROR_INVALID_ID, "no plugin with that id in this world");
    else if (!p->alive || p->generation != id.generation)
        *r = tb_fail(diag_of(pl), TB_ERROR_STALE_ID, "that plugin was unloaded");
    return *r ? NULL : p;
}

tb_result tb_plugins_unload(tb_plugins* pl, tb_plugin_id id)
{
    tb_result r;
    tb_plugin_record* p = lookup(pl, id, &r);
    if (!p) return r;
    pl->stage_total -= p->stage_count;
    close_plugin(pl, p);
    return TB_OK;
}

tb_result tb_plugins_set_param(tb_plugins* pl, tb_plugin_id id, uint32_t offset,
                               const void* data, uint32_t size)
{
    tb_result r;
    tb_plugin_record* p = lookup(pl, id, &r);
    if (!p) return r;
    if (!data && size) return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "data is NULL");
    if ((uint64_t)offset + size > p->desc.param_bytes)
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "bytes %u to %llu are beyond plugin "
                       "%s's %u-byte parameter block", offset, (unsigned long long)offset + size,
                       p->desc.name, p->desc.param_bytes);
    unsigned char block[TB_PLUGIN_MAX_PARAM_BYTES];
    memcpy(block, p->params, sizeof block);
    if (size) memcpy(block + offset, data, size);
    char why[256] = "";
    if (p->desc.check_params && p->desc.check_params(p->desc.user, block, why, sizeof why))
        return tb_fail(diag_of(pl), TB_ERROR_INVALID_ARGUMENT, "plugin %s refused the parameters: %s",
                       p->desc.name, why[0] ? why : "no reason given");
    memcpy(p->params, block, sizeof block);
    pl->params_dirty = 1;
    return TB_OK;
}
