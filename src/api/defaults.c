/* Every default in one place. A def that did not come from here lacks the cookie. */
#include <math.h>

#include "world/world.h"

tb_world_def tb_default_world_def(void)
{
    tb_world_def def = { 0 };
    def.gravity = (tb_vec3){ 0.0f, -9.81f, 0.0f };
    def.initial_body_capacity = 1024;
    def.max_bodies = 0;                          /* 0: 2^24 */
    def.max_shapes = 0;                          /* 0: 2^20 */
    def.max_rotation_per_step = 0.25f * 3.14159265358979f;
    def.substeps = 6;
    def.solver_iterations = 1;
    def.contact_margin = 0.02f;
    def.restitution_threshold = 0.5f;
    def.contact_hertz = 60.0f;
    def.contact_damping_ratio = 10.0f;
    def.contact_push_speed = 1.0f;
    def.internal_cookie = TB_DEF_COOKIE;
    return def;
}

tb_shape_def tb_default_shape_def(void)
{
    tb_shape_def def = { 0 };
    def.density = 1000.0f;
    def.friction = 0.6f;
    def.restitution = 0.0f;
    def.internal_cookie = TB_DEF_COOKIE;
    return def;
}

tb_body_def tb_default_body_def(void)
{
    tb_body_def def = { 0 };
    def.type = TB_BODY_DYNAMIC;
    def.rotation = (tb_quat){ 0.0f, 0.0f, 0.0f, 1.0f };
    def.gravity_scale = 1.0f;
    def.internal_cookie = TB_DEF_COOKIE;
    return def;
}
