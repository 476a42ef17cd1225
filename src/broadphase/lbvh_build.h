/* Linear BVH build on the GPU (Karras 2012), for any set of boxes: the broadphase's
 * bodies today, a mesh's triangles or ray queries later.
 *
 * The caller gives items sorted by key (a Morton code of each box's centre, below
 * TB_LBVH_KEY_END; keys at or above it are no leaves and sort last) and a box per item; the
 * build writes the nodes and links (layout.h: tb_gpu_lbvh_node, TB_LBVH_LINK_*) and the leaf
 * count after the links' sections. Two passes, whatever the count:
 *   broadphase/lbvh_build_hierarchy   every internal node's children, parents, range end
 *   broadphase/lbvh_build_refit       leaf boxes, then each internal node's box and escape,
 *                                     bottom-up (the second child to arrive goes on)
 * Every operand is a device address (push constants), as for the parallel primitives.
 */
#ifndef TB_BROADPHASE_LBVH_BUILD_H
#define TB_BROADPHASE_LBVH_BUILD_H

#include "gpu/graph.h"
#include "gpu/prims.h"
#include "layout.h"

typedef struct tb_lbvh_kernels {
    VkPipeline hierarchy, refit;
} tb_lbvh_kernels;

tb_result tb_lbvh_kernels_create(tb_lbvh_kernels* k, tb_pipelines* pipelines);
void tb_lbvh_kernels_destroy(tb_lbvh_kernels* k, tb_pipelines* pipelines);

/// Bytes of the node array for `capacity` items (internal nodes, then leaves).
VkDeviceSize tb_lbvh_node_bytes(uint32_t capacity);
/// Bytes of the links array for `capacity` items (sections, then the leaf count).
VkDeviceSize tb_lbvh_link_bytes(uint32_t capacity);

typedef struct tb_lbvh_build {
    uint32_t capacity;        ///< items the arrays hold
    tb_gpu_ptr keys, items;   ///< sorted keys and their items (uint each)
    tb_gpu_ptr count;         ///< uint: how many sorted keys (at most capacity)
    tb_gpu_ptr skip;          ///< uint that, when nonzero, stops every pass; address 0: none
    tb_gpu_ptr nodes, links;  ///< tb_lbvh_node_bytes / tb_lbvh_link_bytes, written
    tb_gpu_ptr box_min, box_max; ///< vec4 per item (xyz used), indexed by item
    /// How the passes are dispatched: one thread per key must be covered (threads past the
    /// count return); TB_DISPATCH_PER_BODY when the keys are the world's body slots.
    tb_dispatch_rule rule;
    uint32_t groups;          ///< workgroups for TB_DISPATCH_FIXED
    tb_gpu_ptr indirect;      ///< the command for TB_DISPATCH_INDIRECT
} tb_lbvh_build;

/// Append the build's passes to the list.
tb_result tb_lbvh_record_build(const tb_lbvh_kernels* k, tb_pass_list* list, tb_diag* diag,
                               const tb_lbvh_build* build);

#endif
