/* libFuzzer target over the public API: each input is a sequence of calls (shapes from
 * fuzzed sizes, hull point clouds and meshes, bodies from fuzzed defs, poses, velocities,
 * steps, joints between them (made, changed, read and destroyed), reads with fuzzed
 * capacities, snapshots and damaged restores, distance queries,
 * plugins from fuzzed descriptions) on one world that lives for the whole run and is emptied
 * before each input. Built with AddressSanitizer and UBSan (make fuzz); runs on lavapipe
 * with the validation layers on. Besides crashes and sanitizer reports it stops on:
 *   - a failed call that left no message of its own in tb_world_last_error,
 *   - a failed call that changed the world's body or shape count or its step count,
 *   - a validation message, or a live body whose pose is not finite after a step.
 * TUMBLE_FUZZ_TRACE=1 prints every call with its result (to read a failing input).
 * The plugin descriptions reach the loader through tests/fuzz/plugin.c, a plugin whose
 * entry point returns what this file put in its `tb_fuzz_plugin_given`. */
#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tumble.h"
#include "tumble_plugin.h"
#include "describe.h"

#define MAX_SHAPES 32
#define MAX_BODIES 96
#define MAX_JOINTS 32
#define MAX_STEPS_PER_INPUT 4
#define MAX_PLUGINS 4

static tb_world* world;
static char plugin_path[4096];
static const tb_plugin** plugin_given;   /* tests/fuzz/plugin.c's pointer */

/* What this input made: the ids it may name again (and stale ones after destruction). */
static struct {
    tb_shape_id shapes[MAX_SHAPES];
    uint32_t shape_count;
    tb_body_id bodies[MAX_BODIES];
    uint32_t body_count;
    tb_joint_id joints[MAX_JOINTS];
    uint32_t joint_count;
    tb_plugin_id plugins[MAX_PLUGINS];
    fz_plugin_desc* plugin_descs[MAX_PLUGINS];
    uint32_t plugin_count;
    uint32_t steps;
    unsigned char* snapshot;
    size_t snapshot_size;
} made;

static void die(const char* why)
{
    fprintf(stderr, "fuzz_api: %s (last error: %s)\n", why, tb_world_last_error(world));
    abort();
}

/* The log stays quiet: refusals are what the run is made of. Validation messages are
 * counted in the stats, which every call checks. */
static void log_line(void* user, tb_log_level level, const char* message)
{
    (void)user;
    (void)level;
    (void)message;
}

/* ---- the contract every call keeps ------------------------------------------------------ */

typedef struct world_count { uint32_t bodies, shapes, joints; uint64_t steps; } world_count;

static world_count count_world(void)
{
    tb_world_stats st;
    if (tb_world_get_stats(world, &st) != TB_OK) die("tb_world_get_stats failed");
    if (st.validation_messages) die("a validation message");
    return (world_count){ st.body_count, st.shape_count, tb_world_joint_ids(world, NULL, 0),
                          st.steps };
}

/* A call that fails on purpose, so that the next call's message can be told from it. */
static const char* mark_last_error(void)
{
    tb_shape_id none = { 0x7fffffff, 0, 1 };
    if (tb_shape_destroy(world, none) == TB_OK) die("destroying no shape succeeded");
    return tb_world_last_error(world);
}

static char marked[1024];
static world_count before;

static void call_begins(void)
{
    snprintf(marked, sizeof marked, "%s", mark_last_error());
    before = count_world();
}

static int trace;   /* TUMBLE_FUZZ_TRACE=1: each call and its result on stderr */

/* A failed call said why, in a sentence of its own, and changed nothing that counts. */
static tb_result call_ends(tb_result r, const char* call)
{
    if (trace)
        fprintf(stderr, "%s -> %s%s%s\n", call, tb_result_string(r), r ? ": " : "",
                r ? tb_world_last_error(world) : "");
    if (r == TB_OK) return r;
    const char* now = tb_world_last_error(world);
    if (!now || !*now || strcmp(now, marked) == 0) die("a failed call left no message");
    world_count after = count_world();
    int same = after.bodies == before.bodies && after.shapes == before.shapes &&
               after.joints == before.joints && after.steps == before.steps;
    if (r != TB_ERROR_DEVICE && !same) die("a failed call changed the world");
    return r;
}

