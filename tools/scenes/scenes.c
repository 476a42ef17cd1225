/* Scene registry and the scenes themselves (see scenes.h).
 *
 * Each scene is one row of `scenes[]` below: adding a scene means writing its build /
 * check / destroy functions and adding one line to the table.
 */
#include "scenes.h"
#include "instance.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

scene_instance* instance_alloc(uint32_t count)
{
    scene_instance* inst = calloc(1, sizeof *inst);
    if (!inst) return NULL;
    size_t n = count ? count : 1; /* malloc(0) may return NULL */
    inst->count = count;
    inst->ids = malloc(n * sizeof *inst->ids);
    inst->x0 = malloc(n * sizeof *inst->x0);
    inst->v0 = malloc(n * sizeof *inst->v0);
    if (!inst->ids || !inst->x0 || !inst->v0) {
        free(inst->ids); free(inst->x0); free(inst->v0); free(inst);
        return NULL;
    }
    return inst;
}

void instance_free(scene_instance* inst)
{
    if (!inst) return;
    free(inst->ids);
    free(inst->x0);
    free(inst->v0);
    free(inst);
}

/* ---- deterministic jitter: xorshift32, so every run of a seed builds the same scene ---- */

uint32_t scene_rng_next(uint32_t* state)
{
    uint32_t x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    return x;
}

/* Uniform in [-1, 1). */
float scene_rng_signed(uint32_t* state)
{
    return (float)((double)scene_rng_next(state) / 2147483648.0 - 1.0);
}

uint32_t scene_rng_seed(uint32_t seed)
{
    /* xorshift has a fixed point at 0; scramble so nearby seeds diverge at once. */
    uint32_t s = seed * 2654435761u + 0x9e3779b9u;
    return s ? s : 1u;
}

static tb_vec3 rng_vec3(uint32_t* state, float scale)
{
    tb_vec3 v;
    v.x = scale * scene_rng_signed(state);
    v.y = scale * scene_rng_signed(state);
    v.z = scale * scene_rng_signed(state);
    return v;
}

/* ---- freefall: bodies in free flight, no ground, compared with the closed form ---- */

#define FREEFALL_SPACING 2.0f      /* m between grid cells */
/* Jitter and drift are kept small so no two bodies (box half diagonal 0.71 m) can meet
 * within a few hundred steps: the scene measures integration alone, not contacts. */
#define FREEFALL_JITTER 0.05f      /* m */
#define FREEFALL_LIN_SPEED 0.05f   /* m/s per axis */
#define FREEFALL_ANG_SPEED 3.0f    /* rad/s per axis */

static uint32_t grid_side(uint32_t n)
{
    uint32_t side = (uint32_t)ceil(cbrt((double)n));
    while ((uint64_t)side * side * side < n) side++; /* cbrt rounding */
    return side ? side : 1;
}

/* Cell i of a side^3 grid centred on the origin in x and z, bottom layer 10 m up. */
static tb_vec3 grid_position(uint32_t i, uint32_t side)
{
    float half = 0.5f * (float)(side - 1) * FREEFALL_SPACING;
    tb_vec3 p;
    p.x = (float)(i % side) * FREEFALL_SPACING - half;
    p.z = (float)((i / side) % side) * FREEFALL_SPACING - half;
    p.y = (float)(i / (side * side)) * FREEFALL_SPACING + 10.0f;
    return p;
}

static void freefall_fill_defs(tb_body_def* defs, uint32_t n, uint32_t seed,
                               tb_shape_id sphere, tb_shape_id box)
{
    uint32_t rng = scene_rng_seed(seed);
    uint32_t side = grid_side(n);
    for (uint32_t i = 0; i < n; i++) {
        tb_body_def d = tb_default_body_def();
        tb_vec3 p = grid_position(i, side);
        tb_vec3 j = rng_vec3(&rng, FREEFALL_JITTER);
        d.shape = (i % 2 == 0) ? sphere : box;
        d.position.x = p.x + j.x;
        d.position.y = p.y + j.y;
        d.position.z = p.z + j.z;
        d.linear_velocity = rng_vec3(&rng, FREEFALL_LIN_SPEED);
        d.angular_velocity = rng_vec3(&rng, FREEFALL_ANG_SPEED);
        defs[i] = d;
    }
}

static tb_result freefall_shapes(tb_world* world, tb_shape_id* sphere, tb_shape_id* box)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_vec3 half = { 0.5f, 0.3f, 0.4f };
    tb_result r = tb_shape_create_sphere(world, &sd, 0.5f, sphere);
    if (r != TB_OK) return r;
    return tb_shape_create_box(world, &sd, half, box);
}

