/* The renderer's SPIR-V, compiled from tools/render/shaders/ and embedded at build time. */
#ifndef TUMBLE_RENDER_SHADERS_H
#define TUMBLE_RENDER_SHADERS_H

#include <stddef.h>
#include <stdint.h>

typedef struct tr_shader_blob {
    const char* name;       ///< file name, e.g. "mesh.vert"
    const uint32_t* code;
    size_t size;            ///< bytes
} tr_shader_blob;

extern const tr_shader_blob tr_shader_blobs[];
extern const uint32_t tr_shader_blob_count;

#endif
