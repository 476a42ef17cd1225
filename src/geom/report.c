/* See report.h. */
#include "geom/report.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int tb_geom_fail(char* error, size_t size, const char* fmt, ...)
{
    if (error && size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(error, size, fmt, ap);
        va_end(ap);
    }
    return -1;
}

uint32_t tb_geom_float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

float tb_geom_bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
