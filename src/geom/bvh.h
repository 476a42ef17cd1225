/* A bounding volume hierarchy over a triangle mesh, built on the host once per mesh and
 * walked on the GPU without a stack (the mesh midphase).
 *
 * Nodes are stored depth first (tb_gpu_bvh_node, glsl/common/layout.h): an inner node's
 * first child follows it, its second child follows the first child's subtree, and each
 * inner node records where its subtree ends (its skip index), so a walk that rejects a
 * node jumps there and a walk that accepts one steps to the next node. A leaf holds one
 * triangle. Bounds are quantized to 16 bits per axis over the mesh's box, rounded outward,
 * so a node's box always contains its triangles (16 bytes a node, 2n - 1 nodes for n
 * triangles).
 *
 * The split is at the median of the triangles' centres along the widest axis of those
 * centres: every subtree is balanced (depth about log2 n), and building a million
 * triangles takes O(n log n) with no allocation beyond the output and an index array.
 */
#ifndef TB_GEOM_BVH_H
#define TB_GEOM_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "layout.h"

typedef struct tb_bvh {
    tb_gpu_bvh_node* nodes;
    uint32_t node_count, triangle_count;
    float lo[3], hi[3];       /* the mesh's box: quantization spans it */
} tb_bvh;

/* Build the hierarchy of `triangle_count` triangles (three vertex indices each into `xyz`,
 * `vertex_count` xyz triples). Returns 0 and fills *out, or returns -1 and writes a
 * sentence to `error` (never touching *out) when there are no triangles, more than
 * TB_BVH_MAX_TRIANGLES, an index out of range, or a vertex that is not finite. Triangles
 * of zero area are kept (a walk finds them; contact generation skips them). */
int tb_bvh_build(const float* xyz, uint32_t vertex_count, const uint32_t* indices,
                 uint32_t triangle_count, tb_bvh* out, char* error, size_t error_size);

void tb_bvh_free(tb_bvh* bvh);

/* Quantization steps per metre along each axis of the mesh's box (65535 / extent; 0 where
 * the mesh is flat): what a walk needs, with bvh->lo, to quantize its query. */
void tb_bvh_steps_per_metre(const tb_bvh* bvh, double scale[3]);

/* A node's box in mesh coordinates (dequantized): contains the node's triangles. */
void tb_bvh_node_box(const tb_bvh* bvh, uint32_t node, float lo[3], float hi[3]);

/* The stackless walk the GPU does, on the host: calls `visit` with each triangle whose
 * leaf box overlaps the box [lo, hi]; returns how many nodes it looked at. */
uint32_t tb_bvh_query(const tb_bvh* bvh, const float lo[3], const float hi[3],
                      void (*visit)(void* user, uint32_t triangle), void* user);

#endif
