/* A pile: 216 boxes dropped on the ground, read back every half second until they rest.
 *
 *   cc pile.c $(pkg-config --cflags --libs tumble) -lm -o pile && ./pile
 *
 * Bodies are created with one call and read back with one call: the API is built for
 * bulk, so a frame's transforms of a million bodies are one copy too. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tumble.h"

#define SIDE 6
#define COUNT (SIDE * SIDE * SIDE)

static int check(tb_world* world, tb_result r, const char* what)
{
    if (r != TB_OK) fprintf(stderr, "pile: %s: %s\n", what, tb_world_last_error(world));
    return r == TB_OK;
}

int main(void)
{
    tb_world_def wd = tb_default_world_def();
    tb_world* world;
    if (!check(NULL, tb_world_create(&wd, &world), "tb_world_create")) return 1;
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id ground, box;
    tb_body_def gd = tb_default_body_def();
    tb_body_id ground_body;
    int ok = check(world, tb_shape_create_plane(world, &sd, (tb_vec3){ 0, 1, 0 }, 0, &ground),
                   "plane") &&
             check(world, tb_shape_create_box(world, &sd, (tb_vec3){ 0.5f, 0.5f, 0.5f }, &box),
                   "box");
    gd.type = TB_BODY_STATIC;
    gd.shape = ground;
    ok = ok && check(world, tb_body_create(world, &gd, &ground_body), "ground");

    /* A grid of boxes 1.2 m apart, each layer a little turned, falling from 2 m up. */
    tb_body_def defs[COUNT];
    tb_body_id ids[COUNT];
    for (int i = 0; i < COUNT; i++) {
        int x = i % SIDE, z = (i / SIDE) % SIDE, y = i / (SIDE * SIDE);
        float turn = 0.1f * (float)y;
        defs[i] = tb_default_body_def();
        defs[i].shape = box;
        defs[i].position = (tb_vec3){ 1.2f * (float)(x - SIDE / 2), 2.0f + 1.2f * (float)y,
                                      1.2f * (float)(z - SIDE / 2) };
        defs[i].rotation = (tb_quat){ 0, sinf(turn / 2), 0, cosf(turn / 2) };
    }
    ok = ok && check(world, tb_body_create_many(world, defs, COUNT, ids), "tb_body_create_many");

    tb_vec3 positions[COUNT];
    tb_quat rotations[COUNT];
    for (int frame = 1; ok && frame <= 8; frame++) {
        ok = check(world, tb_world_step_n(world, 1.0f / 60, 30), "step") &&
             check(world, tb_world_read_transforms(world, ids, COUNT, positions, rotations),
                   "read");
        double top = 0, sum = 0;
        for (int i = 0; ok && i < COUNT; i++) {
            sum += positions[i].y;
            if (positions[i].y > top) top = positions[i].y;
        }
        tb_world_stats st;
        tb_world_get_stats(world, &st);
        if (ok) printf("t = %.1f s: mean height %.2f m, top %.2f m, %u contact points, "
                       "GPU %.2f ms/step\n", frame * 0.5, sum / COUNT, top, st.contact_count,
                       st.gpu_ms);
    }
    tb_world_destroy(world);
    return ok ? 0 : 1;
}
