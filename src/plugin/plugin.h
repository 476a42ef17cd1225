/* Plugins loaded into a world (abi/tumble_plugin.h): their stages, parameter blocks and the
 * contact events their callbacks get. */
#ifndef TB_PLUGINS_H
#define TB_PLUGINS_H

#include "base/diag.h"
#include "gpu/graph.h"
#include "gpu/memory.h"
#include "layout.h"
#include "tumble_plugin.h"

/// Plugin stages a world runs in all (with the step's own, within TB_MAX_STAGES).
#define TB_MAX_PLUGIN_STAGES 16u

typedef struct tb_plugin_stage_record {
    char name[8 + 2 * (TB_PLUGIN_MAX_NAME + 1)];   ///< "plugin/<plugin>/<stage>"
    tb_plugin_point point;
    tb_plugin_dispatch dispatch;
    uint32_t groups;
    VkPipeline pipeline;
} tb_plugin_stage_record;

typedef struct tb_plugin_record {
    uint16_t generation;
    uint8_t alive;
    void* handle;                          ///< dlopen's
    tb_plugin desc;                        ///< the plugin's, fields it lacks zeroed
    uint32_t stage_count;
    tb_plugin_stage_record stages[TB_PLUGIN_MAX_STAGES];
    unsigned char params[TB_PLUGIN_MAX_PARAM_BYTES];
} tb_plugin_record;

/// Contact events of one step, as the callbacks get them.
typedef struct tb_event_list {
    tb_contact_event* events;
    uint32_t count, capacity;
} tb_event_list;

typedef struct tb_plugins {
    tb_plugin_record slots[TB_MAX_PLUGINS];
    uint32_t stage_total;
    tb_buffer params_buffer;               ///< every slot's block, bound at TB_BIND_PLUGIN_PARAMS
    int params_dirty;
    VkPipeline mark;                       ///< step/plugin_mark
    VkPipeline events;                     ///< narrowphase/events
    tb_buffer event_buffer;                ///< tb_gpu_contact_event[event_capacity]
    uint32_t event_capacity;
    tb_gpu_contact_event* sorted;          ///< a submission's events, sorted
    uint32_t sorted_capacity;
    tb_event_list begin, end;              ///< one step's, for the callbacks
} tb_plugins;

struct tb_world;

tb_result tb_plugins_init(struct tb_world* w);
/// Unload every plugin and free everything.
void tb_plugins_destroy(struct tb_world* w);

/// Append the stages of `point` to the step graph, each a stage of its own.
tb_result tb_plugins_record(struct tb_world* w, tb_plugin_point point, tb_pass_list* list);
/// Upload the parameter blocks if they changed (into the transfer recorded before a step).
void tb_plugins_record_upload(struct tb_world* w, VkCommandBuffer cb);

/* contact_events.c */
/// Does a loaded plugin want contact events?
int tb_plugins_want_events(const struct tb_world* w);
/// When one does: the stage that finds the step's events (narrowphase/events).
tb_result tb_plugins_record_events(struct tb_world* w, tb_pass_list* list);
/// After a submission: the events of its completed steps to the plugins, step by step.
tb_result tb_plugins_deliver_events(struct tb_world* w, const tb_gpu_counters* counters);
/// A step found more events than the buffer holds (TB_ABORT_EVENTS): make room for `need`.
tb_result tb_plugins_grow_events(struct tb_world* w, uint32_t need);

/// Check a stage's SPIR-V (`what` names it in the error).
tb_result tb_plugin_check_spirv(tb_diag* diag, const char* what, const uint32_t* code, size_t size);

#endif