#define CALL(expr) (call_begins(), call_ends(expr, #expr))

/* ---- ids: mostly what this input made, sometimes a stale or foreign one ------------------ */

static tb_shape_id pick_shape(fz_input* in)
{
    uint8_t b = fz_u8(in);
    if (made.shape_count && b < 240) return made.shapes[b % made.shape_count];
    return (tb_shape_id){ fz_u8(in), (uint16_t)fz_u8(in), (uint16_t)fz_u8(in) };
}

static tb_body_id pick_body(fz_input* in)
{
    uint8_t b = fz_u8(in);
    if (made.body_count && b < 240) return made.bodies[b % made.body_count];
    return (tb_body_id){ fz_u8(in), (uint16_t)fz_u8(in), (uint16_t)fz_u8(in) };
}

static tb_joint_id pick_joint(fz_input* in)
{
    uint8_t b = fz_u8(in);
    if (made.joint_count && b < 240) return made.joints[b % made.joint_count];
    return (tb_joint_id){ fz_u8(in), (uint16_t)fz_u8(in), (uint16_t)fz_u8(in) };
}

static void keep_shape(tb_shape_id id)
{
    if (made.shape_count < MAX_SHAPES) made.shapes[made.shape_count++] = id;
}

static void keep_body(tb_body_id id)
{
    if (made.body_count < MAX_BODIES) made.bodies[made.body_count++] = id;
}

/* ---- joints ------------------------------------------------------------------------------ */

static tb_joint_def joint_def(fz_input* in)
{
    tb_joint_def d = tb_default_joint_def();
    uint8_t which = fz_u8(in);
    d.kind = (tb_joint_kind)(which % 8);
    if (which == 255) d.kind = (tb_joint_kind)fz_u32(in);
    d.body_a = pick_body(in);
    d.body_b = pick_body(in);
    if (fz_u8(in) & 1) {
        (void)tb_joint_def_at(world, &d, fz_point(in), fz_vec3(in));
    } else {
        d.anchor_a = fz_vec3(in);
        d.anchor_b = fz_vec3(in);
    }
    if (which & 8) d.frame_a = fz_rotation(in);
    if (which & 16) {
        d.enable_limit = 1;
        d.lower = fz_float(in);
        d.upper = fz_float(in);
    }
    if (which & 32) {
        d.enable_motor = 1;
        d.motor_speed = fz_float(in);
        d.max_motor_force = fz_float(in);
    }
    if (which & 64) {
        d.enable_spring = 1;
        d.spring_hertz = fz_float(in);
        d.spring_damping_ratio = fz_float(in);
        d.length = fz_float(in);
        d.spring_target = fz_float(in);
    }
    if (d.kind == TB_JOINT_CONE_TWIST && (which & 4)) d.cone_angle = fz_float(in);
    if (which & 2) {
        d.constraint_hertz = fz_float(in);
        d.constraint_damping_ratio = fz_float(in);
    }
    if (d.kind == TB_JOINT_SIX_DOF && (which & 4)) {
        for (int i = 0; i < 6; i++) {
            uint8_t mode = fz_u8(in);
            d.axes[i].mode = (tb_joint_axis_mode)(mode == 255 ? fz_u32(in) : mode % 3u);
            d.axes[i].lower = fz_float(in);
            d.axes[i].upper = fz_float(in);
        }
    }
    if (which & 128) {
        d.break_force = fz_float(in);
        d.break_torque = fz_float(in);
        d.collide_connected = 1;
    }
    if (which == 254) d.internal_cookie = (int32_t)fz_u32(in);
    return d;
}

static void keep_joint(tb_joint_id id)
{
    if (made.joint_count < MAX_JOINTS) made.joints[made.joint_count++] = id;
}

