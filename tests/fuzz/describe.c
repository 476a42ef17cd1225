/* Plugin descriptions made from fuzz input: sizes, versions, names, counts, points,
 * dispatch rules and shaders (a test plugin's GLSL, a broken or missing file, or SPIR-V
 * words from the input) are the input's; the memory the description points at is always
 * there, as a plugin's own would be (the loader cannot check a pointer). */
#include "describe.h"

#include <stdio.h>
#include <stdlib.h>

static void fz_name(fz_input* in, char* out, size_t size)
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyz0123456789_-A /";
    uint32_t length = fz_u8(in) % 40u;
    if (length >= size) length = (uint32_t)size - 1;
    for (uint32_t i = 0; i < length; i++) out[i] = letters[fz_u8(in) % (sizeof letters - 1)];
    out[length] = 0;
}

static void fz_shader(fz_input* in, const char* source_dir, tb_plugin_stage* s, char* path,
                      uint32_t* spirv)
{
    uint8_t kind = fz_u8(in) % 6u;
    if (kind < 4) {
        static const char* files[] = { "tests/plugins/poison.comp", "tests/plugins/broken.comp",
                                       "tests/plugins/missing.comp", "glsl/common/layout.h" };
        snprintf(path, 256, "%s/%s", source_dir, files[kind]);
        s->glsl_path = path;
        return;
    }
    if (kind == 4) {   /* a path of its own, relative to the plugin file */
        fz_name(in, path, 256);
        s->glsl_path = path;
        return;
    }
    uint32_t words = fz_u8(in) % 65u;
    for (uint32_t i = 0; i < words; i++) spirv[i] = fz_u8(in) < 128 ? fz_u32(in) : fz_u8(in);
    if (words && fz_u8(in) < 200) spirv[0] = 0x07230203u;   /* SPIR-V's magic number */
    s->spirv = fz_u8(in) ? spirv : NULL;
    s->spirv_size = fz_u8(in) < 240 ? words * 4u : fz_u32(in);
    s->glsl_path = fz_u8(in) < 128 ? NULL : "poison.comp";
}

static void fz_stage(fz_input* in, const char* source_dir, fz_plugin_desc* d, uint32_t i,
                     uint32_t stride)
{
    tb_plugin_stage s;
    memset(&s, 0, sizeof s);
    s.size = stride;
    fz_name(in, d->stage_names[i], sizeof d->stage_names[i]);
    s.name = fz_u8(in) ? d->stage_names[i] : NULL;
    s.point = (tb_plugin_point)(fz_u8(in) % 5u);
    s.dispatch = (tb_plugin_dispatch)(fz_u8(in) % 4u);
    s.groups = fz_u8(in) < 200 ? fz_u8(in) % 4u : fz_u32(in);
    fz_shader(in, source_dir, &s, d->glsl_paths[i], d->spirv[i]);
    size_t copy = stride < sizeof s ? stride : sizeof s;
    memcpy(d->stages + (size_t)i * stride, &s, copy);
}

fz_plugin_desc* fz_plugin_desc_make(fz_input* in, const char* source_dir)
{
    fz_plugin_desc* d = calloc(1, sizeof *d);
    if (!d) abort();
    tb_plugin* p = &d->plugin;
    p->size = fz_u8(in) < 220 ? (uint32_t)sizeof *p : fz_u32(in) % (uint32_t)(sizeof *p + 1);
    p->abi_version = fz_u8(in) < 230 ? TB_PLUGIN_ABI_VERSION : fz_u32(in);
    fz_name(in, d->name, sizeof d->name);
    p->name = fz_u8(in) ? d->name : NULL;
    p->param_bytes = fz_u8(in) < 230 ? fz_u8(in) % 32u : fz_u32(in);
    for (uint32_t i = 0; i < sizeof d->params; i++) d->params[i] = (unsigned char)i;
    p->default_params = fz_u8(in) & 1 ? d->params : NULL;
    p->stage_count = fz_u8(in) < 240 ? fz_u8(in) % 3u : fz_u32(in);
    uint32_t stride = (uint32_t)sizeof(tb_plugin_stage);
    uint8_t odd = fz_u8(in);
    if (odd >= 240) stride = fz_u32(in);
    uint32_t built = p->stage_count < TB_PLUGIN_MAX_STAGES + 2 ? p->stage_count
                                                               : TB_PLUGIN_MAX_STAGES + 2;
    uint32_t safe_stride = stride < FZ_STAGE_STRIDE_MAX ? (stride ? stride : 1) : FZ_STAGE_STRIDE_MAX;
    for (uint32_t i = 0; i < built; i++) fz_stage(in, source_dir, d, i, safe_stride);
    if (stride != safe_stride && built)   /* the first stage's size field says the odd stride */
        memcpy(d->stages, &stride, sizeof stride);
    p->stages = fz_u8(in) ? (const tb_plugin_stage*)(void*)d->stages : NULL;
    return d;
}

void fz_plugin_desc_free(fz_plugin_desc* desc)
{
    free(desc);
}
