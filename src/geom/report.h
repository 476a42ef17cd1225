/* What the geometry builders share: the sentence a refusal writes into the caller's
 * buffer, and floats as the bits the GPU images store them in. */
#ifndef TB_GEOM_REPORT_H
#define TB_GEOM_REPORT_H

#include <stddef.h>
#include <stdint.h>

/* Write the printf-formatted sentence to error (when it has room) and return -1. */
int tb_geom_fail(char* error, size_t size, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A float's bits as a uint32, and back. */
uint32_t tb_geom_float_bits(float f);
float tb_geom_bits_float(uint32_t u);

#endif
