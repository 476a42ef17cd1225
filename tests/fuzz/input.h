/* The fuzz targets' reader of their input: bytes taken from the front, zeros once it runs
 * out. Numbers are mostly ordinary (so scenes form and steps run) and sometimes the values
 * that break engines: zero, signed zero, the smallest and largest floats, denormals,
 * infinities, NaN and the API's documented limits just inside and just past. */
#ifndef TUMBLE_FUZZ_INPUT_H
#define TUMBLE_FUZZ_INPUT_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "tumble.h"

typedef struct fz_input {
    const uint8_t* data;
    size_t size;
} fz_input;

static inline uint8_t fz_u8(fz_input* in)
{
    if (!in->size) return 0;
    in->size--;
    return *in->data++;
}

static inline uint32_t fz_u32(fz_input* in)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) v = v << 8 | fz_u8(in);
    return v;
}

/* An ordinary value in [-8, 8) in steps of 1/16, or one of the special ones. */
static inline float fz_float(fz_input* in)
{
    static const float special[] = {
        0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 1e-45f, 1.17549435e-38f, 3.4e38f, -3.4e38f,
        1e6f, 1.000001e6f, 1000.0f, 1000.001f, 100.0f, 1e-6f, 1e-3f, 0.5f, 1e30f, -1e30f,
    };
    uint8_t kind = fz_u8(in);
    if (kind < 224) return ((float)(int)fz_u8(in) - 128.0f) / 16.0f;
    if (kind < 224 + sizeof special / sizeof special[0]) return special[kind - 224];
    if (kind == 250) return INFINITY;
    if (kind == 251) return -INFINITY;
    if (kind == 252) return NAN;
    uint32_t bits = fz_u32(in);   /* any bit pattern */
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static inline tb_vec3 fz_vec3(fz_input* in)
{
    tb_vec3 v;
    v.x = fz_float(in);
    v.y = fz_float(in);
    v.z = fz_float(in);
    return v;
}

/* A point: usually within a few metres of the origin, where bodies meet. */
static inline tb_vec3 fz_point(fz_input* in)
{
    return fz_vec3(in);
}

/* Mostly a unit quaternion from its axis and angle; sometimes four raw floats. */
static inline tb_quat fz_rotation(fz_input* in)
{
    uint8_t kind = fz_u8(in);
    tb_quat q = { 0, 0, 0, 1 };
    if (kind < 64) return q;
    if (kind >= 240) {
        q.x = fz_float(in);
        q.y = fz_float(in);
        q.z = fz_float(in);
        q.w = fz_float(in);
        return q;
    }
    tb_vec3 axis = { (float)fz_u8(in) - 127.5f, (float)fz_u8(in) - 127.5f,
                     (float)fz_u8(in) - 127.5f };
    float length = sqrtf(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    float half = (float)fz_u8(in) * 0.0123f;
    float s = sinf(half) / length;
    q = (tb_quat){ axis.x * s, axis.y * s, axis.z * s, cosf(half) };
    return q;
}

#endif
