/* What the joint scenes share (joints_chain.c, joints_bridge.c, joints_ragdolls.c,
 * joints_vehicles.c): static bodies to hang things from or stand on, joints made at a world
 * point from the bodies' poses, a little quaternion arithmetic for placing bodies, and the
 * figures every joint scene reports: bodies that stopped being finite, and how far the
 * two anchors of any joint have come apart. Joints need the block solver, the world's
 * default. */
#include "instance.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>

tb_result joints_static_box(tb_world* w, tb_vec3 centre, tb_vec3 half, tb_body_id* out)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id box;
    tb_result r = tb_shape_create_box(w, &sd, half, &box);
    if (r != TB_OK) return r;
    tb_body_def d = tb_default_body_def();
    d.type = TB_BODY_STATIC;
    d.shape = box;
    d.position = centre;
    return tb_body_create(w, &d, out);
}

tb_result joints_def_at(tb_world* w, tb_joint_kind kind, tb_body_id a, tb_body_id b,
                        tb_vec3 point, tb_vec3 axis, tb_joint_def* out)
{
    *out = tb_default_joint_def();
    out->kind = kind;
    out->body_a = a;
    out->body_b = b;
    return tb_joint_def_at(w, out, point, axis);
}

tb_result joints_create(tb_world* w, const tb_joint_def* defs, uint32_t count)
{
    if (count == 0) return TB_OK;
    tb_joint_id* ids = malloc(count * sizeof *ids);
    if (!ids) return TB_ERROR_OUT_OF_MEMORY;
    tb_result r = tb_joint_create_many(w, defs, count, ids);
    free(ids);
    return r;
}

/* ---- quaternions and vectors (cglm's versor is x, y, z, w, as tb_quat is) ---- */

tb_quat joints_axis_angle(tb_vec3 axis, float angle)
{
    versor q;
    glm_quatv(q, angle, (vec3){ axis.x, axis.y, axis.z });
    return (tb_quat){ q[0], q[1], q[2], q[3] };
}

tb_quat joints_quat_mul(tb_quat a, tb_quat b)
{
    versor qa = { a.x, a.y, a.z, a.w }, qb = { b.x, b.y, b.z, b.w }, out;
    glm_quat_mul(qa, qb, out);
    return (tb_quat){ out[0], out[1], out[2], out[3] };
}

tb_vec3 joints_rotate(tb_quat q, tb_vec3 v)
{
    versor qv = { q.x, q.y, q.z, q.w };
    vec3 out;
    glm_quat_rotatev(qv, (vec3){ v.x, v.y, v.z }, out);
    return (tb_vec3){ out[0], out[1], out[2] };
}

tb_vec3 joints_add(tb_vec3 a, tb_vec3 b)
{
    return (tb_vec3){ a.x + b.x, a.y + b.y, a.z + b.z };
}

double joints_distance(tb_vec3 a, tb_vec3 b)
{
    double dx = (double)a.x - b.x, dy = (double)a.y - b.y, dz = (double)a.z - b.z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

double joints_angle_between(tb_vec3 u, tb_vec3 v)
{
    double cx = (double)u.y * v.z - (double)u.z * v.y, cy = (double)u.z * v.x - (double)u.x * v.z,
           cz = (double)u.x * v.y - (double)u.y * v.x;
    double dot = (double)u.x * v.x + (double)u.y * v.y + (double)u.z * v.z;
    return atan2(sqrt(cx * cx + cy * cy + cz * cz), dot);
}

/* ---- figures ---- */

static tb_result take_census(tb_world* w, joints_census* out)
{
    *out = (joints_census){ 0, 0, 0.0 };
    uint32_t n = tb_world_joint_ids(w, NULL, 0);
    if (n == 0) return TB_OK;
    tb_joint_id* ids = malloc(n * sizeof *ids);
    tb_vec3* a = malloc(n * sizeof *a);
    tb_vec3* b = malloc(n * sizeof *b);
    int32_t* broken = malloc(n * sizeof *broken);
    tb_result r = ids && a && b && broken ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK) n = tb_world_joint_ids(w, ids, n);
    if (r == TB_OK) r = tb_joint_read_anchors(w, ids, n, a, b);
    if (r == TB_OK) r = tb_joint_read_forces(w, ids, n, NULL, NULL, broken);
    for (uint32_t i = 0; r == TB_OK && i < n; i++) {
        double gap = joints_distance(a[i], b[i]);
        /* A NaN gap counts as the largest. */
        if (!(gap <= out->max_gap)) out->max_gap = gap;
        out->broken += broken[i] != 0;
    }
    out->count = n;
    free(ids);
    free(a);
    free(b);
    free(broken);
    return r;
}

tb_result joints_read_poses(tb_world* w, const scene_instance* inst, tb_vec3** pos,
                            tb_quat** rot, uint32_t* nan, joints_census* census)
{
    uint32_t n = inst->count;
    *pos = malloc((n ? n : 1) * sizeof **pos);
    *rot = malloc((n ? n : 1) * sizeof **rot);
    *nan = 0;
    tb_result r = *pos && *rot ? TB_OK : TB_ERROR_OUT_OF_MEMORY;
    if (r == TB_OK && n) r = tb_world_read_transforms(w, inst->ids, n, *pos, *rot);
    for (uint32_t i = 0; r == TB_OK && i < n; i++)
        if (!scene_vec3_finite((*pos)[i]) || !scene_quat_finite((*rot)[i])) (*nan)++;
    return r == TB_OK ? take_census(w, census) : r;
}

