/* Argument checks shared by the API calls. */
#include <math.h>

#include "base/checks.h"

#define ROTATION_TOLERANCE 1e-3f

int tb_finite3(tb_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

int tb_within3(tb_vec3 v, float limit)
{
    double x = v.x, y = v.y, z = v.z;
    return tb_finite3(v) && x * x + y * y + z * z <= (double)limit * limit;
}

int tb_coordinates_within(tb_vec3 v, float limit)
{
    return tb_finite3(v) && fabsf(v.x) <= limit && fabsf(v.y) <= limit && fabsf(v.z) <= limit;
}

int tb_finite_quat(tb_quat q)
{
    return isfinite(q.x) && isfinite(q.y) && isfinite(q.z) && isfinite(q.w);
}

tb_result tb_check_rotation(tb_diag* diag, tb_quat q, tb_quat* out, const char* what)
{
    if (!tb_finite_quat(q))
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT, "%s: rotation is not finite", what);
    double len = sqrt((double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z + (double)q.w * q.w);
    if (fabs(len - 1.0) > ROTATION_TOLERANCE)
        return tb_fail(diag, TB_ERROR_INVALID_ARGUMENT,
                       "%s: rotation quaternion has length %g, not 1 (tolerance %g)", what, len,
                       (double)ROTATION_TOLERANCE);
    out->x = (float)(q.x / len);
    out->y = (float)(q.y / len);
    out->z = (float)(q.z / len);
    out->w = (float)(q.w / len);
    return TB_OK;
}
