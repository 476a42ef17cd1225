/* The world's plugins: what they see of it, and the step recorded again when their stages
 * come or go. */
#include "world/world.h"

tb_result tb_world_plugins_init(tb_world* w)
{
    tb_plugin_host host = { w->kit, w, w->serial };
    tb_result r = tb_plugins_init(&w->plugins, &host);
    return r ? r : tb_events_init(w);
}

tb_result tb_world_plugin_load(tb_world* w, const char* path, tb_plugin_id* out)
{
    tb_result r = tb_plugins_load(&w->plugins, path, out);
    if (!r) w->step_built = 0;
    return r;
}

tb_result tb_world_plugin_unload(tb_world* w, tb_plugin_id id)
{
    tb_result r = tb_plugins_unload(&w->plugins, id);
    if (!r) w->step_built = 0;
    return r;
}