static void make_joints(fz_input* in)
{
    uint32_t count = 1 + fz_u8(in) % 4u;
    tb_joint_def defs[4];
    tb_joint_id ids[4];
    for (uint32_t i = 0; i < count; i++) defs[i] = joint_def(in);
    if (CALL(tb_joint_create_many(world, defs, count, ids)) == TB_OK)
        for (uint32_t i = 0; i < count; i++) keep_joint(ids[i]);
}

/* Change, read or destroy a joint. */
static void use_joint(fz_input* in)
{
    tb_joint_id j = pick_joint(in);
    tb_vec3 f[4], t[4], a[4], b[4];
    int32_t broken[4];
    tb_joint_id ids[4];
    uint32_t count = fz_u8(in) % 5u;
    for (uint32_t i = 0; i < count; i++) ids[i] = pick_joint(in);
    uint8_t nulls = fz_u8(in);
    switch (fz_u8(in) % 6) {
    case 4: CALL(tb_joint_set_spring(world, j, fz_u8(in) & 1, fz_float(in), fz_float(in),
                                     fz_float(in))); break;
    case 0: CALL(tb_joint_set_motor(world, j, fz_u8(in) & 1, fz_float(in), fz_float(in))); break;
    case 1: CALL(tb_joint_set_limit(world, j, fz_u8(in) & 1, fz_float(in), fz_float(in))); break;
    case 2: CALL(tb_joint_read_forces(world, nulls & 8 ? NULL : ids, count, nulls & 1 ? NULL : f,
                                      nulls & 2 ? NULL : t, nulls & 4 ? NULL : broken)); break;
    case 3: CALL(tb_joint_read_anchors(world, nulls & 8 ? NULL : ids, count,
                                       nulls & 1 ? NULL : a, nulls & 2 ? NULL : b)); break;
    default:
        if (CALL(tb_joint_destroy(world, j)) == TB_OK && tb_joint_is_valid(world, j))
            die("a destroyed joint is still valid");
    }
}

/* ---- shapes ------------------------------------------------------------------------------ */

static tb_shape_def shape_def(fz_input* in)
{
    tb_shape_def d = tb_default_shape_def();
    if (fz_u8(in) & 1) d.density = fz_float(in);
    if (fz_u8(in) & 1) d.friction = fz_float(in);
    if (fz_u8(in) & 1) d.restitution = fz_float(in);
    return d;
}

static void make_simple_shape(fz_input* in, uint8_t kind)
{
    tb_shape_def d = shape_def(in);
    tb_shape_id id;
    float a = fz_float(in), b = fz_float(in);
    tb_result r;
    switch (kind % 6) {
    case 0: r = CALL(tb_shape_create_sphere(world, &d, a, &id)); break;
    case 1: r = CALL(tb_shape_create_box(world, &d, fz_vec3(in), &id)); break;
    case 2: r = CALL(tb_shape_create_plane(world, &d, fz_vec3(in), a, &id)); break;
    case 3: r = CALL(tb_shape_create_capsule(world, &d, a, b, &id)); break;
    case 4: r = CALL(tb_shape_create_cylinder(world, &d, a, b, &id)); break;
    default: r = CALL(tb_shape_create_cone(world, &d, a, b, &id)); break;
    }
    if (r == TB_OK) keep_shape(id);
}

static void make_hull(fz_input* in)
{
    uint32_t count = fz_u8(in) + (fz_u8(in) & 1u) * 256u;   /* 0..511 points */
    tb_vec3* points = calloc(count ? count : 1, sizeof *points);
    for (uint32_t i = 0; i < count; i++) points[i] = fz_point(in);
    tb_shape_def d = shape_def(in);
    tb_shape_id id;
    if (CALL(tb_shape_create_hull(world, &d, fz_u8(in) == 0 ? NULL : points, count, &id)) == TB_OK)
        keep_shape(id);
    free(points);
}

