/* Loading a plugin: balls bounce on the ground while plugin_counter.so counts their
 * contacts.
 *
 *   ./plugin ./plugin_counter.so
 *
 * A plugin that cannot be loaded (no such file, a newer ABI, bad shaders) is refused with
 * a sentence and the world goes on without it. */
#include <stdio.h>

#include "tumble.h"

#define BALLS 8

int main(int argc, char** argv)
{
    const char* path = argc > 1 ? argv[1] : "./plugin_counter.so";
    tb_world_def wd = tb_default_world_def();
    tb_world* world;
    if (tb_world_create(&wd, &world) != TB_OK) {
        fprintf(stderr, "plugin: %s\n", tb_world_last_error(NULL));
        return 1;
    }
    tb_plugin_id plugin;
    tb_shape_def sd = tb_default_shape_def();
    sd.restitution = 0.6f;
    tb_shape_id ball, ground;
    tb_body_def gd = tb_default_body_def();
    tb_body_id ground_body, balls[BALLS];
    tb_body_def defs[BALLS];
    if (tb_world_load_plugin(world, path, &plugin) ||
        tb_shape_create_sphere(world, &sd, 0.25f, &ball) ||
        tb_shape_create_plane(world, &sd, (tb_vec3){ 0, 1, 0 }, 0, &ground))
        goto fail;
    gd.type = TB_BODY_STATIC;
    gd.shape = ground;
    for (int i = 0; i < BALLS; i++) {
        defs[i] = tb_default_body_def();
        defs[i].shape = ball;
        defs[i].position = (tb_vec3){ (float)i, 1.0f + 0.25f * (float)i, 0 };
    }
    if (tb_body_create(world, &gd, &ground_body) ||
        tb_body_create_many(world, defs, BALLS, balls) ||
        tb_world_step_n(world, 1.0f / 60, 180) ||
        tb_world_unload_plugin(world, plugin))   /* the plugin reports here */
        goto fail;
    tb_world_destroy(world);
    return 0;
fail:
    fprintf(stderr, "plugin: %s\n", tb_world_last_error(world));
    tb_world_destroy(world);
    return 1;
}
