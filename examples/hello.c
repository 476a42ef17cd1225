/* Hello, Tumble: one ball falls for a second.
 *
 *   cc hello.c $(pkg-config --cflags --libs tumble) -o hello && ./hello
 *
 * Every call returns a tb_result; tb_world_last_error says what went wrong in a sentence. */
#include <stdio.h>

#include "tumble.h"

int main(void)
{
    tb_world_def wd = tb_default_world_def();      /* gravity (0, -9.81, 0), 6 substeps */
    tb_world* world;
    if (tb_world_create(&wd, &world) != TB_OK) {   /* picks the best GPU, else lavapipe */
        fprintf(stderr, "hello: %s\n", tb_world_last_error(NULL));
        return 1;
    }
    tb_device_info device;
    tb_world_device_info(world, &device);
    printf("Tumble %u.%u.%u on %s\n", tb_version() >> 22, (tb_version() >> 12) & 0x3ff,
           tb_version() & 0xfff, device.name);

    tb_shape_def sd = tb_default_shape_def();      /* density 1000 kg/m^3, friction 0.6 */
    tb_shape_id ball;
    tb_body_def bd = tb_default_body_def();        /* dynamic, at the origin, not turned */
    tb_body_id body;
    if (tb_shape_create_sphere(world, &sd, 0.5f, &ball) != TB_OK) goto fail;
    bd.shape = ball;
    bd.position = (tb_vec3){ 0, 10, 0 };
    if (tb_body_create(world, &bd, &body) != TB_OK) goto fail;

    if (tb_world_step_n(world, 1.0f / 60, 60) != TB_OK) goto fail;   /* one submission */
    tb_vec3 p;
    tb_quat q;
    if (tb_world_read_transforms(world, &body, 1, &p, &q) != TB_OK) goto fail;
    printf("after 1 s the ball is at y = %.3f m (free fall: %.3f m)\n", p.y,
           10.0 - 0.5 * 9.81);
    tb_world_destroy(world);
    return 0;
fail:
    fprintf(stderr, "hello: %s\n", tb_world_last_error(world));
    tb_world_destroy(world);
    return 1;
}
