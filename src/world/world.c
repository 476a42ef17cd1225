/* The world: creation and destruction, and room for bodies. */
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define DEFAULT_MAX_BODIES (1u << 24)
#define DEFAULT_MAX_SHAPES (1u << 20)
#define INITIAL_SHAPE_CAPACITY 16u
#define INITIAL_COLOUR_ROUNDS 16u
#define TRANSFER_BOTH (VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT)

static uint16_t next_world_serial(void)
{
    static uint16_t serial;
    uint16_t s = __atomic_add_fetch(&serial, 1, __ATOMIC_RELAXED);
    return s ? s : __atomic_add_fetch(&serial, 1, __ATOMIC_RELAXED);
}

static int env_flag(const char* name)
{
    const char* v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

static tb_result create_gpu_objects(tb_world* w, const tb_world_def* def,
                                    const tb_gpu_options* extra)
{
    w->kit = (tb_gpu_kit){ &w->diag, &w->gpu, &w->memory, &w->pipelines, &w->transfer,
                           &w->prims, &w->graph };
    tb_gpu_options options = *extra;
    options.device = def->device;
    options.validation = def->validation || env_flag("TUMBLE_VALIDATION");
    tb_result r = tb_gpu_create(&w->gpu, &options, &w->diag);
    if (!r) r = tb_memory_init(&w->memory, &w->gpu);
    if (!r) r = tb_pipelines_init(&w->pipelines, &w->gpu, def->pipeline_cache_path);
    if (!r) r = tb_world_shader_dir_from_env(w);
    if (!r) r = tb_transfer_init(&w->transfer, &w->memory);
    if (!r) r = tb_graph_init(&w->graph, &w->gpu, &w->pipelines);
    if (!r) r = tb_buffer_create(&w->memory, sizeof(tb_gpu_params),
                                 VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                 TRANSFER_BOTH, 0, &w->params_buffer);
    if (!r) r = tb_buffer_create(&w->memory, TB_GRAPH_SWAP_SCRATCH_BYTES, TRANSFER_BOTH, 0,
                                 &w->params_swap);
    if (r) return r;
    tb_pipelines_bind(&w->pipelines, TB_BIND_PARAMS, w->params_buffer.buffer);
    int replaced = 0;
    r = tb_shapes_create_buffer(w, INITIAL_SHAPE_CAPACITY);
    if (!r) r = tb_narrowphase_init(&w->narrowphase, &w->kit, &replaced);
    if (replaced) w->buffer_generation++;
    if (!r) r = tb_body_store_init(&w->store, &w->memory, &w->pipelines, &w->transfer,
                                   def->initial_body_capacity);
    uint64_t pairs = def->initial_pair_capacity ? def->initial_pair_capacity
                                                : 4 * (uint64_t)(w->store.capacity ? w->store.capacity : 1);
    if (!r) r = tb_prims_init(&w->prims, &w->pipelines);
    /* The pair capacity is clamped to the device's limit. */
    if (!r) r = tb_sim_init(&w->sim, &w->memory, &w->pipelines, &w->prims, &w->transfer,
                            w->store.capacity, pairs, w->block_solver);
    if (!r) r = tb_joints_init(&w->joints, &w->memory, &w->transfer);
    if (!r) r = tb_solver_init(&w->solver, &w->pipelines);
    if (!r && w->block_solver) r = tb_block_init(&w->block, &w->pipelines);
    if (!r && !w->block_solver) r = tb_solver_prepare_soft_step(&w->solver);
    if (!r) r = tb_step_kernels_create(w);
    if (!r) r = tb_world_plugins_init(w);
    w->bp.kit = w->kit;
    w->split.kit = w->kit;
    if (!r) r = tb_broadphase_shared_create(&w->bp);
    if (!r) r = w->broadphase->create(&w->bp);
    tb_step_broadphase_io(w);
    if (!r) r = w->broadphase->reserve(&w->bp, w->store.capacity);
    /* The step is recorded by the first tb_world_step (run.c), which makes the pipelines
     * only a stepping world needs (narrowphase/contacts among them). */
    return r;
}

tb_result tb_world_build(const tb_world_def* def, tb_broadphase broadphase, tb_diag* early,
                         const tb_gpu_options* extra, tb_world** out)
{
    tb_world* w = calloc(1, sizeof *w);
    if (!w) return tb_fail(early, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    w->diag = *early;
    w->serial = next_world_serial();
    w->gravity = def->gravity;
    w->max_rotation_per_step = def->max_rotation_per_step;
    w->substeps = def->substeps;
    w->solver_iterations = def->solver_iterations;
    w->contact_margin = def->contact_margin;
    w->reuse_distance = TB_DEFAULT_REUSE_DISTANCE;
    w->reuse_angle = TB_DEFAULT_REUSE_ANGLE;
    w->restitution_threshold = def->restitution_threshold;
    w->contact_hertz = def->contact_hertz;
    w->contact_damping_ratio = def->contact_damping_ratio;
    w->contact_push_speed = def->contact_push_speed;
    w->broadphase_kind = broadphase;
    w->broadphase = tb_broadphase_ops_of(broadphase);
    w->colour_rounds = INITIAL_COLOUR_ROUNDS;
    w->block_lanes = 8;
    w->steps_per_submit = tb_world_steps_per_submit();
    /* TUMBLE_BLOCK_LANES=8, 16 or 32 holds the block solver's sweeps at that many lanes a
     * body instead of choosing (to measure them, and to run the wide sweeps on lavapipe). */
    const char* lanes = getenv("TUMBLE_BLOCK_LANES");
    if (lanes && (!strcmp(lanes, "8") || !strcmp(lanes, "16") || !strcmp(lanes, "32"))) {
        w->block_lanes = (uint32_t)atoi(lanes);
        w->block_lanes_fixed = 1;
    }
    /* TUMBLE_BLOCK_FUSED=0 or 1 records the block solver's sweeps as a dispatch a colour or
     * all in one workgroup whatever the world's size (the two give the same results). */
    const char* fused = getenv("TUMBLE_BLOCK_FUSED");
    w->block_fused_forced = fused && (!strcmp(fused, "0") || !strcmp(fused, "1")) ? atoi(fused) : -1;
    /* The block solver unless the environment asks for the soft step (TUMBLE_SOLVER=soft). */
    const char* solver = getenv("TUMBLE_SOLVER");
    w->block_solver = !(solver && strcmp(solver, "soft") == 0);
    w->block_settings = tb_block_default_settings();
    w->max_bodies = def->max_bodies ? def->max_bodies : DEFAULT_MAX_BODIES;
    w->max_shapes = def->max_shapes ? def->max_shapes : DEFAULT_MAX_SHAPES;
    tb_result r = create_gpu_objects(w, def, extra);
    if (r) {
        *early = w->diag;
        tb_world_free(w);
        return r;
    }
    *out = w;
    return TB_OK;
}

void tb_world_free(tb_world* w)
{
    if (!w) return;
    if (w->gpu.device) vkDeviceWaitIdle(w->gpu.device);
    if (w->gpu.device) {
        tb_graph_destroy(&w->graph);
        tb_events_destroy(w);
        tb_plugins_destroy(&w->plugins);
        tb_step_kernels_destroy(w);
        if (w->broadphase) w->broadphase->destroy(&w->bp);
        tb_broadphase_shared_destroy(&w->bp);
        tb_pair_split_destroy(&w->split);
        tb_solver_destroy(&w->solver);
        tb_block_destroy(&w->block);
        tb_joints_destroy(&w->joints);
        tb_sim_destroy(&w->sim);
        tb_prims_destroy(&w->prims);
        tb_body_store_destroy(&w->store);
        tb_buffer_destroy(&w->memory, &w->shape_buffer);
        for (uint32_t i = 0; i < w->shape_slots.used; i++)
            tb_buffer_destroy(&w->memory, &w->shapes[i].mesh_buffer);
        tb_narrowphase_destroy(&w->narrowphase);
        tb_pipeline_destroy(&w->pipelines, w->distance_query);
        tb_buffer_destroy(&w->memory, &w->params_buffer);
        tb_buffer_destroy(&w->memory, &w->params_swap);
        tb_transfer_destroy(&w->transfer);
        tb_pipelines_destroy(&w->pipelines);
        tb_memory_destroy(&w->memory);
    }
    tb_gpu_destroy(&w->gpu);
    tb_slots_free(&w->body_slots);
    tb_slots_free(&w->shape_slots);
    free(w->bodies);
    for (uint32_t i = 0; i < w->shape_slots.used; i++) tb_shape_release_hull(&w->shapes[i]);
    free(w->shapes);
    free(w->gpu_shapes);
    free(w);
}

tb_result tb_world_use_solver(tb_world* w, int block, uint32_t iterations)
{
    if (!block && w->joints.slots.live)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "the soft step does not solve "
                       "joints, and this world has %u: destroy them first",
                       w->joints.slots.live);
    tb_result r = TB_OK;
    if (block && !w->block.pipelines) r = tb_block_init(&w->block, &w->pipelines);
    if (!r && !block) r = tb_solver_prepare_soft_step(&w->solver);
    if (!r) r = tb_sim_set_block_lists(&w->sim, &w->transfer, block);
    if (r) return r;
    w->block_solver = block;
    if (iterations) w->block_settings.iterations = iterations;
    w->step_built = 0;
    w->buffer_generation++;
    return TB_OK;
}

tb_result tb_world_reserve_bodies(tb_world* w, uint32_t slots)
{
    int grew = 0;
    tb_result r = tb_body_store_reserve(&w->store, &w->transfer, slots, &grew);
    if (!r && grew) r = tb_sim_reserve_bodies(&w->sim, &w->transfer, w->store.capacity);
    if (grew) tb_step_broadphase_io(w);
    if (!r && grew) r = w->broadphase->reserve(&w->bp, w->store.capacity);
    if (grew) {
        w->step_built = 0;
        w->buffer_generation++;
    }
    return r;
}
