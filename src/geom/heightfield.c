/* Heightfields: input checks, the triangles' flags, the GPU image (see heightfield.h).
 *
 * The flags come from the mesh rule itself (geom/mesh.h): the grid is handed to the
 * mesh's edge finder as the triangles it stands for, a hole's two as degenerate (a
 * repeated corner), so a heightfield and the same surface given as a mesh have the same
 * active edges.
 */
#include "geom/heightfield.h"
#include "geom/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom/mesh.h"

#define MAX_HEIGHT 1.0e6     /* m, as a mesh's coordinates */
#define MAX_SPAN 2.0e6       /* m, the grid's extent along x or z */
#define HEADER_UVEC4 (sizeof(tb_gpu_heightfield_header) / sizeof(tb_gpu_uvec4))

static int check(const float* heights, uint32_t nx, uint32_t nz, float cx, float cz,
                 char* error, size_t size)
{
    if (!heights) return tb_geom_fail(error, size, "heights are NULL");
    if (nx < 2 || nz < 2 || nx > TB_HEIGHTFIELD_MAX_SAMPLES || nz > TB_HEIGHTFIELD_MAX_SAMPLES)
        return tb_geom_fail(error, size, "a heightfield needs 2 to %u samples along each side, not "
                    "%u x %u", TB_HEIGHTFIELD_MAX_SAMPLES, nx, nz);
    if (!isfinite(cx) || !isfinite(cz) || !(cx > 0) || !(cz > 0))
        return tb_geom_fail(error, size, "cell sizes must be finite and > 0, not %g x %g", (double)cx,
                    (double)cz);
    if ((double)cx * (nx - 1) > MAX_SPAN || (double)cz * (nz - 1) > MAX_SPAN)
        return tb_geom_fail(error, size, "the grid spans more than %g m", MAX_SPAN);
    for (size_t i = 0; i < (size_t)nx * nz; i++)
        if (!isfinite(heights[i]) || fabs(heights[i]) > MAX_HEIGHT)
            return tb_geom_fail(error, size, "height %zu (sample %zu, %zu) is %g: heights must be "
                        "finite and within %g m", i, i % nx, i / nx, (double)heights[i],
                        MAX_HEIGHT);
    return 0;
}

/* Sample (i, k) as a point of the body frame. */
static void sample(const tb_heightfield* f, uint32_t i, uint32_t k, float* p)
{
    p[0] = f->lo[0] + (float)i * f->cell_x;
    p[1] = f->heights[(size_t)k * f->count_x + i];
    p[2] = f->lo[2] + (float)k * f->cell_z;
}

/* The grid as a mesh, flagged by the mesh's rule; its flags packed per cell. */
static int flag_cells(tb_heightfield* f, const uint8_t* holes)
{
    uint32_t cells_x = f->count_x - 1, cells_z = f->count_z - 1;
    size_t cells = (size_t)cells_x * cells_z, samples = (size_t)f->count_x * f->count_z;
    tb_mesh m = { .vertex_count = (uint32_t)samples, .triangle_count = (uint32_t)(2 * cells) };
    m.xyz = malloc(3 * samples * sizeof *m.xyz);
    m.indices = malloc(6 * cells * sizeof *m.indices);
    int failed = !m.xyz || !m.indices;
    for (uint32_t k = 0; !failed && k < f->count_z; k++)
        for (uint32_t i = 0; i < f->count_x; i++) sample(f, i, k, m.xyz + 3 * ((size_t)k * f->count_x + i));
    for (size_t n = 0; !failed && n < cells; n++) {
        uint32_t i = (uint32_t)(n % cells_x), k = (uint32_t)(n / cells_x);
        uint32_t a = k * f->count_x + i, b = a + 1, c = a + f->count_x, d = c + 1;
        uint32_t* t = m.indices + 6 * n;
        if (holes && holes[n]) a = b = c = d;   /* degenerate: nobody's neighbour */
        t[0] = a; t[1] = c; t[2] = b;
        t[3] = b; t[4] = c; t[5] = d;
    }
    if (!failed) failed = tb_mesh_flag_edges(&m);
    for (size_t n = 0; !failed && n < cells; n++)
        f->cell_flags[n] = m.flags[2 * n] | m.flags[2 * n + 1] << 4;
    free(m.xyz);
    free(m.indices);
    free(m.flags);
    return failed ? -1 : 0;
}