static tb_result freefall_build(tb_world* world, const scene_params* params,
                                scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    tb_shape_id sphere, box;
    tb_result r = freefall_shapes(world, &sphere, &box);
    if (r != TB_OK) return r;

    scene_instance* inst = instance_alloc(n);
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (!inst || !defs) {
        free(defs);
        instance_free(inst);
        return TB_ERROR_OUT_OF_MEMORY;
    }
    freefall_fill_defs(defs, n, params->seed, sphere, box);
    for (uint32_t i = 0; i < n; i++) {
        inst->x0[i] = defs[i].position;
        inst->v0[i] = defs[i].linear_velocity;
    }
    r = n ? tb_body_create_many(world, defs, n, inst->ids) : TB_OK;
    free(defs);
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    *out = inst;
    return TB_OK;
}

int scene_vec3_finite(tb_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

int scene_quat_finite(tb_quat q)
{
    return isfinite(q.x) && isfinite(q.y) && isfinite(q.z) && isfinite(q.w);
}

/* Semi-implicit Euler with gravity the only force, per substep of h = dt / S:
 * v_n = v0 + g*h*n, x_n = x_{n-1} + v_n*h, so after k steps (n = k S substeps)
 * x = x0 + v0*k*dt + g*h^2*n(n+1)/2. S is the world's default substeps (tools and tests
 * run default worlds). Evaluated in double so the reference itself adds no error worth
 * reporting. */
static double freefall_error(tb_vec3 x, tb_vec3 x0, tb_vec3 v0, tb_vec3 g, double dt,
                             double k)
{
    double s = tb_default_world_def().substeps, h = dt / s, n = k * s;
    double t = k * dt, a = h * h * n * (n + 1.0) * 0.5;
    double ex = (double)x0.x + (double)v0.x * t + (double)g.x * a - (double)x.x;
    double ey = (double)x0.y + (double)v0.y * t + (double)g.y * a - (double)x.y;
    double ez = (double)x0.z + (double)v0.z * t + (double)g.z * a - (double)x.z;
    return sqrt(ex * ex + ey * ey + ez * ez);
}

static tb_result freefall_check(tb_world* world, const scene_instance* inst, uint32_t steps,
                                float dt, scene_checks* out)
{
    uint32_t n = inst->count;
    tb_vec3* pos = malloc((n ? n : 1) * sizeof *pos);
    tb_quat* rot = malloc((n ? n : 1) * sizeof *rot);
    if (!pos || !rot) {
        free(pos); free(rot);
        return TB_ERROR_OUT_OF_MEMORY;
    }
    tb_result r = n ? tb_world_read_transforms(world, inst->ids, n, pos, rot) : TB_OK;
    if (r == TB_OK) {
        tb_vec3 g = tb_world_get_gravity(world);
        double max_error = 0.0;
        uint32_t nan_count = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (!scene_vec3_finite(pos[i]) || !scene_quat_finite(rot[i])) {
                nan_count++;
                continue;
            }
            double e = freefall_error(pos[i], inst->x0[i], inst->v0[i], g, dt, steps);
            if (e > max_error) max_error = e;
        }
        out->count = 2;
        out->items[0].key = "nan";
        out->items[0].value = nan_count;
        out->items[1].key = "max_error";
        out->items[1].value = max_error;
    }
    free(pos);
    free(rot);
    return r;
}

/* ---- registry ---- */

