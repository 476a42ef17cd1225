/* Helpers shared by the Tumble tests; see harness.h. */
#include "harness.h"

#include <dlfcn.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

/* ---- log recording and worlds --------------------------------------------------------- */

/* One record per live world made here; a test never holds more than a few worlds. */
#define TH_MAX_WORLDS 16
typedef struct th_world_slot {
    tb_world* world;
    int in_use;
    int allow_logged_errors;
    th_log log;
} th_world_slot;
static th_world_slot th_slots[TH_MAX_WORLDS];

void th_log_fn(void* user, tb_log_level level, const char* message)
{
    th_log* log = (th_log*)user;
    if (log) log->messages++;
    if (level < TB_LOG_WARNING) return;
    if (log) {
        log->warnings++;
        snprintf(log->last_warning, sizeof log->last_warning, "%s", message ? message : "");
    }
    fprintf(stderr, "[tumble %s] %s\n", level >= TB_LOG_ERROR ? "error" : "warning",
            message ? message : "(null)");
}

static th_world_slot* th_slot_alloc(void)
{
    for (int i = 0; i < TH_MAX_WORLDS; i++) {
        if (!th_slots[i].in_use) {
            memset(&th_slots[i], 0, sizeof th_slots[i]);
            th_slots[i].in_use = 1;
            return &th_slots[i];
        }
    }
    fail_msg("harness: more than %d live worlds", TH_MAX_WORLDS);
    return NULL;
}

static th_world_slot* th_slot_find(const tb_world* w)
{
    for (int i = 0; i < TH_MAX_WORLDS; i++)
        if (th_slots[i].in_use && th_slots[i].world == w) return &th_slots[i];
    return NULL;
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TH_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define TH_SANITIZED 1
#endif

/* Under AddressSanitizer: the Vulkan loader unloads the driver and the validation layer
 * when a world ends, and LeakSanitizer then cannot name what they kept (their caches) to
 * match tests/lsan.supp. Loaded here for good, they stay named. */
static void th_keep_vulkan_loaded(void)
{
#ifdef TH_SANITIZED
    static int done;
    if (done++) return;
    (void)dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE);
    (void)dlopen("libVkLayer_khronos_validation.so", RTLD_NOW | RTLD_NODELETE);
#endif
}

tb_world* th_world_create_ex(const tb_world_def* def_or_null, int allow_logged_errors)
{
    th_keep_vulkan_loaded();
    tb_world_def def = def_or_null ? *def_or_null : tb_default_world_def();
    th_world_slot* slot = th_slot_alloc();
    def.validation = 1;
    def.log = th_log_fn;
    def.log_user = &slot->log;
    slot->allow_logged_errors = allow_logged_errors;
    tb_world* w = NULL;
    tb_result r = tb_world_create(&def, &w);
    if (r != TB_OK || !w) {
        slot->in_use = 0;
        fail_msg("tb_world_create: %s: %s", tb_result_string(r), tb_world_last_error(NULL));
    }
    slot->world = w;
    return w;
}

tb_world* th_world_create(const tb_world_def* def_or_null)
{
    return th_world_create_ex(def_or_null, 0);
}

const th_log* th_world_log(const tb_world* w)
{
    th_world_slot* slot = th_slot_find(w);
    return slot ? &slot->log : NULL;
}

void th_world_destroy(tb_world* w)
{
    th_world_slot* slot = th_slot_find(w);
    assert_non_null(slot);
    tb_world_stats st = th_stats(w);
    uint32_t warnings = slot->log.warnings;
    int allow = slot->allow_logged_errors;
    char last[sizeof slot->log.last_warning];
    memcpy(last, slot->log.last_warning, sizeof last);
    /* Destroy first so a failing assertion does not leak the device. */
    tb_world_destroy(w);
    slot->in_use = 0;
    if (st.validation_messages != 0)
        fail_msg("%llu validation message(s); last logged: %s",
                 (unsigned long long)st.validation_messages, last);
    if (!allow && warnings != 0)
        fail_msg("%u warning(s) logged; last: %s", warnings, last);
}

tb_world_stats th_stats(const tb_world* w)
{
    tb_world_stats st;
    memset(&st, 0, sizeof st);
    th_assert_ok(tb_world_get_stats(w, &st));
    return st;
}

/* ---- random numbers --------------------------------------------------------------------- */