static void make_mesh(fz_input* in)
{
    uint32_t vertex_count = fz_u8(in) % 64u, triangle_count = fz_u8(in) % 64u;
    tb_vec3* vertices = calloc(vertex_count + 1, sizeof *vertices);
    uint32_t* indices = calloc(3u * triangle_count + 1, sizeof *indices);
    for (uint32_t i = 0; i < vertex_count; i++) vertices[i] = fz_point(in);
    for (uint32_t i = 0; i < 3 * triangle_count; i++)
        indices[i] = fz_u8(in) < 250 ? fz_u8(in) % (vertex_count + 1) : fz_u32(in);
    tb_shape_def d = shape_def(in);
    tb_shape_id id;
    if (CALL(tb_shape_create_mesh(world, &d, vertices, vertex_count, indices, triangle_count,
                                  &id)) == TB_OK)
        keep_shape(id);
    free(vertices);
    free(indices);
}

static void make_heightfield(fz_input* in)
{
    uint32_t nx = fz_u8(in) % 12u, nz = fz_u8(in) % 12u;
    float* heights = calloc(nx * nz + 1, sizeof *heights);
    uint8_t* holes = calloc(nx * nz + 1, 1);
    for (uint32_t i = 0; i < nx * nz; i++) heights[i] = fz_float(in);
    for (uint32_t i = 0; i < nx * nz; i++) holes[i] = fz_u8(in) > 200;
    tb_shape_def d = shape_def(in);
    tb_shape_id id;
    float cx = fz_float(in), cz = fz_float(in);
    if (CALL(tb_shape_create_heightfield(world, &d, heights, nx, nz, cx, cz,
                                         fz_u8(in) & 1 ? holes : NULL, &id)) == TB_OK)
        keep_shape(id);
    free(heights);
    free(holes);
}

static void make_compound(fz_input* in)
{
    uint32_t count = fz_u8(in) % 70u;
    tb_compound_child* children = calloc(count + 1, sizeof *children);
    for (uint32_t i = 0; i < count; i++)
        children[i] = (tb_compound_child){ pick_shape(in), fz_point(in), fz_rotation(in) };
    tb_shape_id id;
    if (CALL(tb_shape_create_compound(world, children, count, &id)) == TB_OK) keep_shape(id);
    free(children);
}

static void read_shape(fz_input* in)
{
    tb_shape_id s = pick_shape(in);
    float f, g;
    tb_vec3 v;
    tb_shape_type type;
    tb_compound_info ci;
    tb_compound_child children[4];
    uint32_t n;
    switch (fz_u8(in) % 6) {
    case 0: CALL(tb_shape_get_sphere_radius(world, s, fz_u8(in) & 1 ? &f : NULL)); break;
    case 1: CALL(tb_shape_get_box_half_extents(world, s, fz_u8(in) & 1 ? &v : NULL)); break;
    case 2: CALL(tb_shape_get_round_size(world, s, &f, fz_u8(in) & 1 ? &g : NULL)); break;
    case 3: CALL(tb_shape_get_type(world, s, fz_u8(in) & 1 ? &type : NULL)); break;
    case 4: CALL(tb_shape_get_compound_info(world, s, fz_u8(in) & 1 ? &ci : NULL)); break;
    default:
        CALL(tb_shape_get_compound_children(world, s, fz_u8(in) & 1 ? children : NULL,
                                            fz_u8(in) % 5, fz_u8(in) & 1 ? &n : NULL));
    }
}

/* ---- bodies ------------------------------------------------------------------------------ */

static tb_body_def body_def(fz_input* in)
{
    tb_body_def d = tb_default_body_def();
    d.shape = pick_shape(in);
    uint8_t which = fz_u8(in);
    d.type = which & 1 ? TB_BODY_STATIC : TB_BODY_DYNAMIC;
    if (which == 255) d.type = (tb_body_type)fz_u32(in);
    d.position = fz_point(in);
    if (which & 2) d.rotation = fz_rotation(in);
    if (which & 4) d.linear_velocity = fz_vec3(in);
    if (which & 8) d.angular_velocity = fz_vec3(in);
    if (which & 16) d.mass = fz_float(in);
    if (which & 32) d.inertia = fz_vec3(in);
    if (which & 64) {
        d.linear_damping = fz_float(in);
        d.angular_damping = fz_float(in);
        d.gravity_scale = fz_float(in);
    }
    if (which == 254) d.internal_cookie = (int32_t)fz_u32(in);
    return d;
}

