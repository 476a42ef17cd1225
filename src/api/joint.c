/* Joints through the API: argument checks; the world keeps them (src/world/joints.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "api/api.h"
#include "base/checks.h"
#include "world/world.h"

#define PI_WITH_ROOM 3.1416f

tb_joint_def tb_default_joint_def(void)
{
    tb_joint_def d;
    memset(&d, 0, sizeof d);
    d.frame_a = (tb_quat){ 0, 0, 0, 1 };
    d.frame_b = (tb_quat){ 0, 0, 0, 1 };
    d.length = 1.0f;
    d.spring_hertz = 1.0f;
    d.cone_angle = (float)GLM_PI_4;
    d.internal_cookie = TB_DEF_COOKIE;
    return d;
}

static int finite_all(const float* v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static tb_result bad(tb_world* w, uint32_t i, const char* what)
{
    return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u: %s", i, what);
}

/* The numbers of a def: finite, in range, limits ordered. */
static tb_result check_numbers(tb_world* w, const tb_joint_def* d, uint32_t i)
{
    float numbers[] = { d->length, d->lower, d->upper, d->motor_speed, d->max_motor_force,
                        d->spring_hertz, d->spring_damping_ratio, d->spring_target,
                        d->cone_angle, d->break_force, d->break_torque, d->constraint_hertz,
                        d->constraint_damping_ratio };
    if (!tb_finite3(d->anchor_a) || !tb_finite3(d->anchor_b) ||
        !finite_all(numbers, (int)(sizeof numbers / sizeof numbers[0])))
        return bad(w, i, "anchors, length, limits, motor, spring, cone, break and constraint "
                   "values must be finite");
    if (!tb_coordinates_within(d->anchor_a, TB_MAX_COORDINATE) ||
        !tb_coordinates_within(d->anchor_b, TB_MAX_COORDINATE))
        return bad(w, i, "anchors must be within TB_MAX_COORDINATE of their bodies");
    if (d->length < 0) return bad(w, i, "length must be >= 0");
    if (d->enable_limit && d->lower > d->upper) return bad(w, i, "limit: lower > upper");
    int turns = d->kind == TB_JOINT_HINGE || d->kind == TB_JOINT_CONE_TWIST;
    if (d->enable_limit && turns && (d->lower < -PI_WITH_ROOM || d->upper > PI_WITH_ROOM))
        return bad(w, i, "a hinge's or cone-twist's limits must be within [-pi, pi]");
    if (d->enable_spring && d->kind == TB_JOINT_HINGE &&
        (d->spring_target < -PI_WITH_ROOM || d->spring_target > PI_WITH_ROOM))
        return bad(w, i, "a hinge's spring_target must be within [-pi, pi]");
    if (d->kind == TB_JOINT_CONE_TWIST && !(d->cone_angle >= 0 && d->cone_angle <= PI_WITH_ROOM))
        return bad(w, i, "cone_angle must be within [0, pi]");
    if (d->enable_limit && d->kind == TB_JOINT_DISTANCE && d->lower < 0)
        return bad(w, i, "a distance joint's lower limit must be >= 0");
    if (d->max_motor_force < 0) return bad(w, i, "max_motor_force must be >= 0");
    if (d->enable_spring && !(d->spring_hertz > 0 && d->spring_damping_ratio >= 0))
        return bad(w, i, "a spring needs spring_hertz > 0 and spring_damping_ratio >= 0");
    if (d->constraint_hertz < 0 || d->constraint_damping_ratio < 0)
        return bad(w, i, "constraint_hertz and constraint_damping_ratio must be >= 0 (0 Hz: "
                   "rigid)");
    if (d->break_force < 0 || d->break_torque < 0)
        return bad(w, i, "break_force and break_torque must be >= 0 (0: never)");
    return TB_OK;
}

/* A 6-dof joint's axes: known modes, finite ordered limits, turns within [-pi, pi]. */
static tb_result check_axes(tb_world* w, const tb_joint_def* d, uint32_t i)
{
    for (int k = 0; k < 6; k++) {
        const tb_joint_axis* x = &d->axes[k];
        if (x->mode != TB_JOINT_AXIS_LOCKED && x->mode != TB_JOINT_AXIS_FREE &&
            x->mode != TB_JOINT_AXIS_LIMITED)
            return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u: axis %d has an "
                           "unknown mode %d", i, k, (int)x->mode);
        if (x->mode != TB_JOINT_AXIS_LIMITED) continue;
        if (!isfinite(x->lower) || !isfinite(x->upper) || x->lower > x->upper)
            return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u: axis %d's limits "
                           "must be finite with lower <= upper", i, k);
        if (k >= 3 && (x->lower < -PI_WITH_ROOM || x->upper > PI_WITH_ROOM))
            return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u: axis %d (a turn) "
                           "must be limited within [-pi, pi]", i, k);
    }
    return TB_OK;
}

