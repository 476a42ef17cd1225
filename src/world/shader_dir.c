/* Shader hot-reload for the world: the step records again when a pipeline was swapped (the
 * work is src/gpu/reload.c's). */
#include <stdlib.h>

#include "world/world.h"

tb_result tb_world_shader_dir(tb_world* w, const char* dir)
{
    uint32_t swapped = 0;
    tb_result r = tb_pipelines_set_shader_dir(&w->pipelines, dir, &swapped);
    if (swapped) w->step_built = 0;
    return r;
}

tb_result tb_world_shader_dir_from_env(tb_world* w)
{
    const char* dir = getenv("TUMBLE_SHADER_DIR");
    return dir && *dir ? tb_world_shader_dir(w, dir) : TB_OK;
}

void tb_world_reload_shaders(tb_world* w)
{
    if (tb_pipelines_reload(&w->pipelines)) w->step_built = 0;
}