static void make_bodies(fz_input* in)
{
    uint32_t count = 1 + fz_u8(in) % 16u;
    tb_body_def defs[16];
    tb_body_id ids[16];
    for (uint32_t i = 0; i < count; i++) defs[i] = body_def(in);
    if (count == 1) {
        if (CALL(tb_body_create(world, &defs[0], fz_u8(in) == 0 ? NULL : ids)) == TB_OK)
            keep_body(ids[0]);
        return;
    }
    if (CALL(tb_body_create_many(world, defs, count, ids)) == TB_OK)
        for (uint32_t i = 0; i < count; i++) keep_body(ids[i]);
}

static void move_body(fz_input* in)
{
    tb_body_id b = pick_body(in);
    switch (fz_u8(in) % 3) {
    case 0: CALL(tb_body_set_pose(world, b, fz_point(in), fz_rotation(in))); break;
    case 1: CALL(tb_body_set_velocity(world, b, fz_vec3(in), fz_vec3(in))); break;
    default: CALL(tb_body_apply_impulse(world, b, fz_vec3(in), fz_point(in))); break;
    }
}

static void read_body(fz_input* in)
{
    tb_body_id b = pick_body(in);
    tb_vec3 p, v, w;
    tb_quat q;
    float m;
    tb_body_type type;
    uint8_t nulls = fz_u8(in);
    switch (fz_u8(in) % 5) {
    case 0: CALL(tb_body_get_pose(world, b, nulls & 1 ? NULL : &p, nulls & 2 ? NULL : &q)); break;
    case 1: CALL(tb_body_get_velocity(world, b, nulls & 1 ? NULL : &v, nulls & 2 ? NULL : &w));
        break;
    case 2: CALL(tb_body_get_mass(world, b, nulls & 1 ? NULL : &m, nulls & 2 ? NULL : &v)); break;
    case 3: CALL(tb_body_get_type(world, b, nulls & 1 ? NULL : &type)); break;
    default: (void)tb_body_get_user_data(world, b); (void)tb_body_is_valid(world, b);
    }
}

static void destroy_something(fz_input* in)
{
    if (fz_u8(in) & 1) CALL(tb_body_destroy(world, pick_body(in)));
    else CALL(tb_shape_destroy(world, pick_shape(in)));
}

/* ---- the world --------------------------------------------------------------------------- */

static void check_poses(void)
{
    tb_body_id ids[MAX_BODIES + 16];
    tb_vec3 p[MAX_BODIES + 16];
    uint32_t n = tb_world_body_ids(world, ids, MAX_BODIES + 16);
    if (n && tb_world_read_transforms(world, ids, n, p, NULL) != TB_OK)
        die("reading the live bodies' poses failed");
    for (uint32_t i = 0; i < n; i++)
        if (!isfinite(p[i].x) || !isfinite(p[i].y) || !isfinite(p[i].z))
            die("a live body's position is not finite");
}

static void step(fz_input* in)
{
    if (made.steps >= MAX_STEPS_PER_INPUT) return;
    float dt = fz_u8(in) < 200 ? 1.0f / 60.0f : fz_float(in);
    uint32_t n = fz_u8(in) % 3u;
    tb_result r = n == 0 ? CALL(tb_world_step(world, dt)) : CALL(tb_world_step_n(world, dt, n));
    made.steps += n ? n : 1;
    if (r == TB_OK) check_poses();
}

