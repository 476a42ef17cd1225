/* Heightfields on the host: a grid of heights checked and copied, with optional holes, the
 * flags of its triangles (which edges are active, as a mesh's: geom/mesh.h), and the GPU
 * image a heightfield shape's buffer holds (tb_gpu_heightfield_header, glsl/common/layout.h,
 * says how the grid is cut into triangles and laid out).
 *
 * The grid is centred on the body's origin in x and z: sample (i, k) lies at
 * x = (i - (count_x - 1) / 2) * cell_x, z = (k - (count_z - 1) / 2) * cell_z, y its height.
 * A hole cell has no triangles; the edges around it are the grid's border there.
 */
#ifndef TB_GEOM_HEIGHTFIELD_H
#define TB_GEOM_HEIGHTFIELD_H

#include <stddef.h>
#include <stdint.h>

#include "layout.h"

/* Most samples along each side: cells then number fewer than 2^31 triangles, so a
 * triangle's index + 1 fits a pair's sub-shape word. */
#define TB_HEIGHTFIELD_MAX_SAMPLES 32768u

typedef struct tb_heightfield {
    uint32_t count_x, count_z;  /* samples along x and z, at least 2 each */
    float cell_x, cell_z;       /* spacing, m */
    float* heights;             /* count_x * count_z, row by row along x */
    uint32_t* cell_flags;       /* per cell: triangle 2n's TB_MESH_* bits | 2n + 1's << 4 */
    uint32_t hole_count;        /* cells that are holes */
    float lo[3], hi[3];         /* the box of the samples, body frame */
} tb_heightfield;

/* Check and build. Returns 0 and fills *out, or -1 with a sentence in `error` (out
 * untouched, nothing leaked) when heights is NULL, a side has fewer than 2 or more than
 * TB_HEIGHTFIELD_MAX_SAMPLES samples, a cell size is not finite and > 0, the grid spans
 * more than 2e6 m, a height is not finite or beyond 1e6 m, every cell is a hole, or memory
 * runs out. `holes` (may be NULL) has (count_x - 1) * (count_z - 1) bytes, row by row along
 * x; nonzero marks a hole. */
int tb_heightfield_build(const float* heights, uint32_t count_x, uint32_t count_z, float cell_x,
                         float cell_z, const uint8_t* holes, tb_heightfield* out, char* error,
                         size_t error_size);
void tb_heightfield_free(tb_heightfield* field);

/* Size of the GPU image in uvec4, and the image itself. */
size_t tb_heightfield_image_size(const tb_heightfield* field);
void tb_heightfield_pack(const tb_heightfield* field, tb_gpu_uvec4* image);

#endif
