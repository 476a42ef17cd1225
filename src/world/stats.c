/* What the world tells of itself: its device, and the stats of the last step. */
#include <stdio.h>
#include <string.h>

#include "world/world.h"

void tb_world_device(const tb_world* w, tb_device_info* out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", w->gpu.props.deviceName);
    snprintf(out->driver, sizeof out->driver, "%.*s", (int)sizeof out->driver - 1, w->gpu.driver);
    out->vendor_id = w->gpu.props.vendorID;
    out->device_id = w->gpu.props.deviceID;
    out->api_version = w->gpu.props.apiVersion;
    out->subgroup_size = w->gpu.subgroup_size;
    out->is_cpu = w->gpu.is_cpu;
}

void tb_world_stats_read(const tb_world* w, tb_world_stats* out)
{
    memset(out, 0, sizeof *out);
    out->body_count = w->body_slots.live;
    out->body_capacity = w->store.capacity;
    out->shape_count = w->shape_slots.live;
    out->steps = w->steps;
    out->submits = w->submits;
    out->records = w->graph.records;
    out->buffer_growths = w->store.growths;
    out->validation_messages = w->diag.validation_messages;
    out->gpu_ms = w->gpu_ms;
    const tb_gpu_counters* c = tb_sim_counters(&w->sim);
    out->pair_count = c->state.z;
    out->pair_capacity = w->sim.pair_capacity;
    out->contact_count = c->solver.w;
    out->colour_count = c->solver.x;
    out->batch_count = c->solver.z;
    out->colour_rounds = w->colour_rounds;
    out->steps_redone = w->steps_redone;
    out->broadphase = w->broadphase->name;
    out->buffer_growths += w->sim.growths;
    out->stage_count = w->graph.count;
    for (uint32_t i = 0; i < w->graph.count; i++) {
        out->stages[i].name = w->graph.stages[i].name;
        out->stages[i].ms = w->stage_ms[i];
    }
}
