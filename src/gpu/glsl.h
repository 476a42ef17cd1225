/* GLSL compiled at run time (libshaderc, glslang underneath), as the build compiles it:
 * Vulkan 1.2 SPIR-V, `#include "x"` looked up beside the including file, then in the
 * include directories, then among the embedded headers. Used by shader hot-reload and by plugins that give a GLSL path. */
#ifndef TB_GLSL_H
#define TB_GLSL_H

#include <stddef.h>
#include <stdint.h>

#include "base/diag.h"

/// A header every run-time compilation can include: abi/tumble_plugin.glsl and
/// glsl/common/layout.h, embedded in the library at build time (build/glsl_headers.c).
typedef struct tb_glsl_header {
    const char* name;      ///< as an #include names it, e.g. "layout.h"
    const char* text;
} tb_glsl_header;

extern const tb_glsl_header tb_glsl_headers[];
extern const uint32_t tb_glsl_header_count;

/// A compiled module and every file it was made of (the source first, then its includes,
/// as the paths were opened).
typedef struct tb_spirv {
    uint32_t* code;
    size_t size;            ///< bytes
    char** files;
    uint32_t file_count;
} tb_spirv;

/// Compile the compute shader at `path` (the embedded headers are no files: they are not
/// listed in tb_spirv.files). On failure the result is TB_ERROR_INVALID_ARGUMENT
/// and diag's message holds the compiler's first line ("file:line: error: ...").
/// `include_dirs` may be NULL when `include_dir_count` is 0.
tb_result tb_glsl_compile(tb_diag* diag, const char* path, const char* const* include_dirs,
                          uint32_t include_dir_count, tb_spirv* out);
/// Does the module depend on `file` (a path as tb_spirv.files holds them)?
int tb_spirv_uses(const tb_spirv* spirv, const char* file);
void tb_spirv_free(tb_spirv* spirv);

#endif
