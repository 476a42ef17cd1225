/* SPIR-V that did not come from the build (a plugin's stage, a shader compiled from a shader
 * directory) is checked before Vulkan sees it: a module the driver or the validation layer
 * would reject (or crash on, or run against the wrong buffer) is refused with a sentence
 * instead. */
#include <spirv-tools/libspirv.h>
#include <string.h>

#include "gpu/pipeline.h"
#include "layout.h"

#define SPIRV_MAGIC 0x07230203u
#define OP_ENTRY_POINT 15u
#define OP_DECORATE 71u
#define EXECUTION_GL_COMPUTE 5u
#define DECORATION_BINDING 33u
#define DECORATION_DESCRIPTOR_SET 34u

static tb_result validate(tb_diag* diag, const char* what, const uint32_t* words, size_t count)
{
    spv_context context = spvContextCreate(SPV_ENV_VULKAN_1_2);
    spv_diagnostic diagnostic = NULL;
    spv_result_t result = context ? spvValidateBinary(context, words, count, &diagnostic)
                                  : SPV_ERROR_OUT_OF_MEMORY;
    tb_result r = TB_OK;
    if (result != SPV_SUCCESS)
        r = tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s is not valid SPIR-V for Vulkan 1.2: %s",
                    what, diagnostic && diagnostic->error ? diagnostic->error : "no reason given");
    spvDiagnosticDestroy(diagnostic);
    spvContextDestroy(context);
    return r;
}

/* A compute entry point named "main"; every resource in set 0 at a binding of the world's
 * set. (The validator already checked that instructions are well formed.) */
static tb_result check_interface(tb_diag* diag, const char* what, const uint32_t* words,
                                 size_t count)
{
    int has_main = 0;
    for (size_t at = 5; at < count;) {
        uint32_t length = words[at] >> 16, op = words[at] & 0xffffu;
        if (length == 0 || at + length > count) break;
        if (op == OP_ENTRY_POINT && length >= 4 && words[at + 1] == EXECUTION_GL_COMPUTE &&
            memcmp(&words[at + 3], "main", 5) == 0)
            has_main = 1;
        if (op == OP_DECORATE && length >= 4 && words[at + 2] == DECORATION_DESCRIPTOR_SET &&
            words[at + 3] != 0)
            return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s uses descriptor set %u; "
                           "Tumble's shaders have set 0 only", what, words[at + 3]);
        if (op == OP_DECORATE && length >= 4 && words[at + 2] == DECORATION_BINDING &&
            words[at + 3] >= TB_BIND_COUNT)
            return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s uses binding %u, which the world's "
                           "set does not have (see tumble_plugin.glsl)", what, words[at + 3]);
        at += length;
    }
    if (!has_main)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s has no compute entry point named main",
                       what);
    return TB_OK;
}

tb_result tb_spirv_check_module(tb_diag* diag, const char* what, const uint32_t* code, size_t size)
{
    if (!code || size < 20 || size % 4 != 0)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s is not SPIR-V: %zu bytes is no "
                       "whole module", what, size);
    if (code[0] != SPIRV_MAGIC)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s is not SPIR-V: it starts with "
                       "%#010x, not the magic number 0x07230203", what, code[0]);
    tb_result r = validate(diag, what, code, size / 4);
    return r ? r : check_interface(diag, what, code, size / 4);
}
