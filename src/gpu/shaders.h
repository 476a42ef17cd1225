/* The SPIR-V modules compiled from glsl/ at build time and embedded in the library. */
#ifndef TB_SHADERS_H
#define TB_SHADERS_H

#include <stddef.h>
#include <stdint.h>

typedef struct tb_shader_blob {
    const char* name;      ///< path under glsl/ without ".comp", e.g. "integrate/integrate"
    const uint32_t* code;
    size_t size;           ///< bytes
} tb_shader_blob;

extern const tb_shader_blob tb_shader_blobs[];
extern const uint32_t tb_shader_blob_count;

/// The embedded module of that name, or NULL.
const tb_shader_blob* tb_shader_find(const char* name);

#endif