/* What each kind takes: limits, motors and springs only where the kind has them. */
static tb_result check_kind(tb_world* w, const tb_joint_def* d, uint32_t i)
{
    tb_joint_kind k = d->kind;
    if (k < TB_JOINT_BALL || k > TB_JOINT_SIX_DOF) {
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u: unknown joint kind %d",
                       i, (int)k);
    }
    int limited = k == TB_JOINT_HINGE || k == TB_JOINT_SLIDER || k == TB_JOINT_DISTANCE ||
                  k == TB_JOINT_CONE_TWIST;
    if (d->enable_limit && !limited)
        return bad(w, i, "only hinges, sliders, distance and cone-twist joints take a limit "
                   "(6-dof joints: their axes)");
    if (d->enable_motor && k != TB_JOINT_HINGE && k != TB_JOINT_SLIDER)
        return bad(w, i, "only hinges and sliders take a motor");
    if (d->enable_spring && k != TB_JOINT_DISTANCE && k != TB_JOINT_HINGE && k != TB_JOINT_SLIDER)
        return bad(w, i, "only distance joints, hinges and sliders take a spring");
    return k == TB_JOINT_SIX_DOF ? check_axes(w, d, i) : TB_OK;
}

/* A def checked; its bodies' slots to a and b. */
static tb_result resolve(tb_world* w, const tb_joint_def* d, uint32_t i, tb_joint_def* out,
                         uint32_t* a, uint32_t* b)
{
    if (!d || d->internal_cookie != TB_DEF_COOKIE)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joint def %u was not initialised "
                       "with tb_default_joint_def()", i);
    tb_result r = check_kind(w, d, i);
    if (r) return r;
    const tb_body_record* ra = tb_body_lookup(w, d->body_a, a, &r);
    if (!ra) return r;
    const tb_body_record* rb = tb_body_lookup(w, d->body_b, b, &r);
    if (!rb) return r;
    if (*a == *b) return bad(w, i, "a joint needs two different bodies");
    if (ra->type != TB_BODY_DYNAMIC && rb->type != TB_BODY_DYNAMIC)
        return bad(w, i, "at least one of the two bodies must be dynamic");
    if ((r = check_numbers(w, d, i))) return r;
    *out = *d;
    if ((r = tb_check_rotation(&w->diag, d->frame_a, &out->frame_a, "joint def frame_a")))
        return r;
    return tb_check_rotation(&w->diag, d->frame_b, &out->frame_b, "joint def frame_b");
}

tb_result tb_joint_create_many(tb_world* w, const tb_joint_def* defs, uint32_t count,
                               tb_joint_id* out)
{
    if (!w || (count && (!defs || !out)))
        return w ? tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "defs and out_ids are required")
                 : TB_ERROR_INVALID_ARGUMENT;
    if (w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_joint_create");
    if (!w->block_solver)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "joints are solved by the block "
                       "solver; this world steps with the soft step (tb_world_set_solver)");
    if ((uint64_t)w->joints.slots.live + count > TB_MAX_JOINTS)
        return tb_fail(&w->diag, TB_ERROR_CAPACITY, "%u more joints would pass the limit of %u "
                       "(TB_MAX_JOINTS)", count, (unsigned)TB_MAX_JOINTS);
    size_t n = count ? count : 1;
    tb_joint_def* checked = malloc(n * sizeof *checked);
    uint32_t* a = malloc(n * sizeof *a);
    uint32_t* b = malloc(n * sizeof *b);
    tb_result r = checked && a && b ? TB_OK
                  : tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    for (uint32_t i = 0; i < count && !r; i++) r = resolve(w, &defs[i], i, &checked[i], &a[i], &b[i]);
    if (!r) r = tb_world_joints_add(w, checked, a, b, count, out);
    free(checked);
    free(a);
    free(b);
    return r;
}

tb_result tb_joint_create(tb_world* w, const tb_joint_def* def, tb_joint_id* out)
{
    return tb_joint_create_many(w, def, 1, out);
}

tb_result tb_joint_destroy(tb_world* w, tb_joint_id id)
{
    uint32_t slot;
    tb_result r;
    if (w && w->in_callbacks) return tb_api_refuse_in_callbacks(w, "tb_joint_destroy");
    if (!tb_joint_lookup(w, id, &slot, &r)) return r;
    tb_world_joint_remove(w, slot);
    return TB_OK;
}

