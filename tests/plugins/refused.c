/* Plugins the library must refuse, one per REFUSED_* value (tests/test_plugin.c). */
#include "tumble_plugin.h"

#define REFUSED_NEWER 1       /* built for a newer plugin ABI */
#define REFUSED_NO_ENTRY 2    /* exports no tb_plugin_entry */
#define REFUSED_NOT_SPIRV 3   /* a stage whose blob is not SPIR-V at all */
#define REFUSED_BAD_SPIRV 4   /* a stage whose SPIR-V is broken after a good header */
#define REFUSED_BAD_GLSL 5    /* a stage whose GLSL does not compile */
#define REFUSED_PAIRS_EARLY 6 /* a per-pair stage at the pre-step point */
#define REFUSED_HUGE_STAGE 7  /* two stages whose size field says 2 GB: the second would be
                                 read far past the array */
#define REFUSED_GLSL_DIR 8    /* a stage whose GLSL path names a directory */

#if REFUSED == REFUSED_BAD_SPIRV
/* A module header (magic, version 1.5, generator, bound, schema) and then nonsense. */
static const uint32_t broken_spirv[] = { 0x07230203u, 0x00010500u, 0u, 16u, 0u,
                                         0x00040011u, 0xdeadbeefu, 0x12345678u };
#elif REFUSED == REFUSED_NOT_SPIRV
static const uint32_t not_spirv[] = { 0x464c457fu, 1u, 2u, 3u, 4u, 5u };   /* an ELF header */
#endif

static const tb_plugin_stage stages[] = { {
    .size = sizeof(tb_plugin_stage), .name = "stage", .point = TB_PLUGIN_PRE_STEP,
    .dispatch = TB_PLUGIN_PER_BODY,
#if REFUSED == REFUSED_NOT_SPIRV
    .spirv = not_spirv, .spirv_size = sizeof not_spirv,
#elif REFUSED == REFUSED_BAD_SPIRV
    .spirv = broken_spirv, .spirv_size = sizeof broken_spirv,
#elif REFUSED == REFUSED_GLSL_DIR
    .glsl_path = ".",   /* the folder the shared object is in */
#else
    .glsl_path = "broken.comp",   /* beside the shared object: a syntax error on line 5 */
#endif
} };

#if REFUSED == REFUSED_PAIRS_EARLY
static tb_plugin_stage early_stage(void)
{
    tb_plugin_stage s = stages[0];
    s.dispatch = TB_PLUGIN_PER_PAIR;
    return s;
}
#endif

#if REFUSED == REFUSED_HUGE_STAGE
static tb_plugin_stage huge[2];
#endif

static tb_plugin plugin = {
    .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION, .name = "refused",
    .stage_count = 1, .stages = stages,
};

#if REFUSED == REFUSED_NO_ENTRY
TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry_point(uint32_t host_abi_version);
TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry_point(uint32_t host_abi_version)
#else
TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
#endif
{
    (void)host_abi_version;
#if REFUSED == REFUSED_NEWER
    plugin.abi_version = TB_PLUGIN_ABI_VERSION + 1;
#elif REFUSED == REFUSED_PAIRS_EARLY
    static tb_plugin_stage early[1];
    early[0] = early_stage();
    plugin.stages = early;
#elif REFUSED == REFUSED_HUGE_STAGE
    huge[0] = huge[1] = stages[0];
    huge[0].size = 0x7fffffffu;
    plugin.stages = huge;
    plugin.stage_count = 2;
#endif
    return &plugin;
}
