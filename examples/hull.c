/* A convex hull: a rock from a cloud of points, dropped on the ground.
 *
 *   cc hull.c $(pkg-config --cflags --libs tumble) -lm -o hull && ./hull
 *
 * The library builds the hull (quickhull), merges coplanar faces, works out its volume,
 * centre of mass and principal axes, and simulates it in that principal frame: a body's
 * position is its centre of mass. Points inside the hull are fine; a flat or degenerate
 * cloud is refused with a sentence. */
#include <math.h>
#include <stdio.h>

#include "tumble.h"

int main(void)
{
    /* An irregular rock: a stretched octahedron with some points on and inside it. */
    const tb_vec3 cloud[] = {
        { 1.0f, 0.0f, 0.0f }, { -0.8f, 0.1f, 0.0f }, { 0.0f, 0.6f, 0.1f },
        { 0.1f, -0.5f, 0.0f }, { 0.0f, 0.0f, 0.7f }, { 0.0f, 0.1f, -0.9f },
        { 0.4f, 0.3f, 0.3f }, { -0.3f, -0.2f, 0.4f }, { 0.1f, 0.1f, 0.1f },
        { 0.5f, -0.2f, -0.4f }, { -0.4f, 0.3f, -0.3f },
    };
    tb_world_def wd = tb_default_world_def();
    tb_world* world;
    if (tb_world_create(&wd, &world) != TB_OK) {
        fprintf(stderr, "hull: %s\n", tb_world_last_error(NULL));
        return 1;
    }
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id rock, ground;
    tb_hull_info info;
    tb_body_def bd = tb_default_body_def(), gd = tb_default_body_def();
    tb_body_id body, ground_body;
    if (tb_shape_create_hull(world, &sd, cloud, sizeof cloud / sizeof cloud[0], &rock) ||
        tb_shape_get_hull_info(world, rock, &info) ||
        tb_shape_create_plane(world, &sd, (tb_vec3){ 0, 1, 0 }, 0, &ground))
        goto fail;
    printf("hull: %u vertices, %u faces, %u edges, volume %.3f m^3, centre of mass "
           "(%.3f, %.3f, %.3f)\n", info.vertex_count, info.face_count, info.edge_count,
           info.volume, info.center_of_mass.x, info.center_of_mass.y, info.center_of_mass.z);

    gd.type = TB_BODY_STATIC;
    gd.shape = ground;
    bd.shape = rock;
    bd.position = (tb_vec3){ 0, 2, 0 };
    bd.angular_velocity = (tb_vec3){ 1, 2, 0.5f };
    if (tb_body_create(world, &gd, &ground_body) || tb_body_create(world, &bd, &body))
        goto fail;
    for (int second = 1; second <= 3; second++) {
        tb_vec3 p, v, w;
        tb_quat q;
        if (tb_world_step_n(world, 1.0f / 60, 60) ||
            tb_world_read_transforms(world, &body, 1, &p, &q) ||
            tb_body_get_velocity(world, body, &v, &w))
            goto fail;
        printf("t = %d s: centre of mass at y = %.3f m, speed %.3f m/s\n", second, p.y,
               sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z));
    }
    tb_world_destroy(world);
    return 0;
fail:
    fprintf(stderr, "hull: %s\n", tb_world_last_error(world));
    tb_world_destroy(world);
    return 1;
}
