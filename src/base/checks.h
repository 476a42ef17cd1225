/* Argument checks shared by the API calls: finite numbers and unit rotations. */
#ifndef TB_BASE_CHECKS_H
#define TB_BASE_CHECKS_H

#include "base/diag.h"

int tb_finite3(tb_vec3 v);
/// |v| <= limit (and finite).
int tb_within3(tb_vec3 v, float limit);
/// Every component finite and within [-limit, limit].
int tb_coordinates_within(tb_vec3 v, float limit);
int tb_finite_quat(tb_quat q);
/// Check a rotation and return it normalised; fails beyond the 1e-3 tolerance.
tb_result tb_check_rotation(tb_diag* diag, tb_quat q, tb_quat* out, const char* what);

#endif