static const scene scenes[] = {
    { "freefall", "spheres and boxes in free flight on a 3-D grid, no ground; checks "
                  "positions against the closed form", 1.0f / 60.0f, 1000, 200,
      freefall_build, freefall_check, instance_free },
    { "spheres", "N spheres on a jittered grid dropped into a walled box; checks nan, "
                 "escaped, max_penetration", 1.0f / 60.0f, 10000, 300,
      spheres_build, pile_check, instance_free },
    { "boxes", "N boxes on a jittered grid dropped into a walled box; checks nan, "
               "escaped, max_penetration", 1.0f / 60.0f, 10000, 300,
      boxes_build, pile_check, instance_free },
    { "mixed", "spheres and boxes of sizes spread 1:100 (most small, few large) dropped "
               "into a walled box; checks nan, escaped, max_penetration", 1.0f / 60.0f, 10000,
      300, sizes_build, pile_check, instance_free },
    { "pile", "spheres and boxes (half each) dropped into a walled box: the default "
              "scene", 1.0f / 60.0f, 4000, 360, mixed_build, pile_check, instance_free },
    { "stack", "N unit boxes in one column at rest on a plane; checks drift (largest "
               "displacement, m), nan, fallen", 1.0f / 60.0f, 10, 1000,
      stack_build, stack_check, instance_free },
    { "pyramid", "2-D pyramid of unit boxes on a plane, base b with b(b+1)/2 <= N; checks "
                 "drift, nan, fallen", 1.0f / 60.0f, 55, 1000,
      pyramid_build, stack_check, instance_free },
    { "columns", "N unit boxes in free-standing columns 16 deep on a grid of pitch 1.1 m, "
                 "each box shifted sideways by up to 4 cm, dropped onto each other from 10 cm "
                 "apart; checks resting, sideways drift, nan, fallen", 1.0f / 60.0f, 144,
      600, columns_build, columns_check, instance_free },
    { "deep", "N unit boxes on a grid of pitch 1.1 m, ceil(cbrt N)^2 a layer, dropped into "
              "a container whose 10 m walls are lower than the pile, friction 0.5; checks "
              "escaped, resting, max_penetration, column heights", 1.0f / 60.0f, 100000, 600,
      deep_build, deep_check, instance_free },
    { "hulls", "N random convex hulls (8-32 vertices) dropped into a walled box; checks "
               "nan, escaped, max_penetration", 1.0f / 60.0f, 4000, 360,
      hulls_build, pile_check, instance_free },
    { "compounds", "N compound bodies of 2-5 children (dumbbells, angles, tables, snowmen, "
                   "clubs of a hull and a sphere) dropped into a walled box; checks nan, "
                   "escaped, resting, max_penetration", 1.0f / 60.0f, 10000, 600,
      compounds_build, pile_check, instance_free },
    { "shapes", "N capsules, cylinders and cones (a quarter each, two sizes of each) and "
                "boxes and hulls (an eighth each) at random rotations dropped into a walled "
                "box; checks nan, escaped, resting, max_penetration", 1.0f / 60.0f, 10000, 600,
      shapes_build, pile_check, instance_free },
    { "crowd", "N spheres created at one point, every one touching every other: the worst "
               "case of pairs, colours and growth; checks nan, slowest, max_penetration",
      1.0f / 60.0f, 2000, 3, crowd_build, crowd_check, instance_free },
    { "terrain", "N boxes and hulls (half each) dropped in 4 layers onto a bowl of rolling "
                 "hills, a static triangle mesh of 131,072 triangles; checks nan, escaped "
                 "(through or off it), resting, max_penetration", 1.0f / 60.0f, 10000, 600,
      terrain_build, pile_check, instance_free },
    { "heightfield", "the terrain scene on a heightfield of the same 131,072 triangles "
                     "(cells found by row and column, no tree)", 1.0f / 60.0f, 10000, 600,
      heightfield_build, pile_check, instance_free },
    { "chain", "N capsule links joined end to end by ball joints, hung from a static post "
               "and let go level, the last link 100 times heavier; checks nan, max_gap, "
               "stretch, length_error, broken", 1.0f / 60.0f, 20, 600,
      chain_build, chain_check, instance_free },
    { "joint_grid", "a vertical net of floor(sqrt N)^2 spheres joined to their right and "
                    "lower neighbours by ball joints, the top row static; checks nan, sag "
                    "of the centre, max_gap, broken", 1.0f / 60.0f, 10000, 300,
      joint_grid_build, joint_grid_check, instance_free },
    { "bridge", "N planks hinged end to end between two static posts, a heavy box dropped "
                "on the middle; checks nan, sag of the middle plank, max_gap, max_twist, "
                "broken, load_fell", 1.0f / 60.0f, 20, 600, bridge_build, bridge_check, instance_free },
    { "ragdolls", "N ragdolls of 11 bodies (cone-twist joints at spine, neck, shoulders "
                  "and hips, limited hinges at elbows and knees) dropped leaning onto a "
                  "plane; checks nan, below_ground, max_gap, max_twist, max_swing_over, "
                  "broken, resting, max_penetration", 1.0f / 60.0f, 100, 600,
      ragdolls_build, ragdolls_check, instance_free },
    { "vehicles", "N cars of a box chassis and four cylinder wheels on motored hinges "
                  "driving on a plane; checks nan, mean_speed (+x, m/s), min and max, "
                  "flipped, max_gap, max_twist, broken", 1.0f / 60.0f, 100, 600,
      vehicles_build, vehicles_check, instance_free },
};

#define SCENE_COUNT ((uint32_t)(sizeof scenes / sizeof scenes[0]))

const scene* scene_find(const char* name)
{
    if (!name) return NULL;
    for (uint32_t i = 0; i < SCENE_COUNT; i++)
        if (strcmp(scenes[i].name, name) == 0) return &scenes[i];
    return NULL;
}

const scene* scene_list(uint32_t* count)
{
    if (count) *count = SCENE_COUNT;
    return scenes;
}

const scene* scene_default(void)
{
    return scene_find("pile");
}

const tb_body_id* scene_body_ids(const scene_instance* inst, uint32_t* count)
{
    if (count) *count = inst ? inst->count : 0;
    return inst ? inst->ids : NULL;
}

int scene_parse_u32(const char* text, uint32_t* out)
{
    char* end;
    errno = 0;
    if (!text || *text == '\0' || *text == '-') return 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || *end != '\0' || v > UINT32_MAX) return 0;
    *out = (uint32_t)v;
    return 1;
}

void scene_print_list(FILE* f)
{
    uint32_t count;
    const scene* list = scene_list(&count);
    fprintf(f, "scenes:\n");
    for (uint32_t i = 0; i < count; i++)
        fprintf(f, "  %-12s %s (default n %u, steps %u)\n", list[i].name,
                list[i].description, list[i].default_n, list[i].default_steps);
}
