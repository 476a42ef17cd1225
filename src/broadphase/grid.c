/* The uniform grid broadphase (glsl/broadphase/grid*.comp): each body in the cell of its
 * AABB's centre, sorted by cell hash; a body searches its own cell and the 13 "forward" of
 * its 26 neighbours (the other 13 search it). Large static bodies stay out of the grid and are tested by every dynamic body.
 * Its buffers are the grid bindings of the world's set (src/world/sim.c sizes them). */
#include "broadphase/broadphase.h"

#include <stdlib.h>

typedef struct grid_state {
    VkPipeline assign, ranges, pairs;
} grid_state;

static void grid_destroy(tb_broadphase_ctx* bp)
{
    grid_state* g = bp->state;
    if (!g) return;
    VkPipeline all[] = { g->assign, g->ranges, g->pairs };
    tb_broadphase_destroy_pipelines(bp, all, sizeof all / sizeof all[0]);
    free(g);
    bp->state = NULL;
}

static tb_result grid_create(tb_broadphase_ctx* bp)
{
    grid_state* g = calloc(1, sizeof *g);
    if (!g) return tb_fail(bp->kit.diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    bp->state = g;
    tb_pipelines* p = bp->kit.pipelines;
    tb_result r = tb_pipeline_create(p, "broadphase/grid_assign", TB_WORKGROUP_SIZE, &g->assign);
    if (!r) r = tb_pipeline_create(p, "broadphase/grid_ranges", TB_WORKGROUP_SIZE, &g->ranges);
    if (!r) r = tb_pipeline_create(p, "broadphase/grid_pairs", TB_WORKGROUP_SIZE, &g->pairs);
    return r;
}

static tb_result grid_reserve(tb_broadphase_ctx* bp, uint32_t capacity)
{
    (void)bp;
    (void)capacity;   /* the grid's buffers grow with the sim's per-body buffers */
    return TB_OK;
}

static tb_result grid_record(tb_broadphase_ctx* bp, tb_pass_list* list, tb_broadphase_search* search)
{
    grid_state* g = bp->state;
    const tb_broadphase_io* io = &bp->io;
    tb_gpu_ptr entries = io->slots;
    tb_gpu_ptr none = { 0 };
    tb_gpu_broadphase_push count = { { TB_BROADPHASE_COUNT, 0, 0, 0 }, { { 0 } } };
    tb_gpu_broadphase_push write = { { TB_BROADPHASE_WRITE, 0, 0, 0 }, { { 0 } } };
    tb_result r = tb_broadphase_add(bp, list, g->assign, TB_DISPATCH_PER_BODY, 0, none, &count);
    if (!r) r = tb_prims_sort(bp->kit.prims, list, io->grid_keys, io->grid_bodies, entries,
                              io->body_capacity, io->grid_key_bits, io->scratch);
    if (!r) r = tb_prims_compact(bp->kit.prims, list, io->large_flags, io->large_list, entries,
                                 io->body_capacity, io->large_count, io->scratch);
    if (!r) r = tb_broadphase_add(bp, list, g->ranges, TB_DISPATCH_PER_BODY, 0, none, &count);
    search->counts[0] = tb_broadphase_pass(g->pairs, TB_DISPATCH_PER_BODY, 0, none, &count);
    search->writes[0] = tb_broadphase_pass(g->pairs, TB_DISPATCH_PER_BODY, 0, none, &write);
    search->n = 1;
    return r;
}

const tb_broadphase_ops tb_broadphase_grid = {
    "grid", "broadphase/grid", grid_create, grid_reserve, grid_record, grid_destroy, 0, NULL,
};
