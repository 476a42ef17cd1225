/* Terrain: N bodies, boxes and hulls by turns, dropped in TERRAIN_LAYERS layers onto a static
 * triangle mesh of TERRAIN_CELLS x TERRAIN_CELLS quads (two triangles each, 131,072 in all;
 * the scene `heightfield` has the same surface as a heightfield of as many cells):
 * a bowl, so what lands stays on it, with rolling hills of TERRAIN_HILL m on top. The
 * terrain spans the drop grid and a margin; its cells grow with N (a 10,000-body drop gets
 * cells of about 0.22 m, smaller than a body; 100,000 bodies about 0.68 m).
 *
 * Checks as the piles do: nan, escaped (fell through the terrain or off its edge), resting,
 * max_penetration.
 */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define TERRAIN_CELLS 256
#define TERRAIN_LAYERS 4
#define TERRAIN_HILL 0.5f       /* amplitude of the hills, m */
#define TERRAIN_WAVE 12.0f      /* their wavelength, m */
#define TERRAIN_BOWL 0.1f       /* rise of the rim, per metre of half width */
#define TERRAIN_BOX 0.3f        /* half extent of the boxes, m */
#define PI_F 3.14159265f

static float terrain_height(float x, float z, float half)
{
    float u = x / half, v = z / half;
    return TERRAIN_BOWL * half * (u * u + v * v) +
           TERRAIN_HILL * sinf(2.0f * PI_F * x / TERRAIN_WAVE) * sinf(2.0f * PI_F * z / TERRAIN_WAVE);
}

/* The mesh over [-half, half]^2, counter-clockwise seen from above. */
static tb_result make_terrain(tb_world* w, float half, tb_shape_id* out)
{
    const uint32_t cells = TERRAIN_CELLS, side = cells + 1;
    tb_vec3* v = malloc(sizeof *v * side * side);
    uint32_t* t = malloc(sizeof *t * 6 * cells * cells);
    tb_result r = v && t ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t j = 0; r == TB_OK && j < side; j++) {
        for (uint32_t i = 0; i < side; i++) {
            float x = half * (2.0f * (float)i / cells - 1.0f);
            float z = half * (2.0f * (float)j / cells - 1.0f);
            v[j * side + i] = (tb_vec3){ x, terrain_height(x, z, half), z };
        }
    }
    for (uint32_t j = 0; r == TB_OK && j < cells; j++) {
        for (uint32_t i = 0; i < cells; i++) {
            uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
            uint32_t* q = t + 6 * (j * cells + i);
            q[0] = a; q[1] = c; q[2] = b;
            q[3] = b; q[4] = c; q[5] = d;
        }
    }
    tb_shape_def sd = tb_default_shape_def();
    if (r == TB_OK) r = tb_shape_create_mesh(w, &sd, v, side * side, t, 2 * cells * cells, out);
    free(v);
    free(t);
    return r;
}

/* The same surface as a heightfield: the grid's samples, centred as the mesh is. */
static tb_result make_field(tb_world* w, float half, tb_shape_id* out)
{
    const uint32_t side = TERRAIN_CELLS + 1;
    float* h = malloc(sizeof *h * side * side);
    if (!h) return TB_ERROR_OUT_OF_MEMORY;
    float cell = 2.0f * half / TERRAIN_CELLS;
    for (uint32_t k = 0; k < side; k++)
        for (uint32_t i = 0; i < side; i++)
            h[k * side + i] = terrain_height(half * (2.0f * (float)i / TERRAIN_CELLS - 1.0f),
                                             half * (2.0f * (float)k / TERRAIN_CELLS - 1.0f), half);
    tb_shape_def sd = tb_default_shape_def();
    tb_result r = tb_shape_create_heightfield(w, &sd, h, side, side, cell, cell, NULL, out);
    free(h);
    return r;
}

static tb_result build(tb_world* w, const scene_params* params, int field, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n;
    uint32_t across = (uint32_t)ceil(sqrt((double)(n ? n : 1) / TERRAIN_LAYERS));
    float pitch = 1.1f;
    float grid_half = 0.5f * (float)across * pitch;
    float half = 1.2f * grid_half + 4.0f;
    uint32_t rng = scene_rng_seed(params->seed);
    tb_shape_id hulls[HULLS_SHAPES], box, terrain;
    tb_result r = hulls_make_shapes(w, &rng, hulls);
    tb_shape_def sd = tb_default_shape_def();
    if (r == TB_OK) r = tb_shape_create_box(w, &sd, (tb_vec3){ TERRAIN_BOX, TERRAIN_BOX,
                                                               TERRAIN_BOX }, &box);
    if (r == TB_OK) r = field ? make_field(w, half, &terrain) : make_terrain(w, half, &terrain);
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    if (r == TB_OK && (!inst || !defs)) r = TB_ERROR_OUT_OF_MEMORY;
    /* Above the highest point of the terrain under the grid (the bowl's rim and a hill). */
    float top = TERRAIN_BOWL * 2.0f * grid_half * grid_half / half + TERRAIN_HILL + 1.0f;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        uint32_t layer = i / (across * across), cell = i % (across * across);
        tb_body_def d = tb_default_body_def();
        d.shape = i % 2 ? hulls[(i / 2) % HULLS_SHAPES] : box;
        d.position = (tb_vec3){ -grid_half + pitch * (0.5f + (float)(cell % across)) +
                                    0.05f * scene_rng_signed(&rng),
                                top + pitch * (float)layer,
                                -grid_half + pitch * (0.5f + (float)(cell / across)) +
                                    0.05f * scene_rng_signed(&rng) };
        d.rotation = hulls_random_rotation(&rng);
        defs[i] = d;
    }
    if (r == TB_OK) r = tb_body_create_many(w, defs, n, inst->ids);
    free(defs);
    if (r == TB_OK) {
        tb_body_def d = tb_default_body_def();
        d.type = TB_BODY_STATIC;
        d.shape = terrain;
        tb_body_id id;
        r = tb_body_create(w, &d, &id);
    }
    if (r != TB_OK) {
        instance_free(inst);
        return r;
    }
    /* Escaped: below the bowl's bottom (the hills reach TERRAIN_HILL under it) or off the
     * terrain's edge. */
    inst->box_min = (tb_vec3){ -half, -TERRAIN_HILL - 1.0f, -half };
    inst->box_max = (tb_vec3){ half, 1.0e6f, half };
    *out = inst;
    return TB_OK;
}

tb_result terrain_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return build(w, params, 0, out);
}

tb_result heightfield_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    return build(w, params, 1, out);
}