int tb_joint_is_valid(const tb_world* w, tb_joint_id id)
{
    if (!w || id.index1 == 0 || id.world != w->serial || id.index1 > w->joints.slots.used)
        return 0;
    const tb_joint_record* j = &w->joints.records[id.index1 - 1];
    return j->alive && j->generation == id.generation;
}

void* tb_joint_get_user_data(const tb_world* w, tb_joint_id id)
{
    return tb_joint_is_valid(w, id) ? w->joints.records[id.index1 - 1].def.user_data : NULL;
}

tb_result tb_joint_get_bodies(const tb_world* cw, tb_joint_id id, tb_body_id* a, tb_body_id* b)
{
    tb_world* w = (tb_world*)cw;
    uint32_t slot;
    tb_result r;
    const tb_joint_record* j = tb_joint_lookup(w, id, &slot, &r);
    if (!j) return r;
    if (a) *a = j->def.body_a;
    if (b) *b = j->def.body_b;
    return TB_OK;
}

/* A live joint's def `d` with its limit or motor changed: checked, then in its record and
 * on its way to the GPU; refused, the joint stays as it was. */
static tb_result replace_def(tb_world* w, tb_joint_record* j, uint32_t slot, const tb_joint_def* d)
{
    tb_result r;
    if ((r = check_kind(w, d, 0)) || (r = check_numbers(w, d, 0))) return r;
    j->def = *d;
    tb_joints_changed(&w->joints, slot);
    return TB_OK;
}

tb_result tb_joint_set_motor(tb_world* w, tb_joint_id id, int32_t enable, float speed,
                             float max_force)
{
    uint32_t slot;
    tb_result r;
    tb_joint_record* j = tb_joint_lookup(w, id, &slot, &r);
    if (!j) return r;
    tb_joint_def d = j->def;
    d.enable_motor = enable;
    d.motor_speed = speed;
    d.max_motor_force = max_force;
    return replace_def(w, j, slot, &d);
}

tb_result tb_joint_set_limit(tb_world* w, tb_joint_id id, int32_t enable, float lower,
                             float upper)
{
    uint32_t slot;
    tb_result r;
    tb_joint_record* j = tb_joint_lookup(w, id, &slot, &r);
    if (!j) return r;
    tb_joint_def d = j->def;
    d.enable_limit = enable;
    d.lower = lower;
    d.upper = upper;
    return replace_def(w, j, slot, &d);
}

tb_result tb_joint_set_spring(tb_world* w, tb_joint_id id, int32_t enable, float hertz,
                              float damping_ratio, float target)
{
    uint32_t slot;
    tb_result r;
    tb_joint_record* j = tb_joint_lookup(w, id, &slot, &r);
    if (!j) return r;
    tb_joint_def d = j->def;
    d.enable_spring = enable;
    d.spring_hertz = hertz;
    d.spring_damping_ratio = damping_ratio;
    if (d.kind == TB_JOINT_DISTANCE)
        d.length = target;
    else
        d.spring_target = target;
    return replace_def(w, j, slot, &d);
}

/* The slots of `count` ids, all valid, or an error. */
static tb_result slots_of(tb_world* w, const tb_joint_id* ids, uint32_t count, uint32_t** out)
{
    *out = malloc((count ? count : 1) * sizeof **out);
    if (!*out) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    tb_result r = TB_OK;
    for (uint32_t i = 0; i < count && !r; i++)
        if (!tb_joint_lookup(w, ids[i], &(*out)[i], &r)) break;
    if (r) {
        free(*out);
        *out = NULL;
    }
    return r;
}

tb_result tb_joint_read_forces(tb_world* w, const tb_joint_id* ids, uint32_t count,
                               tb_vec3* forces, tb_vec3* torques, int32_t* broken)
{
    if (!w || (count && !ids)) return w ? bad(w, 0, "ids are required") : TB_ERROR_INVALID_ARGUMENT;
    uint32_t* slots;
    tb_result r = slots_of(w, ids, count, &slots);
    if (r) return r;
    tb_gpu_joint_state* states = malloc((count ? count : 1) * sizeof *states);
    r = states ? tb_joints_read_state(&w->joints, &w->transfer, slots, count, states)
               : tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    for (uint32_t i = 0; i < count && !r; i++) {
        const tb_gpu_joint_state* s = &states[i];
        /* A joint that has not stepped yet has another joint's state (or none) in its slot. */
        int own = s->info.x == w->joints.records[slots[i]].generation;
        if (forces) forces[i] = own ? (tb_vec3){ s->force.x, s->force.y, s->force.z } : (tb_vec3){ 0, 0, 0 };
        if (torques) torques[i] = own ? (tb_vec3){ s->torque.x, s->torque.y, s->torque.z } : (tb_vec3){ 0, 0, 0 };
        if (broken) broken[i] = own && s->info.y != 0;
    }
    free(states);
    free(slots);
    return r;
}

