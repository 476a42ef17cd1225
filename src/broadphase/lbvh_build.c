/* Linear BVH build: the two passes and their push constants (see gpu/lbvh.h). */
#include "broadphase/lbvh_build.h"

#include <string.h>

tb_result tb_lbvh_kernels_create(tb_lbvh_kernels* k, tb_pipelines* pipelines)
{
    tb_result r = tb_pipeline_create(pipelines, "broadphase/lbvh_build_hierarchy",
                                     TB_WORKGROUP_SIZE, &k->hierarchy);
    if (!r) r = tb_pipeline_create(pipelines, "broadphase/lbvh_build_refit", TB_WORKGROUP_SIZE,
                                   &k->refit);
    return r;
}

void tb_lbvh_kernels_destroy(tb_lbvh_kernels* k, tb_pipelines* pipelines)
{
    tb_pipeline_destroy(pipelines, k->hierarchy);
    tb_pipeline_destroy(pipelines, k->refit);
    k->hierarchy = k->refit = VK_NULL_HANDLE;
}

VkDeviceSize tb_lbvh_node_bytes(uint32_t capacity)
{
    return 2 * (VkDeviceSize)(capacity ? capacity : 1) * sizeof(tb_gpu_lbvh_node);
}

VkDeviceSize tb_lbvh_link_bytes(uint32_t capacity)
{
    return ((VkDeviceSize)TB_LBVH_LINK_SECTIONS * capacity + 1) * sizeof(uint32_t);
}

static tb_gpu_uvec4 two_addresses(tb_gpu_ptr a, tb_gpu_ptr b)
{
    tb_gpu_uvec4 v = { (uint32_t)a.address, (uint32_t)(a.address >> 32),
                       (uint32_t)b.address, (uint32_t)(b.address >> 32) };
    return v;
}

static tb_pass build_pass(VkPipeline pipeline, const tb_lbvh_build* b,
                          const tb_gpu_lbvh_push* push)
{
    tb_pass pass;
    memset(&pass, 0, sizeof pass);
    pass.pipeline = pipeline;
    pass.rule = b->rule;
    pass.groups[0] = b->groups ? b->groups : 1;
    pass.groups[1] = pass.groups[2] = 1;
    pass.indirect = b->indirect.buffer;
    pass.indirect_offset = b->indirect.offset;
    pass.push_size = sizeof *push;
    memcpy(pass.push, push, sizeof *push);
    return pass;
}

tb_result tb_lbvh_record_build(const tb_lbvh_kernels* k, tb_pass_list* list, tb_diag* diag,
                               const tb_lbvh_build* build)
{
    tb_gpu_lbvh_push push;
    memset(&push, 0, sizeof push);
    push.args.x = build->capacity;
    push.keys = two_addresses(build->keys, build->items);
    push.counts = two_addresses(build->count, build->skip);
    push.tree = two_addresses(build->nodes, build->links);
    push.boxes = two_addresses(build->box_min, build->box_max);
    tb_pass hierarchy = build_pass(k->hierarchy, build, &push);
    tb_pass refit = build_pass(k->refit, build, &push);
    tb_result r = tb_pass_list_add(list, diag, &hierarchy);
    if (!r) r = tb_pass_list_add(list, diag, &refit);
    return r;
}
