/* The narrowphase: the host side of glsl/narrowphase/.
 *
 * Reads this step's pairs (the broadphase's), the bodies' poses and the shape table, the
 * packed hulls (the hull table below) and last step's manifolds. Writes one manifold per
 * pair (up to four points sharing a normal, with last step's impulses of the same features
 * for the warm start). The manifolds alternate between two arrays by the step's parity, so
 * this step's, with the solver's final impulses, are last step's for the next where they
 * lie. Its passes:
 *   narrowphase/contacts     one thread per pair: the manifold; a hull pair gets only last
 *                            step's separating axis tried, and the pairs that does not
 *                            decide are listed for
 *   narrowphase/hull_sat     the separating axis test of those, a subgroup per pair
 *   narrowphase/hull_points  the touching hull pairs' points (clip and reduce); hull_sat and
 *                            hull_points are recorded only while the world has hull shapes
 *   narrowphase/round_cull, round_order, round_points
 *                            the points of every pair with a capsule, cylinder or cone
 *                            (against any convex shape, a plane or a mesh triangle):
 *                            those surely apart given their empty manifold, the others
 *                            grouped by kind, then their points; recorded only while the
 *                            world has such shapes
 *   narrowphase/mesh_points  the points of each pair of a body and a mesh triangle (the
 *                            broadphase split the body pair by triangle), then
 *   narrowphase/mesh_reduce  at most four of them per body pair; both recorded only while
 *                            the world has mesh shapes
 * Per-pair passes are dispatched with counters.pair_dispatch.
 *
 * The hull table packs the geometry of every live hull and box shape into the two buffers
 * bound at TB_BIND_HULL_VECTORS and TB_BIND_HULL_TOPOLOGY (layout.h). Shapes are few and
 * change rarely next to bodies, so any change marks it dirty and the next upload packs every
 * live hull again, in slot order, rewriting each shape's locator (tb_gpu_shape.hull). The
 * buffers grow to the next power of two when the packed data outgrows them; that replaces a
 * binding, so the step is recorded again.
 */
#ifndef TB_NARROWPHASE_H
#define TB_NARROWPHASE_H

#include "geom/geom.h"
#include "gpu/gpu.h"
#include "layout.h"

/// Every live hull's GPU data, packed.
typedef struct tb_hull_table {
    tb_buffer vector_buffer, topology_buffer;
    uint32_t vector_capacity, topology_capacity; ///< elements of the buffers and host images
    tb_gpu_vec4* vectors;        ///< host image of hull_vectors
    uint32_t* topology;          ///< host image of hull_topology
    uint32_t vectors_used, topology_used;
    int dirty;                   ///< a hull shape came or went: pack again
    int upload;                  ///< packed data not yet uploaded
} tb_hull_table;

typedef struct tb_narrowphase {
    tb_gpu_kit kit;
    VkPipeline contacts, hull_sat, hull_points;
    VkPipeline mesh_points, mesh_reduce;   ///< made when the world's first mesh comes
    /// made when the world's first round shape comes: the round pairs apart sorted out, the
    /// others counted and grouped by kind, then their points
    VkPipeline round_order, round_cull, round_points;
    tb_hull_table hulls;
} tb_narrowphase;

/// The shapes as the hull table packs them: per shape slot, its hull (NULL for a dead slot
/// or a shape without one), and the GPU shape table whose locators packing rewrites.
typedef struct tb_hull_shapes {
    uint32_t count;
    const tb_hull* (*hull_at)(const void* owner, uint32_t slot);
    const void* owner;
    tb_gpu_shape* gpu_shapes;
} tb_hull_shapes;

/// The first hull buffers (bound; the pipelines are made as the step is first recorded).
/// *replaced: buffers were bound.
tb_result tb_narrowphase_init(tb_narrowphase* np, const tb_gpu_kit* kit, int* replaced);
void tb_narrowphase_destroy(tb_narrowphase* np);

/// narrowphase/contacts; `counters` is the buffer bound at TB_BIND_COUNTERS. With `listed`
/// (while round shapes live, after round_cull) over the pairs round_order listed for it,
/// otherwise over every pair. Its pipeline is made the first time.
tb_result tb_narrowphase_record_contacts(tb_narrowphase* np, tb_pass_list* list,
                                         VkBuffer counters, int listed);
/// narrowphase/hull_sat, the separating axis test of the hull pairs contacts listed
/// (recorded only while the world has hull shapes, between contacts and hull_points; its
/// pipeline is made the first time, as hull_points's).
tb_result tb_narrowphase_record_hull_sat(tb_narrowphase* np, tb_pass_list* list,
                                         VkBuffer counters);
/// narrowphase/hull_points, the points of the touching hull pairs (recorded only while the
/// world has hull shapes); `listed` as for contacts.
tb_result tb_narrowphase_record_hull_points(tb_narrowphase* np, tb_pass_list* list,
                                            VkBuffer counters, int listed);
/// narrowphase/mesh_points and mesh_reduce, the points of the mesh pairs (recorded only
/// while the world has mesh shapes; their pipelines are made the first time).
tb_result tb_narrowphase_record_mesh_points(tb_narrowphase* np, tb_pass_list* list,
                                            VkBuffer counters);
/// narrowphase/round_cull and round_order: the pairs with a capsule, cylinder or cone that
/// are surely apart given their empty manifold, the others counted and grouped by kind for
/// round_points (recorded only while the world has such shapes, before round_points; their
/// pipelines are made the first time).
tb_result tb_narrowphase_record_round_cull(tb_narrowphase* np, tb_pass_list* list,
                                           VkBuffer counters);
/// narrowphase/round_points, the points of the round pairs round_cull listed.
tb_result tb_narrowphase_record_round_points(tb_narrowphase* np, tb_pass_list* list,
                                             VkBuffer counters);

/// Pack the hulls again if shapes changed (may replace the buffers: *replaced set).
/// Rewrites the locators of every hull shape in shapes->gpu_shapes.
tb_result tb_hull_table_prepare(tb_narrowphase* np, const tb_hull_shapes* shapes, int* replaced);
/// Staging bytes of the upload packing left, if any.
VkDeviceSize tb_hull_table_upload_bytes(const tb_narrowphase* np);
void tb_hull_table_record_upload(tb_narrowphase* np, tb_transfer* transfer);

#endif
