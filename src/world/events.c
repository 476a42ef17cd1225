/* Contact events for plugins' host callbacks: the pairs whose contact began or ended in a
 * step. The GPU finds them (narrowphase/events over this step's and last step's manifolds,
 * recorded only while a loaded plugin wants them), so what comes back is proportional to
 * the events, not to the contacts. After each submission the events of its completed steps
 * go to the plugins, one callback per step that has any, each sorted by kind and then by
 * the bodies' slots. */
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define FIRST_EVENT_CAPACITY 1024u
#define USAGE (VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT)

/* The passes hold the buffer's address: the world records the step again after this. */
tb_result tb_events_init(tb_world* w)
{
    return tb_pipeline_create(&w->pipelines, "narrowphase/events", TB_WORKGROUP_SIZE,
                              &w->events.find);
}

void tb_events_destroy(tb_world* w)
{
    tb_events* e = &w->events;
    tb_pipeline_destroy(&w->pipelines, e->find);
    tb_buffer_destroy(&w->memory, &e->buffer);
    free(e->sorted);
    free(e->begin.events);
    free(e->end.events);
    memset(e, 0, sizeof *e);
}

static tb_result replace_event_buffer(tb_world* w, uint32_t capacity)
{
    tb_events* e = &w->events;
    tb_buffer fresh;
    tb_result r = tb_buffer_create(&w->memory, (VkDeviceSize)capacity * sizeof(tb_gpu_contact_event),
                                   USAGE, 0, &fresh);
    if (r) return r;
    tb_buffer_destroy(&w->memory, &e->buffer);
    e->buffer = fresh;
    e->capacity = capacity;
    w->step_built = 0;   /* the passes hold its address */
    return TB_OK;
}

tb_result tb_events_grow(tb_world* w, uint32_t need)
{
    uint64_t want = (uint64_t)need + need / 4 + 64;
    if (want < 2ull * w->events.capacity) want = 2ull * w->events.capacity;
    if (want > UINT32_MAX / sizeof(tb_gpu_contact_event)) want = UINT32_MAX / sizeof(tb_gpu_contact_event);
    return replace_event_buffer(w, (uint32_t)want);
}

static tb_pass events_pass(tb_world* w, uint32_t kind)
{
    const tb_events* e = &w->events;
    uint64_t events = e->buffer.address;
    uint64_t marks = w->sim.pair[TB_SIM_EVENT_MARKS].address;
    tb_gpu_events_push push = {
        { kind, e->capacity, 0, 0 },
        { (uint32_t)events, (uint32_t)(events >> 32), (uint32_t)marks, (uint32_t)(marks >> 32) },
    };
    tb_pass pass = tb_pass_with_args(e->find, kind == TB_EVENTS_BEGIN ? TB_DISPATCH_INDIRECT
                                                                      : TB_DISPATCH_FIXED,
                                     w->sim.counters.buffer, TB_COUNTERS_PAIR_DISPATCH_OFFSET,
                                     0, 0, 0);
    if (kind == TB_EVENTS_END) pass.groups[0] = TB_EVENTS_END_GROUPS;
    pass.push_size = sizeof push;
    memcpy(pass.push, &push, sizeof push);
    return pass;
}

tb_result tb_events_record(tb_world* w, tb_pass_list* list)
{
    if (!tb_plugins_want_events(&w->plugins)) return TB_OK;
    tb_result r = w->events.buffer.buffer ? TB_OK
                  : replace_event_buffer(w, FIRST_EVENT_CAPACITY);
    tb_pass begin = events_pass(w, TB_EVENTS_BEGIN), end = events_pass(w, TB_EVENTS_END);
    if (!r) r = tb_pass_list_add(list, &w->diag, &begin);
    if (!r) r = tb_pass_list_add(list, &w->diag, &end);
    if (!r) r = tb_graph_append_passes(&w->graph, "plugin/contact_events", list);
    return r;
}

/* ---- delivery ---------------------------------------------------------------------------- */

static int by_step_kind_bodies(const void* x, const void* y)
{
    const tb_gpu_contact_event *e = x, *f = y;
    const uint32_t a[4] = { e->info.w, e->info.x, e->info.y, e->info.z };
    const uint32_t b[4] = { f->info.w, f->info.x, f->info.y, f->info.z };
    for (int i = 0; i < 4; i++)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

static tb_result read_events(tb_world* w, uint32_t count)
{
    tb_events* e = &w->events;
    if (count > e->sorted_capacity) {
        tb_gpu_contact_event* grown = realloc(e->sorted, count * sizeof *grown);
        if (!grown) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        e->sorted = grown;
        e->sorted_capacity = count;
    }
    VkDeviceSize bytes = (VkDeviceSize)count * sizeof(tb_gpu_contact_event);
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, bytes + 64);
    if (r) return r;
    const void* landing = tb_transfer_download(t, e->buffer.buffer, 0, bytes);
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &t->cb, 1);
    if (r) return r;
    memcpy(e->sorted, landing, bytes);
    qsort(e->sorted, count, sizeof *e->sorted, by_step_kind_bodies);
    return TB_OK;
}

static tb_result append(tb_world* w, tb_event_list* list, const tb_gpu_contact_event* e)
{
    if (list->count == list->capacity) {
        uint32_t cap = list->capacity ? 2 * list->capacity : 64;
        tb_contact_event* grown = realloc(list->events, cap * sizeof *grown);
        if (!grown) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        list->events = grown;
        list->capacity = cap;
    }
    list->events[list->count++] = (tb_contact_event){
        .a = tb_body_id_of_slot(w, e->info.y), .b = tb_body_id_of_slot(w, e->info.z),
        .point = { e->point.x, e->point.y, e->point.z },
        .normal = { e->normal.x, e->normal.y, e->normal.z },
        .normal_impulse = e->normal.w,
        .friction_impulse = { e->friction.x, e->friction.y, e->friction.z },
        .point_count = (uint32_t)e->point.w,
    };
    return TB_OK;
}

/* The step numbers the callbacks see are tb_world_stats.steps after that step: the GPU's
 * count of completed steps (info.w counts those before it) plus one. */
tb_result tb_events_deliver(tb_world* w, const tb_gpu_counters* counters)
{
    tb_events* e = &w->events;
    uint32_t count = counters->events.y;
    if (!count || !tb_plugins_want_events(&w->plugins) || !e->buffer.buffer) return TB_OK;
    if (count > e->capacity) count = e->capacity;
    tb_result r = read_events(w, count);
    for (uint32_t i = 0; i < count && !r;) {
        uint32_t step = e->sorted[i].info.w;
        e->begin.count = e->end.count = 0;
        for (; i < count && e->sorted[i].info.w == step && !r; i++)
            r = append(w, e->sorted[i].info.x == TB_EVENT_BEGIN ? &e->begin : &e->end,
                       &e->sorted[i]);
        tb_contact_events events = { (uint64_t)step + 1, e->begin.events, e->begin.count,
                                     e->end.events, e->end.count };
        if (r) break;
        w->in_callbacks = 1;
        tb_plugins_on_contacts(&w->plugins, &events);
        w->in_callbacks = 0;
    }
    return r;
}
