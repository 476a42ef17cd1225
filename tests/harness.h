/* Helpers shared by the Tumble tests (prefix th_). Plain C99 on top of cmocka.
 *
 * Every GPU test makes its worlds with th_world_create, which turns the validation layer on
 * and routes the library's log through a recorder, and ends them with th_world_destroy,
 * which fails the test when the validation layer or the library complained.
 */
#ifndef TH_HARNESS_H
#define TH_HARNESS_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "tumble.h"

/* ---- log recording ------------------------------------------------------------------- */

/// What the log callback saw for one world.
typedef struct th_log {
    uint32_t messages;       ///< every message
    uint32_t warnings;       ///< TB_LOG_WARNING and above
    char last_warning[512];  ///< text of the last warning or error
} th_log;

/// tb_log_fn that records into the th_log passed as `user` (may be NULL) and prints
/// warnings and errors to stderr.
void th_log_fn(void* user, tb_log_level level, const char* message);

/// Create a world (def NULL: tb_default_world_def()) with validation on and th_log_fn as
/// its log. Asserts success.
tb_world* th_world_create(const tb_world_def* def_or_null);
/// As th_world_create; with allow_logged_errors the library may log warnings and errors
/// (tests that feed bad input on purpose). Validation messages still fail.
tb_world* th_world_create_ex(const tb_world_def* def_or_null, int allow_logged_errors);
/// The log record of a world made by th_world_create (NULL for other worlds).
const th_log* th_world_log(const tb_world* w);
/// Asserts no validation message and (unless allowed) no logged warning, then destroys.
void th_world_destroy(tb_world* w);

/// Whether a large scene (a pile of thousands of bodies settling for hundreds of steps) runs
/// in this run: on lavapipe only at one of its vector widths, `width` ("256" or "128"), as
/// the scene tests the solver, not the width (the unit tests cover both); make test runs
/// both widths at once on two cores, so a test file with two large scenes gives each its
/// own width and the two runs take about as long. Without LP_NATIVE_VECTOR_WIDTH, or with
/// TB_ALL_WIDTHS=1, they run at every width. Prints why when not.
int th_large_scene_runs(const char* what, const char* width);

/* ---- deterministic random numbers (xorshift64*) --------------------------------------- */

typedef struct th_rng { uint64_t s; } th_rng;

th_rng th_rng_seed(uint64_t seed);
uint32_t th_rng_u32(th_rng* r);
/// Uniform in [lo, hi).
float th_rng_range(th_rng* r, float lo, float hi);
/// Uniformly distributed unit quaternion (Shoemake).
tb_quat th_rng_quat(th_rng* r);

/* ---- small vector / quaternion math (double precision for references) --------------- */

tb_vec3 th_v3(float x, float y, float z);
tb_quat th_q(float x, float y, float z, float w);
tb_quat th_quat_axis_angle(tb_vec3 axis, double angle);
double th_quat_length(tb_quat q);
/// Rotate v by the unit quaternion q, in double.
void th_quat_rotate(tb_quat q, const double v[3], double out[3]);
/// Rotation angle of a unit quaternion in [0, pi].
double th_quat_angle(tb_quat q);

/* ---- float comparisons ---------------------------------------------------------------- */

/// |a - b| <= abs_tol + rel_tol * max(|a|, |b|); NaN never passes.
int th_near(double a, double b, double abs_tol, double rel_tol);
void th_assert_near_(double a, double b, double abs_tol, double rel_tol, const char* ea,
                     const char* eb, const char* file, int line);
#define th_assert_near(a, b, abs_tol, rel_tol) \
    th_assert_near_((a), (b), (abs_tol), (rel_tol), #a, #b, __FILE__, __LINE__)
/// Componentwise th_assert_near of two tb_vec3.
#define th_assert_vec3_near(a, b, abs_tol, rel_tol) do { \
        tb_vec3 th_a_ = (a), th_b_ = (b); \
        th_assert_near_(th_a_.x, th_b_.x, (abs_tol), (rel_tol), #a ".x", #b ".x", __FILE__, __LINE__); \
        th_assert_near_(th_a_.y, th_b_.y, (abs_tol), (rel_tol), #a ".y", #b ".y", __FILE__, __LINE__); \
        th_assert_near_(th_a_.z, th_b_.z, (abs_tol), (rel_tol), #a ".z", #b ".z", __FILE__, __LINE__); \
    } while (0)
/// Asserts a tb_result equals the expected one, naming both codes on failure.
void th_assert_result_(tb_result got, tb_result want, const char* expr, const char* file,
                       int line);
#define th_assert_result(expr, want) th_assert_result_((expr), (want), #expr, __FILE__, __LINE__)
#define th_assert_ok(expr) th_assert_result_((expr), TB_OK, #expr, __FILE__, __LINE__)

/* ---- object helpers (assert success) -------------------------------------------------- */

tb_shape_id th_sphere(tb_world* w, float radius);
tb_shape_id th_box(tb_world* w, tb_vec3 half_extents);
tb_shape_id th_plane(tb_world* w, tb_vec3 normal, float offset);
/// A small 8-vertex hull, a box of about 0.2 m with its faces moved apart unevenly, so its
/// centre of mass is off the origin of its points.
tb_shape_id th_rock(tb_world* w);
/// tb_default_body_def() with the given shape and position (dynamic).
tb_body_def th_dynamic_def(tb_shape_id shape, tb_vec3 position);
/// As th_dynamic_def, static.
tb_body_def th_static_def(tb_shape_id shape, tb_vec3 position);
tb_body_id th_body(tb_world* w, const tb_body_def* def);
/// A static post at `at` for joints to hang from: a small sphere nothing touches.
tb_body_id th_post(tb_world* w, tb_vec3 at);
/// A def of a joint of `kind` between a and b at the world point `at`, its frames' x axes
/// along `axis` (tb_joint_def_at).
tb_joint_def th_joint_def_at(tb_world* w, tb_joint_kind kind, tb_body_id a, tb_body_id b,
                             tb_vec3 at, tb_vec3 axis);
tb_joint_id th_joint(tb_world* w, const tb_joint_def* def);
/// How far apart a joint's two anchors are, m.
double th_joint_gap(tb_world* w, tb_joint_id joint);
/// Pose of one body through tb_world_read_transforms.
void th_read_pose(tb_world* w, tb_body_id id, tb_vec3* position, tb_quat* rotation);
tb_world_stats th_stats(const tb_world* w);

/* ---- scenes (assert success) ---------------------------------------------------------- */

/// A ball of radius 0.25 m and restitution `restitution` dropped from `drop` m above a floor
/// (the plane y = 0, both made in w), stepped at 60 Hz until it falls again after its first
/// bounce (at most 600 steps): the height of its lowest point at the apex, m. Asserts that it
/// bounced.
double th_bounce_apex(tb_world* w, float restitution, float drop);

#endif