static void read_world(fz_input* in)
{
    tb_body_id ids[8];
    tb_vec3 a[8], b[8];
    tb_quat q[8];
    tb_contact contacts[8];
    uint32_t count = fz_u8(in) % 9u, n;
    for (uint32_t i = 0; i < count; i++) ids[i] = pick_body(in);
    uint8_t nulls = fz_u8(in);
    switch (fz_u8(in) % 6) {
    case 0: CALL(tb_world_read_transforms(world, nulls & 4 ? NULL : ids, count,
                                          nulls & 1 ? NULL : a, nulls & 2 ? NULL : q)); break;
    case 1: CALL(tb_world_read_aabbs(world, nulls & 4 ? NULL : ids, count, nulls & 1 ? NULL : a,
                                     nulls & 2 ? NULL : b)); break;
    case 2: CALL(tb_world_read_contacts(world, nulls & 1 ? NULL : contacts, count,
                                        nulls & 2 ? NULL : &n)); break;
    case 3: (void)tb_world_body_ids(world, nulls & 1 ? NULL : ids, count); break;
    case 4: (void)tb_world_isolated_bodies(world, nulls & 1 ? NULL : ids, count); break;
    default: {
        tb_shape_id shapes[8];
        (void)tb_world_shape_ids(world, nulls & 1 ? NULL : shapes, count);
    }
    }
}

static void set_world(fz_input* in)
{
    uint8_t what = fz_u8(in);
    if (what & 1) {
        CALL(tb_world_set_gravity(world, fz_vec3(in)));
        return;
    }
    tb_solver_kind kind = (tb_solver_kind)(fz_u8(in) % 3);
    if (fz_u8(in) == 255) kind = (tb_solver_kind)fz_u32(in);
    CALL(tb_world_set_solver(world, kind, fz_u8(in) < 250 ? fz_u8(in) : fz_u32(in)));
}

static void snapshot_restore(fz_input* in)
{
    size_t size = 0;
    tb_result r = tb_world_snapshot(world, NULL, 0, &size);
    if ((r != TB_OK && r != TB_ERROR_CAPACITY) || size == 0) die("no snapshot size");
    free(made.snapshot);
    made.snapshot = malloc(size);
    made.snapshot_size = size;
    if (CALL(tb_world_snapshot(world, made.snapshot, size, &size)) != TB_OK) return;
    uint32_t damage = fz_u8(in) % 4u;
    for (uint32_t i = 0; i < damage && size; i++)   /* flip a byte, or cut the tail */
        made.snapshot[fz_u32(in) % size] ^= (unsigned char)(1u + fz_u8(in) % 255u);
    size_t given = fz_u8(in) < 230 ? size : fz_u32(in) % (size + 1);
    CALL(tb_world_restore(world, made.snapshot, given));
}

static void query(fz_input* in)
{
    tb_distance_query q[4];
    tb_distance_result out[4];
    uint32_t count = fz_u8(in) % 5u;
    for (uint32_t i = 0; i < count; i++)
        q[i] = (tb_distance_query){ pick_shape(in), pick_shape(in), fz_point(in),
                                    fz_rotation(in), fz_point(in), fz_rotation(in),
                                    (tb_penetration)(fz_u8(in) % 4) };
    CALL(tb_world_query_distances(world, q, count, fz_u8(in) ? out : NULL));
}

/* ---- plugins ----------------------------------------------------------------------------- */

static void load_plugin(fz_input* in)
{
    if (made.plugin_count == MAX_PLUGINS || !plugin_given) return;
    fz_plugin_desc* desc = fz_plugin_desc_make(in, TB_SOURCE_DIR);
    *plugin_given = fz_u8(in) == 0 ? NULL : &desc->plugin;
    tb_plugin_id id;
    if (CALL(tb_world_load_plugin(world, plugin_path, &id)) == TB_OK) {
        made.plugins[made.plugin_count] = id;
        made.plugin_descs[made.plugin_count++] = desc;
    } else {
        fz_plugin_desc_free(desc);
    }
    *plugin_given = NULL;
}

static void plugin_param(fz_input* in)
{
    tb_plugin_id id = made.plugin_count ? made.plugins[fz_u8(in) % made.plugin_count]
                                        : (tb_plugin_id){ fz_u8(in), 0, 1 };
    unsigned char data[300];
    uint32_t size = fz_u8(in) + (fz_u8(in) & 1u) * 44u;
    for (uint32_t i = 0; i < size; i++) data[i] = fz_u8(in);
    CALL(tb_world_set_plugin_param(world, id, fz_u8(in) < 250 ? fz_u8(in) : fz_u32(in),
                                   fz_u8(in) ? data : NULL, size));
}

