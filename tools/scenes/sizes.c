/* The "mixed" scene: spheres and boxes whose sizes spread 1:100, dropped into a container.
 * Sizes follow a steep power law (most bodies small, a few large), so small bodies lie
 * beside large ones: a grid sized by the largest body holds many small ones per cell, the
 * case that sort-and-sweep and trees are for. Sizes come in a few dozen classes so a
 * million bodies share a few dozen shapes. */
#include "instance.h"

#include <math.h>
#include <stdlib.h>

#define SIZE_SMALLEST 0.05f  /* half extent (radius) of the smallest class, m */
#define SIZE_SPREAD 100.0f   /* largest / smallest */
#define SIZE_CLASSES 24
#define SIZE_GAP 0.05f       /* m between neighbours at the start */
#define SIZE_DROP 0.5f       /* m between the floor and the lowest layer */

static float class_size(uint32_t k)
{
    return SIZE_SMALLEST * powf(SIZE_SPREAD, (float)k / (float)(SIZE_CLASSES - 1));
}

/* Class of a body: u^4 of a uniform u, so a body is ten times larger about half as often. */
static uint32_t pick_class(uint32_t* rng)
{
    float u = 0.5f + 0.5f * scene_rng_signed(rng);
    uint32_t k = (uint32_t)(powf(u, 4.0f) * (float)SIZE_CLASSES);
    return k < SIZE_CLASSES ? k : SIZE_CLASSES - 1;
}

/* Rows along x, rows of rows along z, layers upwards: each row as deep and each layer as
 * tall as its largest body. The footprint is about as wide as the packed bodies are tall. */
typedef struct packer { float width, x, z, y, row_depth, layer_height; } packer;

static tb_vec3 pack(packer* p, float side)
{
    if (p->x + side > p->width) { p->x = 0; p->z += p->row_depth; p->row_depth = 0; }
    if (p->z + side > p->width) { p->z = 0; p->y += p->layer_height; p->layer_height = 0; }
    tb_vec3 at = { p->x + 0.5f * side - 0.5f * p->width, SIZE_DROP + p->y + 0.5f * side,
                   p->z + 0.5f * side - 0.5f * p->width };
    p->x += side;
    p->row_depth = fmaxf(p->row_depth, side);
    p->layer_height = fmaxf(p->layer_height, side);
    return at;
}

static float footprint(const uint8_t* cls, uint32_t n)
{
    double volume = 0;
    for (uint32_t i = 0; i < n; i++) volume += pow(2.0 * class_size(cls[i]) + SIZE_GAP, 3.0);
    float width = (float)(1.6 * cbrt(volume));
    float largest = 2.0f * class_size(SIZE_CLASSES - 1) + SIZE_GAP;
    return width > 2.0f * largest ? width : 2.0f * largest;
}

tb_result sizes_build(tb_world* w, const scene_params* params, scene_instance** out)
{
    *out = NULL;
    uint32_t n = params->n, rng = scene_rng_seed(params->seed);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id shapes[2][SIZE_CLASSES];
    tb_result r = TB_OK;
    for (uint32_t k = 0; r == TB_OK && k < SIZE_CLASSES; k++) {
        float h = class_size(k);
        r = tb_shape_create_sphere(w, &sd, h, &shapes[0][k]);
        if (r == TB_OK) r = tb_shape_create_box(w, &sd, (tb_vec3){ h, h, h }, &shapes[1][k]);
    }
    scene_instance* inst = r == TB_OK ? instance_alloc(n) : NULL;
    tb_body_def* defs = malloc((n ? n : 1) * sizeof *defs);
    uint8_t* cls = malloc(n ? n : 1);
    if (r == TB_OK && (!inst || !defs || !cls)) r = TB_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; r == TB_OK && i < n; i++) cls[i] = (uint8_t)pick_class(&rng);
    packer p = { r == TB_OK ? footprint(cls, n) : 1.0f, 0, 0, 0, 0, 0 };
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        tb_body_def d = tb_default_body_def();
        d.shape = shapes[i % 2][cls[i]];
        d.position = pack(&p, 2.0f * class_size(cls[i]) + SIZE_GAP);
        defs[i] = d;
    }
    pile_layout l = { 0 };
    l.half_width = 0.5f * p.width;
    l.height = SIZE_DROP + p.y + p.layer_height + 2.0f;
    free(cls);
    return pile_finish(w, &l, defs, n, r, inst, out);
}