th_rng th_rng_seed(uint64_t seed)
{
    th_rng r;
    r.s = seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
    if (r.s == 0) r.s = 1; /* xorshift state must be non-zero */
    return r;
}

uint32_t th_rng_u32(th_rng* r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (uint32_t)((r->s * 0x2545F4914F6CDD1Dull) >> 32);
}

float th_rng_range(th_rng* r, float lo, float hi)
{
    double u = (double)th_rng_u32(r) / 4294967296.0;
    return (float)(lo + (hi - lo) * u);
}

tb_quat th_rng_quat(th_rng* r)
{
    const double two_pi = 6.283185307179586;
    double u1 = th_rng_range(r, 0.f, 1.f), u2 = th_rng_range(r, 0.f, 1.f);
    double u3 = th_rng_range(r, 0.f, 1.f);
    double a = sqrt(1.0 - u1), b = sqrt(u1);
    tb_quat q = { (float)(a * sin(two_pi * u2)), (float)(a * cos(two_pi * u2)),
                  (float)(b * sin(two_pi * u3)), (float)(b * cos(two_pi * u3)) };
    return q;
}

/* ---- vector math -------------------------------------------------------------------------- */

tb_vec3 th_v3(float x, float y, float z)
{
    tb_vec3 v = { x, y, z };
    return v;
}

tb_quat th_q(float x, float y, float z, float w)
{
    tb_quat q = { x, y, z, w };
    return q;
}

tb_quat th_quat_axis_angle(tb_vec3 axis, double angle)
{
    double n = sqrt((double)axis.x * axis.x + (double)axis.y * axis.y + (double)axis.z * axis.z);
    double s = sin(angle * 0.5) / n;
    return th_q((float)(axis.x * s), (float)(axis.y * s), (float)(axis.z * s),
                (float)cos(angle * 0.5));
}

double th_quat_length(tb_quat q)
{
    return sqrt((double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z + (double)q.w * q.w);
}

void th_quat_rotate(tb_quat q, const double v[3], double out[3])
{
    /* v' = v + 2w (u x v) + 2 u x (u x v), u = vector part */
    double u[3] = { q.x, q.y, q.z }, w = q.w;
    double t[3] = { 2 * (u[1] * v[2] - u[2] * v[1]), 2 * (u[2] * v[0] - u[0] * v[2]),
                    2 * (u[0] * v[1] - u[1] * v[0]) };
    out[0] = v[0] + w * t[0] + (u[1] * t[2] - u[2] * t[1]);
    out[1] = v[1] + w * t[1] + (u[2] * t[0] - u[0] * t[2]);
    out[2] = v[2] + w * t[2] + (u[0] * t[1] - u[1] * t[0]);
}

double th_quat_angle(tb_quat q)
{
    double s = sqrt((double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z);
    return 2.0 * atan2(s, fabs((double)q.w));
}

/* ---- comparisons ------------------------------------------------------------------------ */

int th_near(double a, double b, double abs_tol, double rel_tol)
{
    double m = fmax(fabs(a), fabs(b));
    return fabs(a - b) <= abs_tol + rel_tol * m; /* false for NaN */
}

void th_assert_near_(double a, double b, double abs_tol, double rel_tol, const char* ea,
                     const char* eb, const char* file, int line)
{
    if (th_near(a, b, abs_tol, rel_tol)) return;
    print_error("%s = %.9g, %s = %.9g, difference %.3g exceeds %.3g + %.3g relative\n", ea, a,
                eb, b, a - b, abs_tol, rel_tol);
    _fail(file, line);
}

void th_assert_result_(tb_result got, tb_result want, const char* expr, const char* file,
                       int line)
{
    if (got == want) return;
    print_error("%s returned %d (%s), expected %d (%s)\n", expr, (int)got,
                tb_result_string(got), (int)want, tb_result_string(want));
    _fail(file, line);
}

/* ---- object helpers --------------------------------------------------------------------- */

tb_shape_id th_sphere(tb_world* w, float radius)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id id = tb_null_shape;
    th_assert_ok(tb_shape_create_sphere(w, &sd, radius, &id));
    return id;
}

tb_shape_id th_box(tb_world* w, tb_vec3 half_extents)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id id = tb_null_shape;
    th_assert_ok(tb_shape_create_box(w, &sd, half_extents, &id));
    return id;
}

