/* Compounds on the host: a rigid union of convex children, their mass properties composed
 * (each child's mass at its place, its inertia turned into the compound's frame, the parallel
 * axis theorem to the common centre of mass), the compound re-expressed in its principal
 * frame as the GPU uses it, and the GPU image of a compound shape (tb_gpu_compound_child in
 * glsl/common/layout.h). */
#ifndef TB_GEOM_COMPOUND_H
#define TB_GEOM_COMPOUND_H

#include <stddef.h>
#include <stdint.h>

#include "layout.h"

/* A child as the caller gives it, with what its shape says about it. */
typedef struct tb_compound_input {
    uint32_t shape;            /* the child's shape slot */
    float position[3];         /* the child's origin, caller's frame */
    float rotation[4];         /* its frame (x y z w), normalised */
    double volume, density;    /* m^3, kg/m^3 */
    double unit_inertia[3];    /* principal moments per kg, about the child's axes */
    float box_center[3], box_half[3];   /* the child's box, child frame */
} tb_compound_input;

/* A child in the compound's principal frame. */
typedef struct tb_compound_part {
    uint32_t shape;
    float position[3], rotation[4];
    float box_center[3], box_half[3];
} tb_compound_part;

typedef struct tb_compound {
    uint32_t count;
    tb_compound_part parts[TB_COMPOUND_MAX_CHILDREN];
    double volume;             /* m^3, the children's sum */
    double mass_per_volume;    /* kg/m^3 */
    double center[3];          /* centre of mass, caller's frame */
    double rotation[4];        /* principal frame -> caller's frame (x y z w) */
    double unit_inertia[3];    /* principal moments per kg */
    float box_min[3], box_max[3];   /* the children's boxes' union, principal frame */
} tb_compound;

/* Compose `count` children (1 .. TB_COMPOUND_MAX_CHILDREN, checked by the caller). Children
 * of zero density weigh by their volume alone when all are (so a body given its mass still
 * gets the inertia of the shape). */
void tb_compound_build(const tb_compound_input* children, uint32_t count, tb_compound* out);

/* The GPU image: its size in uvec4, and the image written at dst. */
size_t tb_compound_image_size(const tb_compound* c);
void tb_compound_pack(const tb_compound* c, void* dst);

#endif
