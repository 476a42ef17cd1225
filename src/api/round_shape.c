/* Capsules, cylinders and cones through the API: their sizes checked, exact volume and
 * principal inertia per unit mass, and the GPU shape (params x radius, y half height; the
 * axis is the body's y axis and the body origin the centre of mass). */
#include <math.h>

#include "api/api.h"
#include "base/checks.h"
#include "world/world.h"

#define PI 3.14159265358979323846
/* The largest radius or half height taken: squares and volumes stay far inside float. */
#define ROUND_MAX_SIZE 1.0e6f

static tb_result check_size(tb_world* w, const char* what, float radius, float half_height,
                            int flat_allowed)
{
    int ok = isfinite(radius) && isfinite(half_height) && radius > 0 &&
             radius <= ROUND_MAX_SIZE && half_height <= ROUND_MAX_SIZE &&
             (flat_allowed ? half_height >= 0 : half_height > 0);
    if (ok) return TB_OK;
    return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "%s needs a finite radius in (0, 1e6] "
                   "and a finite half height in %s, not radius %g and half height %g", what,
                   flat_allowed ? "[0, 1e6]" : "(0, 1e6]", (double)radius, (double)half_height);
}

static tb_result add_round(tb_world* w, const tb_shape_def* def, tb_shape_type type,
                           float radius, float half_height, double volume, tb_vec3 unit_inertia,
                           tb_vec3 box_center, tb_vec3 box_half, tb_shape_id* out)
{
    tb_shape_record rec = { .type = type, .material = *def, .volume = (float)volume,
                            .unit_inertia = unit_inertia };
    tb_gpu_shape gpu = tb_api_gpu_shape((uint32_t)type, box_half,
                                        (tb_gpu_vec4){ radius, half_height, 0, 0 });
    gpu.aabb_center = (tb_gpu_vec4){ box_center.x, box_center.y, box_center.z, 0 };
    return tb_shapes_add(w, &rec, &gpu, out);
}

/* A capsule is a cylinder of length 2h and two half balls whose centres of mass lie 3r/8
 * beyond the cylinder's ends; the balls' moment about a transverse axis through the centre
 * is theirs about their own centres plus the parallel-axis shift. */
tb_result tb_shape_create_capsule(tb_world* w, const tb_shape_def* def, float radius,
                                  float half_height, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (!r) r = check_size(w, "capsule", radius, half_height, 1);
    if (r) return r;
    double a = radius, h = half_height;
    double cylinder = PI * a * a * 2 * h, ball = 4.0 / 3.0 * PI * a * a * a;
    double volume = cylinder + ball;
    double axial = (cylinder * a * a / 2 + ball * 2 * a * a / 5) / volume;
    double across = (cylinder * (a * a / 4 + h * h / 3) +
                     ball * (2 * a * a / 5 + h * h + 3 * h * a / 4)) / volume;
    tb_vec3 inertia = { (float)across, (float)axial, (float)across };
    return add_round(w, def, TB_SHAPE_CAPSULE, radius, half_height, volume, inertia,
                     (tb_vec3){ 0, 0, 0 }, (tb_vec3){ radius, half_height + radius, radius }, out);
}

tb_result tb_shape_create_cylinder(tb_world* w, const tb_shape_def* def, float radius,
                                   float half_height, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (!r) r = check_size(w, "cylinder", radius, half_height, 0);
    if (r) return r;
    double a = radius, h = half_height;
    tb_vec3 inertia = { (float)(a * a / 4 + h * h / 3), (float)(a * a / 2),
                        (float)(a * a / 4 + h * h / 3) };
    return add_round(w, def, TB_SHAPE_CYLINDER, radius, half_height, PI * a * a * 2 * h, inertia,
                     (tb_vec3){ 0, 0, 0 }, (tb_vec3){ radius, half_height, radius }, out);
}

/* A cone of height H = 2h: its centre of mass lies H/4 above the base. */
tb_result tb_shape_create_cone(tb_world* w, const tb_shape_def* def, float radius,
                               float half_height, tb_shape_id* out)
{
    tb_result r = tb_api_check_shape_def(w, def, out);
    if (!r) r = check_size(w, "cone", radius, half_height, 0);
    if (r) return r;
    double a = radius, height = 2.0 * half_height;
    double across = 3.0 / 20.0 * a * a + 3.0 / 80.0 * height * height;
    tb_vec3 inertia = { (float)across, (float)(3.0 / 10.0 * a * a), (float)across };
    return add_round(w, def, TB_SHAPE_CONE, radius, half_height, PI * a * a * height / 3,
                     inertia, (tb_vec3){ 0, half_height / 2, 0 },
                     (tb_vec3){ radius, half_height, radius }, out);
}

tb_result tb_shape_get_round_size(const tb_world* cw, tb_shape_id id, float* radius,
                                  float* half_height)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    tb_shape_record* s = tb_shape_lookup(w, id, &slot, &r);
    if (!s) return r;
    if (s->type != TB_SHAPE_CAPSULE && s->type != TB_SHAPE_CYLINDER && s->type != TB_SHAPE_CONE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "shape {%u, %u, %u} is not a "
                       "capsule, cylinder or cone", id.index1, id.world, id.generation);
    if (!radius || !half_height)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "radius or half_height is NULL");
    *radius = w->gpu_shapes[slot].params.x;
    *half_height = w->gpu_shapes[slot].params.y;
    return TB_OK;
}