tb_shape_id th_rock(tb_world* w)
{
    tb_vec3 pts[8];
    for (int i = 0; i < 8; i++)
        pts[i] = th_v3(i & 1 ? 0.1f : -0.1f, i & 2 ? 0.12f : -0.1f, i & 4 ? 0.1f : -0.08f);
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id id = tb_null_shape;
    th_assert_ok(tb_shape_create_hull(w, &sd, pts, 8, &id));
    return id;
}

tb_shape_id th_plane(tb_world* w, tb_vec3 normal, float offset)
{
    tb_shape_def sd = tb_default_shape_def();
    tb_shape_id id = tb_null_shape;
    th_assert_ok(tb_shape_create_plane(w, &sd, normal, offset, &id));
    return id;
}

tb_body_def th_dynamic_def(tb_shape_id shape, tb_vec3 position)
{
    tb_body_def d = tb_default_body_def();
    d.type = TB_BODY_DYNAMIC;
    d.shape = shape;
    d.position = position;
    return d;
}

tb_body_def th_static_def(tb_shape_id shape, tb_vec3 position)
{
    tb_body_def d = th_dynamic_def(shape, position);
    d.type = TB_BODY_STATIC;
    return d;
}

tb_body_id th_body(tb_world* w, const tb_body_def* def)
{
    tb_body_id id = tb_null_body;
    th_assert_ok(tb_body_create(w, def, &id));
    assert_true(tb_body_is_valid(w, id));
    return id;
}

tb_body_id th_post(tb_world* w, tb_vec3 at)
{
    tb_body_def d = th_static_def(th_sphere(w, 0.02f), at);
    return th_body(w, &d);
}

tb_joint_def th_joint_def_at(tb_world* w, tb_joint_kind kind, tb_body_id a, tb_body_id b,
                             tb_vec3 at, tb_vec3 axis)
{
    tb_joint_def d = tb_default_joint_def();
    d.kind = kind;
    d.body_a = a;
    d.body_b = b;
    th_assert_ok(tb_joint_def_at(w, &d, at, axis));
    return d;
}

tb_joint_id th_joint(tb_world* w, const tb_joint_def* def)
{
    tb_joint_id id;
    th_assert_ok(tb_joint_create(w, def, &id));
    return id;
}

double th_joint_gap(tb_world* w, tb_joint_id joint)
{
    tb_vec3 a, b;
    th_assert_ok(tb_joint_read_anchors(w, &joint, 1, &a, &b));
    return sqrt(pow(b.x - a.x, 2) + pow(b.y - a.y, 2) + pow(b.z - a.z, 2));
}

void th_read_pose(tb_world* w, tb_body_id id, tb_vec3* position, tb_quat* rotation)
{
    th_assert_ok(tb_world_read_transforms(w, &id, 1, position, rotation));
}

double th_bounce_apex(tb_world* w, float restitution, float drop)
{
    tb_body_def ground = th_static_def(th_plane(w, th_v3(0, 1, 0), 0.0f), th_v3(0, 0, 0));
    th_body(w, &ground);
    tb_shape_def sd = tb_default_shape_def();
    sd.restitution = restitution;   /* the pair takes the larger of the two */
    tb_shape_id s;
    th_assert_ok(tb_shape_create_sphere(w, &sd, 0.25f, &s));
    tb_body_def d = th_dynamic_def(s, th_v3(0, 0.25f + drop, 0));
    tb_body_id ball = th_body(w, &d);
    int bounced = 0;
    double apex = 0;
    for (int i = 0; i < 600; i++) {
        th_assert_ok(tb_world_step(w, 1.0f / 60.0f));
        tb_vec3 p, v, omega;
        th_read_pose(w, ball, &p, NULL);
        th_assert_ok(tb_body_get_velocity(w, ball, &v, &omega));
        if (!bounced && v.y > 0) bounced = 1;
        if (bounced && p.y - 0.25 > apex) apex = p.y - 0.25;
        if (bounced && v.y < 0) break;
    }
    assert_true(bounced);
    return apex;
}

int th_large_scene_runs(const char* what, const char* width)
{
    const char* here = getenv("LP_NATIVE_VECTOR_WIDTH");
    if (!here || strcmp(here, width) == 0 || getenv("TB_ALL_WIDTHS")) return 1;
    print_message("  %s runs at LP_NATIVE_VECTOR_WIDTH=%s only (TB_ALL_WIDTHS=1: here too)\n",
                  what, width);
    return 0;
}
