/* Plugins through the API (abi/tumble_plugin.h); loading and checking them is
 * src/plugin/'s work. */
#include "api/api.h"
#include "world/world.h"

tb_result tb_world_load_plugin(tb_world* w, const char* path, tb_plugin_id* out)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_world_load_plugin");
    if (!path || !out) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "path or out is NULL");
    return tb_world_plugin_load(w, path, out);
}

tb_result tb_world_unload_plugin(tb_world* w, tb_plugin_id id)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_world_unload_plugin");
    return tb_world_plugin_unload(w, id);
}

tb_result tb_world_set_plugin_param(tb_world* w, tb_plugin_id id, uint32_t offset,
                                    const void* data, uint32_t size)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    return tb_plugins_set_param(&w->plugins, id, offset, data, size);
}