static void unload_plugins(void)
{
    for (uint32_t i = 0; i < made.plugin_count; i++) {
        if (tb_world_unload_plugin(world, made.plugins[i]) != TB_OK) die("unloading a plugin failed");
        fz_plugin_desc_free(made.plugin_descs[i]);
    }
    made.plugin_count = 0;
}

/* ---- one input --------------------------------------------------------------------------- */

/* The world as the run began: no bodies, no shapes, no plugins, default gravity. (The
 * solver stays the one the first stepping input left: it is chosen before a first step.) */
static void empty_world(void)
{
    unload_plugins();
    tb_body_id ids[256];
    uint32_t n;
    while ((n = tb_world_body_ids(world, ids, 256)) != 0)
        for (uint32_t i = 0; i < n; i++)
            if (tb_body_destroy(world, ids[i]) != TB_OK) die("destroying a live body failed");
    tb_shape_id shapes[256];
    for (int pass = 0; pass < 2; pass++) {   /* compounds first, then their children */
        n = tb_world_shape_ids(world, shapes, 256);
        for (uint32_t i = 0; i < n; i++) (void)tb_shape_destroy(world, shapes[i]);
    }
    if (tb_world_shape_ids(world, shapes, 1) != 0) die("a shape outlived its compound");
    tb_world_def def = tb_default_world_def();
    if (tb_world_set_gravity(world, def.gravity) != TB_OK) die("setting gravity failed");
    free(made.snapshot);
    memset(&made, 0, sizeof made);
}

static void run_call(fz_input* in)
{
    uint8_t op = fz_u8(in);
    switch (op % 16) {
    case 0: make_simple_shape(in, fz_u8(in)); break;
    case 1: make_hull(in); break;
    case 2: make_mesh(in); break;
    case 3: make_heightfield(in); break;
    case 4: make_compound(in); break;
    case 5: read_shape(in); break;
    case 6: case 7: make_bodies(in); break;
    case 8: if (op & 16) move_body(in); else if (op & 32) make_joints(in); else use_joint(in);
        break;
    case 9: read_body(in); break;
    case 10: destroy_something(in); break;
    case 11: step(in); break;
    case 12: read_world(in); break;
    case 13: if (op & 16) set_world(in); else query(in); break;
    case 14: snapshot_restore(in); break;
    default:
        if (op & 16) load_plugin(in);
        else plugin_param(in);
    }
}

int LLVMFuzzerInitialize(int* argc, char*** argv);
int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerInitialize(int* argc, char*** argv)
{
    (void)argc;
    trace = getenv("TUMBLE_FUZZ_TRACE") && strcmp(getenv("TUMBLE_FUZZ_TRACE"), "0") != 0;
    const char* dir = getenv("TUMBLE_FUZZ_PLUGIN");
    snprintf(plugin_path, sizeof plugin_path, "%s", dir ? dir : "");
    void* plugin = plugin_path[0] ? dlopen(plugin_path, RTLD_NOW | RTLD_LOCAL) : NULL;
    if (plugin) plugin_given = (const tb_plugin**)dlsym(plugin, "tb_fuzz_plugin_given");
    if (!plugin_given)
        fprintf(stderr, "fuzz_api: no plugin at TUMBLE_FUZZ_PLUGIN (%s): plugin calls left out\n",
                plugin_path);
    tb_world_def def = tb_default_world_def();
    def.validation = 1;
    def.log = log_line;
    def.initial_body_capacity = 64;
    if (tb_world_create(&def, &world) != TB_OK) {
        fprintf(stderr, "%s: no world: %s\n", (*argv)[0], tb_world_last_error(NULL));
        exit(1);
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    fz_input in = { data, size };
    empty_world();
    for (int calls = 0; calls < 64 && in.size; calls++) run_call(&in);
    return 0;
}
