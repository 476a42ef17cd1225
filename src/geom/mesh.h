/* Triangle meshes on the host: the caller's vertices and triangles checked and copied, each
 * triangle's flags (which of its edges are active, whether it is degenerate), the BVH over
 * them (geom/bvh.h), and the GPU image a mesh shape's buffer holds (tb_gpu_mesh_header,
 * glsl/common/layout.h, says how it is laid out and what the flags mean).
 *
 * Adjacency is by vertex index: two triangles are neighbours across an edge when they use
 * the same two vertex indices, never because their vertices happen to sit at the same
 * place. A mesh whose triangles each carry their own copies of shared corners (a "soup", as
 * some exporters write them) has every edge on its border, so every edge active and bumps
 * where the triangles meet: callers should weld such vertices into one index first.
 *
 * Degenerate triangles (a repeated vertex index, or an area too small for a float cross
 * product of their edges to give a direction) are kept, flagged TB_MESH_DEGENERATE, get no
 * contacts and neighbour nobody: the edges they share with other triangles count as those
 * triangles' border.
 */
#ifndef TB_GEOM_MESH_H
#define TB_GEOM_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "geom/bvh.h"
#include "layout.h"

/* How far from the mesh's origin a vertex may lie (m): a float there still resolves about
 * 6 cm, and farther than this a mesh is almost surely in the wrong units. */
#define TB_MESH_MAX_COORDINATE 1.0e6

/* A triangle is degenerate when twice its area is below this times its longest edge
 * squared: about float's epsilon, under which the float cross product of two edges that
 * the GPU takes for the normal is mostly rounding. */
#define TB_MESH_DEGENERATE_RATIO 1.1920929e-7

typedef struct tb_mesh {
    tb_bvh bvh;                 /* from tb_bvh_build over the same triangles */
    float* xyz;                 /* vertex_count xyz triples (a copy of the input) */
    uint32_t* indices;          /* 3 per triangle (a copy), counter-clockwise seen from the
                                   front, the side the triangle collides on */
    uint32_t* flags;            /* per triangle: TB_MESH_EDGE_ACTIVE_k bits (edge k runs from
                                   corner k to corner k + 1 mod 3), or TB_MESH_DEGENERATE
                                   alone */
    uint32_t vertex_count, triangle_count;
    uint32_t degenerate_count;  /* triangles flagged degenerate */
} tb_mesh;

/* Check and build a mesh of `triangle_count` triangles (three indices each into `xyz`,
 * `vertex_count` xyz triples, m). Returns 0 and fills *out, or returns -1 and writes a
 * sentence to `error` (never touching *out, leaking nothing) when xyz or indices is NULL,
 * there are no triangles or more than TB_BVH_MAX_TRIANGLES, more vertices than the GPU
 * image can address, an index is out of range, a coordinate is not finite or beyond
 * TB_MESH_MAX_COORDINATE, every triangle is degenerate, or memory runs out. Takes
 * O(n log n) time for n triangles (a million in well under a second). */
int tb_mesh_build(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                  uint32_t triangle_count, tb_mesh* out, char* error, size_t error_size);

void tb_mesh_free(tb_mesh* mesh);

/* The flags alone, as tb_mesh_build finds them, of a mesh whose xyz, indices and counts
 * are set and checked (no BVH is built): allocates mesh->flags and sets degenerate_count.
 * Returns -1 when out of memory (flags then NULL). Heightfields use it for their grid. */
int tb_mesh_flag_edges(tb_mesh* mesh);

/* Size of the mesh's GPU image in uvec4: the header, the BVH's nodes, the triangles, the
 * vertices. */
size_t tb_mesh_image_size(const tb_mesh* mesh);

/* Write the GPU image, tb_mesh_image_size(mesh) uvec4 at `image`: the header
 * (tb_gpu_mesh_header: the BVH's box and quantization scale with the node, triangle and
 * vertex counts in their w, and where each section starts), the nodes, each triangle as
 * (i0, i1, i2, flags), each vertex as (x, y, z, 0) in float bits. */
void tb_mesh_pack(const tb_mesh* mesh, tb_gpu_uvec4* image);

#endif
