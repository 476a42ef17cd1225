/* Plugins loaded into a world (abi/tumble_plugin.h): loading and checking them, their
 * stages in the step, their parameter blocks and the contact events their callbacks get.
 *
 * Reads, at the plugin points of the step (pre-step, post-broadphase, post-solve,
 * post-step): whatever the plugins' stages read of the body arrays, pairs and step
 * parameters (abi/tumble_plugin.glsl); writes what they write and the parameter blocks
 * (binding TB_BIND_PLUGIN_PARAMS). The world finds each step's contact events and hands
 * them to the plugins that want them (src/world/events.c). The plugins see the world only
 * through tb_plugin_host and the buffers of tb_plugins_io.
 */
#ifndef TB_PLUGIN_PLUGIN_H
#define TB_PLUGIN_PLUGIN_H

#include "gpu/gpu.h"
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

/// What plugins see of the world that loads them.
typedef struct tb_plugin_host {
    tb_gpu_kit kit;
    tb_world* world;             ///< handed to the callbacks, never looked into
    uint16_t serial;             ///< the world's, in plugin ids
} tb_plugin_host;

/// The step's buffers the plugins' passes use (they move when they grow).
typedef struct tb_plugins_io {
    VkBuffer counters;           ///< bound at TB_BIND_COUNTERS (per-pair dispatch)
} tb_plugins_io;

typedef struct tb_plugins {
    tb_plugin_host host;
    tb_plugin_record slots[TB_MAX_PLUGINS];
    uint32_t stage_total;
    tb_buffer params_buffer;               ///< every slot's block, bound at TB_BIND_PLUGIN_PARAMS
    int params_dirty;
    VkPipeline mark;                       ///< step/plugin_mark
} tb_plugins;

/* stages.c */
tb_result tb_plugins_init(tb_plugins* p, const tb_plugin_host* host);
/// Unload every plugin and free everything.
void tb_plugins_destroy(tb_plugins* p);

/// Append the stages of `point` to the step graph, each a stage of its own.
tb_result tb_plugins_record(tb_plugins* p, tb_plugin_point point, tb_pass_list* list,
                            const tb_plugins_io* io);
/// Upload the parameter blocks if they changed (into the transfer recorded before a step).
void tb_plugins_record_upload(tb_plugins* p, VkCommandBuffer cb);

/* loader.c: what the API's plugin calls do once their arguments are checked. A refused
 * plugin leaves everything as it was. The step must be recorded again after a load or an
 * unload. */
tb_result tb_plugins_load(tb_plugins* p, const char* path, tb_plugin_id* out);
tb_result tb_plugins_unload(tb_plugins* p, tb_plugin_id id);
tb_result tb_plugins_set_param(tb_plugins* p, tb_plugin_id id, uint32_t offset,
                               const void* data, uint32_t size);

/// Does a loaded plugin want contact events?
int tb_plugins_want_events(const tb_plugins* p);
/// One step's contact events to every plugin that wants them, in load order.
void tb_plugins_on_contacts(const tb_plugins* p, const tb_contact_events* events);

#endif
