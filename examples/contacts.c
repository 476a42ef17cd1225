/* Contacts: a box resting on the ground, its contact points read back.
 *
 *   cc contacts.c $(pkg-config --cflags --libs tumble) -o contacts && ./contacts
 *
 * Each step's contact points come back in one call, grouped by pair, with the normal from
 * body a to body b and the impulses the solver applied: at rest the normal impulses of a
 * step add up to the box's weight times the step. */
#include <stdio.h>

#include "tumble.h"

#define MAX_CONTACTS 16

int main(void)
{
    const float dt = 1.0f / 60;
    tb_world_def wd = tb_default_world_def();
    tb_world* world;
    if (tb_world_create(&wd, &world) != TB_OK) {
        fprintf(stderr, "contacts: %s\n", tb_world_last_error(NULL));
        return 1;
    }
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id ground, box;
    tb_body_def gd = tb_default_body_def(), bd = tb_default_body_def();
    tb_body_id ground_body, body;
    tb_contact contacts[MAX_CONTACTS];
    uint32_t count = 0;
    float mass;
    tb_vec3 inertia;
    gd.type = TB_BODY_STATIC;
    if (tb_shape_create_plane(world, &sd, (tb_vec3){ 0, 1, 0 }, 0, &ground) ||
        tb_shape_create_box(world, &sd, (tb_vec3){ 0.5f, 0.25f, 0.5f }, &box))
        goto fail;
    gd.shape = ground;
    bd.shape = box;
    bd.position = (tb_vec3){ 0, 0.25f, 0 };   /* touching the ground */
    if (tb_body_create(world, &gd, &ground_body) || tb_body_create(world, &bd, &body) ||
        tb_body_get_mass(world, body, &mass, &inertia) ||
        tb_world_step_n(world, dt, 60) ||
        tb_world_read_contacts(world, contacts, MAX_CONTACTS, &count))
        goto fail;
    float total = 0;
    for (uint32_t i = 0; i < count && i < MAX_CONTACTS; i++) {
        const tb_contact* c = &contacts[i];
        printf("point (%.2f, %.2f, %.2f) normal (%.1f, %.1f, %.1f) separation %.4f m "
               "impulse %.3f N s\n", c->point.x, c->point.y, c->point.z, c->normal.x,
               c->normal.y, c->normal.z, c->separation, c->normal_impulse);
        total += c->normal_impulse;
    }
    printf("%u points; their impulses %.3f N s, the weight over a step %.3f N s\n", count,
           total, mass * 9.81f * dt);
    tb_world_destroy(world);
    return count == 4 ? 0 : 1;
fail:
    fprintf(stderr, "contacts: %s\n", tb_world_last_error(world));
    tb_world_destroy(world);
    return 1;
}
