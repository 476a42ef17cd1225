/* The one layout of GPU data, included by the C core and by every shader.
 *
 * Everything the GPU reads or writes is declared here once: structs, binding indices,
 * specialization constant ids, stage ids, flags. Members are vec4-sized so std140, std430
 * and C agree without padding rules; tests/test_layout.c checks sizes and offsets from C.
 *
 * Bodies are stored as a structure of arrays of vec4, one storage buffer per array, so a
 * stage touches only the arrays it needs and each read is one 16-byte load.
 */
#ifndef TB_LAYOUT_H
#define TB_LAYOUT_H

#if defined(__STDC__) || defined(__cplusplus)
/* ---- C side ---- */
#include <stdint.h>
typedef struct tb_gpu_vec4 { float x, y, z, w; } tb_gpu_vec4;
typedef struct tb_gpu_uvec4 { uint32_t x, y, z, w; } tb_gpu_uvec4;
#define TB_VEC4 tb_gpu_vec4
#define TB_UVEC4 tb_gpu_uvec4
#define TB_STRUCT(name) typedef struct name name; struct name
#define TB_U(x) x##u
#else
/* ---- GLSL side ---- */
#define TB_VEC4 vec4
#define TB_UVEC4 uvec4
#define TB_STRUCT(name) struct name
#define TB_U(x) uint(x)
#endif

/* Descriptor set 0: the world. Binding indices. */
#define TB_BIND_PARAMS          0  /* uniform tb_gpu_params */
#define TB_BIND_BODY_POS        1  /* vec4[]: xyz position of the centre (m), w inverse mass (0 static) */
#define TB_BIND_BODY_ROT        2  /* vec4[]: orientation quaternion (x, y, z, w) */
#define TB_BIND_BODY_LINVEL     3  /* vec4[]: xyz linear velocity (m/s), w linear damping (1/s) */
#define TB_BIND_BODY_ANGVEL     4  /* vec4[]: xyz angular velocity (rad/s), w angular damping (1/s) */
#define TB_BIND_BODY_INV_INERTIA 5 /* vec4[]: xyz inverse principal inertia, body frame; w gravity scale */
#define TB_BIND_BODY_INFO       6  /* uvec4[]: x shape index, y TB_BODY_FLAG_*, z w reserved */
#define TB_BIND_BODY_AABB_MIN   7  /* vec4[]: world AABB minimum corner, w unused */
#define TB_BIND_BODY_AABB_MAX   8  /* vec4[]: world AABB maximum corner, w unused */
#define TB_BIND_SHAPES          9  /* tb_gpu_shape[] */
#define TB_BIND_COUNT           10

/* Specialization constant ids, set for every pipeline. */
#define TB_SPEC_WORKGROUP_SIZE  0  /* local_size_x */
#define TB_SPEC_SUBGROUP_SIZE   1  /* the device's subgroup size: 8 lavapipe, 32 NVIDIA, 64 AMD */

/* Stage ids: the order of the step. Names in src/gpu/stages.c match the shader paths. */
#define TB_STAGE_APPLY_FORCES   0  /* integrate/apply_forces: gravity and damping -> velocity */
#define TB_STAGE_INTEGRATE      1  /* integrate/integrate: velocity -> position, orientation */
#define TB_STAGE_WORLD_AABB     2  /* broadphase/world_aabb: pose + shape -> world AABB */
#define TB_STAGE_COUNT          3

/* tb_gpu_body info.y */
#define TB_BODY_FLAG_ALIVE      TB_U(1)
#define TB_BODY_FLAG_DYNAMIC    TB_U(2)

/* tb_gpu_shape info.x; equal to tb_shape_type in tumble.h */
#define TB_GPU_SHAPE_SPHERE     TB_U(0)
#define TB_GPU_SHAPE_BOX        TB_U(1)
#define TB_GPU_SHAPE_PLANE      TB_U(2)

/* Half extent given to unbounded shapes (planes): large, yet its square stays finite. */
#define TB_UNBOUNDED_EXTENT     1.0e18

/* Threads per workgroup of per-body stages. */
#define TB_WORKGROUP_SIZE       64

/* Parameters of the step, written by the host before a submission (never mid-step). */
TB_STRUCT(tb_gpu_params) {
    TB_VEC4 gravity;        /* xyz gravity (m/s^2), w time step dt (s) */
    TB_UVEC4 counts;        /* x body slots in use (high-water mark), y shape count, z w reserved */
    TB_VEC4 limits;         /* x largest rotation per step (rad), y z w reserved */
    TB_UVEC4 body_dispatch; /* xyz: VkDispatchIndirectCommand covering counts.x bodies; w reserved */
};
#define TB_PARAMS_BODY_DISPATCH_OFFSET 48 /* byte offset of body_dispatch */

/* A shape as the GPU sees it. */
TB_STRUCT(tb_gpu_shape) {
    TB_VEC4 aabb_center;    /* xyz centre of the local AABB, body frame */
    TB_VEC4 aabb_half;      /* xyz half extents of the local AABB */
    TB_VEC4 params;         /* sphere: x radius; box: xyz half extents; plane: xyz normal, w offset */
    TB_UVEC4 info;          /* x TB_GPU_SHAPE_*, y z w reserved */
};

#endif