/* World point of a point given in a body's frame (pose from the fresh mirror). */
static tb_vec3 world_point(const tb_world* w, uint32_t body, tb_vec3 local)
{
    const tb_gpu_vec4* p = &w->store.host[TB_ARRAY_POS][body];
    const tb_gpu_vec4* q = &w->store.host[TB_ARRAY_ROT][body];
    versor rot = { q->x, q->y, q->z, q->w };
    vec3 v = { local.x, local.y, local.z }, out;
    glm_quat_rotatev(rot, v, out);
    return (tb_vec3){ p->x + out[0], p->y + out[1], p->z + out[2] };
}

tb_result tb_joint_read_anchors(tb_world* w, const tb_joint_id* ids, uint32_t count,
                                tb_vec3* anchors_a, tb_vec3* anchors_b)
{
    if (!w || (count && !ids)) return w ? bad(w, 0, "ids are required") : TB_ERROR_INVALID_ARGUMENT;
    uint32_t* slots;
    tb_result r = slots_of(w, ids, count, &slots);
    if (!r) r = tb_world_fetch(w, TB_ARRAY_BIT(TB_ARRAY_POS) | TB_ARRAY_BIT(TB_ARRAY_ROT));
    for (uint32_t i = 0; i < count && !r; i++) {
        const tb_joint_record* j = &w->joints.records[slots[i]];
        if (anchors_a) anchors_a[i] = world_point(w, j->body_a, j->def.anchor_a);
        if (anchors_b) anchors_b[i] = world_point(w, j->body_b, j->def.anchor_b);
    }
    free(slots);
    return r;
}

/* The frame in a body's frame whose x axis is the world direction `axis` (unit). */
static tb_quat frame_in_body(const tb_world* w, uint32_t body, const float* axis)
{
    const tb_gpu_vec4* q = &w->store.host[TB_ARRAY_ROT][body];
    versor rot = { q->x, q->y, q->z, q->w }, inv, along, out;
    vec3 x = { 1, 0, 0 }, dir = { axis[0], axis[1], axis[2] };
    glm_quat_from_vecs(x, dir, along);
    glm_quat_inv(rot, inv);
    glm_quat_mul(inv, along, out);
    glm_quat_normalize(out);
    return (tb_quat){ out[0], out[1], out[2], out[3] };
}

/* A point in a body's frame from a world point. */
static tb_vec3 local_point(const tb_world* w, uint32_t body, tb_vec3 point)
{
    const tb_gpu_vec4* p = &w->store.host[TB_ARRAY_POS][body];
    const tb_gpu_vec4* q = &w->store.host[TB_ARRAY_ROT][body];
    versor rot = { q->x, q->y, q->z, q->w }, inv;
    glm_quat_inv(rot, inv);
    vec3 v = { point.x - p->x, point.y - p->y, point.z - p->z }, out;
    glm_quat_rotatev(inv, v, out);
    return (tb_vec3){ out[0], out[1], out[2] };
}

tb_result tb_joint_def_at(tb_world* w, tb_joint_def* def, tb_vec3 point, tb_vec3 axis)
{
    if (!w) return TB_ERROR_INVALID_ARGUMENT;
    if (!def) return bad(w, 0, "def is required");
    float len = sqrtf(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    if (!tb_finite3(point) || !tb_finite3(axis) || !(len > 1e-6f))
        return bad(w, 0, "point and axis must be finite, the axis not zero");
    uint32_t a, b;
    tb_result r;
    if (!tb_body_lookup(w, def->body_a, &a, &r) || !tb_body_lookup(w, def->body_b, &b, &r))
        return r;
    if ((r = tb_world_fetch(w, TB_ARRAY_BIT(TB_ARRAY_POS) | TB_ARRAY_BIT(TB_ARRAY_ROT))))
        return r;
    float unit[3] = { axis.x / len, axis.y / len, axis.z / len };
    def->anchor_a = local_point(w, a, point);
    def->anchor_b = local_point(w, b, point);
    def->frame_a = frame_in_body(w, a, unit);
    def->frame_b = frame_in_body(w, b, unit);
    return TB_OK;
}

uint32_t tb_world_joint_ids(const tb_world* w, tb_joint_id* out, uint32_t capacity)
{
    return w ? tb_world_joints_ids(w, out, capacity) : 0;
}