int tb_heightfield_build(const float* heights, uint32_t count_x, uint32_t count_z, float cell_x,
                         float cell_z, const uint8_t* holes, tb_heightfield* out, char* error,
                         size_t error_size)
{
    if (check(heights, count_x, count_z, cell_x, cell_z, error, error_size)) return -1;
    size_t samples = (size_t)count_x * count_z, cells = (size_t)(count_x - 1) * (count_z - 1);
    tb_heightfield f = { count_x, count_z, cell_x, cell_z, NULL, NULL, 0, { 0 }, { 0 } };
    for (size_t n = 0; holes && n < cells; n++) f.hole_count += holes[n] != 0;
    if (f.hole_count == cells) return tb_geom_fail(error, error_size, "every cell is a hole");
    f.heights = malloc(samples * sizeof *f.heights);
    f.cell_flags = malloc(cells * sizeof *f.cell_flags);
    if (!f.heights || !f.cell_flags) {
        tb_heightfield_free(&f);
        return tb_geom_fail(error, error_size, "no host memory for a heightfield of %zu samples", samples);
    }
    memcpy(f.heights, heights, samples * sizeof *f.heights);
    float low = heights[0], high = heights[0];
    for (size_t i = 1; i < samples; i++) {
        low = fminf(low, heights[i]);
        high = fmaxf(high, heights[i]);
    }
    f.lo[0] = -0.5f * cell_x * (float)(count_x - 1);
    f.lo[2] = -0.5f * cell_z * (float)(count_z - 1);
    f.hi[0] = -f.lo[0];
    f.hi[2] = -f.lo[2];
    f.lo[1] = low;
    f.hi[1] = high;
    if (flag_cells(&f, holes)) {
        tb_heightfield_free(&f);
        return tb_geom_fail(error, error_size, "no host memory for the edges of a heightfield of %zu "
                    "cells", cells);
    }
    *out = f;
    return 0;
}

void tb_heightfield_free(tb_heightfield* f)
{
    free(f->heights);
    free(f->cell_flags);
    f->heights = NULL;
    f->cell_flags = NULL;
}

static size_t in_uvec4(size_t words)
{
    return (words + 3) / 4;
}

size_t tb_heightfield_image_size(const tb_heightfield* f)
{
    size_t samples = (size_t)f->count_x * f->count_z;
    size_t cells = (size_t)(f->count_x - 1) * (f->count_z - 1);
    return HEADER_UVEC4 + in_uvec4(samples) + in_uvec4(cells);
}

void tb_heightfield_pack(const tb_heightfield* f, tb_gpu_uvec4* image)
{
    size_t samples = (size_t)f->count_x * f->count_z;
    size_t cells = (size_t)(f->count_x - 1) * (f->count_z - 1);
    uint32_t first_height = (uint32_t)HEADER_UVEC4;
    uint32_t first_flags = first_height + (uint32_t)in_uvec4(samples);
    tb_gpu_heightfield_header h = {
        .lo = { f->lo[0], f->lo[1], f->lo[2], f->cell_x },
        .hi = { f->hi[0], f->hi[1], f->hi[2], f->cell_z },
        .counts = { f->count_x, f->count_z, first_height, first_flags },
    };
    memcpy(image, &h, sizeof h);
    uint32_t* words = (uint32_t*)(image + first_height);
    for (size_t i = 0; i < 4 * in_uvec4(samples); i++)
        words[i] = i < samples ? tb_geom_float_bits(f->heights[i]) : 0;
    words = (uint32_t*)(image + first_flags);
    for (size_t n = 0; n < 4 * in_uvec4(cells); n++) words[n] = n < cells ? f->cell_flags[n] : 0;
}
