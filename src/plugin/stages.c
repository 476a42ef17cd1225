/* Plugin stages in the step graph, the parameter blocks they read, and the callbacks. */
#include <string.h>

#include "plugin/plugin.h"

#define PARAMS_BYTES (TB_MAX_PLUGINS * TB_PLUGIN_PARAM_VEC4S * 16)

tb_result tb_plugins_init(tb_plugins* p, const tb_plugin_host* host)
{
    p->host = *host;
    tb_result r = tb_buffer_create(p->host.kit.memory, PARAMS_BYTES,
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, &p->params_buffer);
    if (r) return r;
    tb_pipelines_bind(p->host.kit.pipelines, TB_BIND_PLUGIN_PARAMS, p->params_buffer.buffer);
    p->params_dirty = 1;
    return tb_pipeline_create(p->host.kit.pipelines, "step/plugin_mark", 1, &p->mark);
}

void tb_plugins_destroy(tb_plugins* p)
{
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++)
        if (p->slots[i].alive) tb_plugins_unload(p, (tb_plugin_id){ i + 1, p->host.serial,
                                                                        p->slots[i].generation });
    tb_pipeline_destroy(p->host.kit.pipelines, p->mark);
    tb_buffer_destroy(p->host.kit.memory, &p->params_buffer);
    memset(p, 0, sizeof *p);
}

void tb_plugins_record_upload(tb_plugins* p, VkCommandBuffer cb)
{
    if (!p->params_dirty) return;
    unsigned char blocks[PARAMS_BYTES];
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++)
        memcpy(blocks + i * TB_PLUGIN_MAX_PARAM_BYTES, p->slots[i].params, TB_PLUGIN_MAX_PARAM_BYTES);
    vkCmdUpdateBuffer(cb, p->params_buffer.buffer, 0, PARAMS_BYTES, blocks);
    p->params_dirty = 0;
}

static tb_pass stage_pass(VkBuffer counters, uint32_t slot, uint32_t index,
                          const tb_plugin_stage_record* s)
{
    tb_dispatch_rule rule = s->dispatch == TB_PLUGIN_PER_BODY ? TB_DISPATCH_PER_BODY
                          : s->dispatch == TB_PLUGIN_PER_PAIR ? TB_DISPATCH_INDIRECT
                                                              : TB_DISPATCH_FIXED;
    tb_pass pass = tb_pass_with_args(s->pipeline, rule, counters,
                                     TB_COUNTERS_PAIR_DISPATCH_OFFSET,
                                     slot * TB_PLUGIN_PARAM_VEC4S, (uint32_t)s->point, index);
    if (rule == TB_DISPATCH_FIXED) pass.groups[0] = s->groups;
    return pass;
}

/* Each stage of `point` in load order; after the last, at the points a step may be
 * abandoned after (and run again), the note that they ran. */
tb_result tb_plugins_record(tb_plugins* p, tb_plugin_point point, tb_pass_list* list,
                            const tb_plugins_io* io)
{
    const char* last = NULL;
    tb_result r = TB_OK;
    for (uint32_t slot = 0; slot < TB_MAX_PLUGINS && !r; slot++) {
        const tb_plugin_record* plugin = &p->slots[slot];
        for (uint32_t i = 0; plugin->alive && i < plugin->stage_count && !r; i++) {
            const tb_plugin_stage_record* s = &plugin->stages[i];
            if (s->point != point) continue;
            if (last) r = tb_graph_append_passes(p->host.kit.graph, last, list);
            tb_pass pass = stage_pass(io->counters, slot, i, s);
            if (!r) r = tb_pass_list_add(list, p->host.kit.diag, &pass);
            last = s->name;
        }
    }
    if (!r && last && (point == TB_PLUGIN_PRE_STEP || point == TB_PLUGIN_POST_BROADPHASE)) {
        tb_pass mark = tb_pass_with_args(p->mark, TB_DISPATCH_FIXED, VK_NULL_HANDLE, 0,
                                         point == TB_PLUGIN_PRE_STEP ? 0 : 1, 0, 0);
        r = tb_pass_list_add(list, p->host.kit.diag, &mark);
    }
    if (!r && last) r = tb_graph_append_passes(p->host.kit.graph, last, list);
    return r;
}

int tb_plugins_want_events(const tb_plugins* p)
{
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++)
        if (p->slots[i].alive && p->slots[i].desc.on_contacts) return 1;
    return 0;
}

void tb_plugins_on_contacts(const tb_plugins* p, const tb_contact_events* events)
{
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++) {
        const tb_plugin_record* plugin = &p->slots[i];
        if (plugin->alive && plugin->desc.on_contacts)
            plugin->desc.on_contacts(p->host.world, plugin->desc.user, events);
    }
}
