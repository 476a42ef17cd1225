/* Plugin descriptions made from fuzz input (tests/fuzz/describe.c). */
#ifndef TUMBLE_FUZZ_DESCRIBE_H
#define TUMBLE_FUZZ_DESCRIBE_H

#include "input.h"
#include "tumble_plugin.h"

#define FZ_STAGE_STRIDE_MAX 4096u

/* A tb_plugin and everything it points at, owned together. */
typedef struct fz_plugin_desc {
    tb_plugin plugin;
    char name[48];
    unsigned char params[TB_PLUGIN_MAX_PARAM_BYTES + 16];
    /* Room for TB_PLUGIN_MAX_STAGES + 2 stages at the largest stride the loader takes. */
    unsigned char stages[(TB_PLUGIN_MAX_STAGES + 2) * FZ_STAGE_STRIDE_MAX];
    char stage_names[TB_PLUGIN_MAX_STAGES + 2][48];
    char glsl_paths[TB_PLUGIN_MAX_STAGES + 2][256];
    uint32_t spirv[TB_PLUGIN_MAX_STAGES + 2][64];
} fz_plugin_desc;

/* A description from the input; `source_dir` is the repository, for its test shaders. */
fz_plugin_desc* fz_plugin_desc_make(fz_input* in, const char* source_dir);
void fz_plugin_desc_free(fz_plugin_desc* desc);

#endif
