/* The narrowphase kernel (narrowphase/contacts) driven alone, without the rest of the step.
 *
 * Bodies are made through the public API and uploaded with tb_world_flush; the test owns
 * the other buffers the kernel uses (counters, body_pairs, pairs and manifolds with both
 * halves), writes the pair list and params, records one indirect dispatch and reads the
 * manifolds back.
 *
 * Checks are by property against plain C geometry in double (DESIGN.md §7): the two surface
 * points of every contact point (the point moved by half the separation either way along
 * the normal) lie on the two surfaces; pushing body b along the normal by the deepest
 * penetration leaves the shapes touching, measured by an independent distance or separating
 * axis routine; swapping a and b negates the normal and changes nothing else. Analytic
 * cases pin counts, depths, points and normals; feature keys and the warm start are
 * checked on prepared previous halves.
 */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/world.h"
#include "gpu/graph.h"

#define MARGIN 0.02f
#define GROUP 64u
#define MAX_SLOTS 4096u
#define PI 3.14159265358979
/* Float poses about a metre from the origin: positions are good to ~1e-7 m. */
#define SURFACE_TOL 2e-4
#define EXACT_TOL 2e-5
/* After pushing b out by the deepest penetration, the shapes touch within this... */
#define PUSH_TOL 1e-3
/* ...plus what the kernel may give away on purpose: a face axis is kept unless another
 * axis is clearly better (5 % relative, 0.5 mm absolute, see box_box.glsl). */
#define AXIS_REL_TOL 0.05
#define AXIS_ABS_TOL 5e-4

/* ---- plumbing: the kernel's buffers, one dispatch, read back ---------------------------- */

enum { BUF_COUNTERS, BUF_BODY_PAIRS, BUF_PAIRS, BUF_MANIFOLDS, BUF_PREV_MANIFOLDS, BUF_COUNT };
static const uint32_t rig_binding[BUF_COUNT] = { TB_BIND_COUNTERS, TB_BIND_BODY_PAIRS,
                                                 TB_BIND_PAIRS, TB_BIND_MANIFOLDS,
                                                 TB_BIND_PREV_MANIFOLDS };

typedef struct rig {
    tb_world* w;
    uint32_t cap;                 /* pairs per half */
    VkPipeline pipeline;
    VkCommandBuffer cb;
    tb_buffer dev[BUF_COUNT];     /* device-local, bound to the world's set */
    tb_buffer up, down;           /* host-visible images of the four, back to back */
    /* Host images of the four buffers: uploaded whole by rig_run, read back whole after. */
    tb_gpu_counters counters;
    tb_gpu_uvec4* body_pairs;     /* MAX_SLOTS */
    tb_gpu_uvec4* pairs;          /* 2 * cap; half h starts at h * cap */
    tb_gpu_manifold* manifolds;   /* 2 * cap: the manifolds of each half's pairs; a run
                                     binds its half's as this step's, the other's as last
                                     step's */
    uint32_t made;                /* shapes made, to vary their materials */
} rig;

static VkDeviceSize rig_bytes(const rig* r, int i)
{
    switch (i) {
    case BUF_COUNTERS: return sizeof(tb_gpu_counters);
    case BUF_BODY_PAIRS: return MAX_SLOTS * sizeof(tb_gpu_uvec4);
    case BUF_PAIRS: return 2 * (VkDeviceSize)r->cap * sizeof(tb_gpu_uvec4);
    default: return (VkDeviceSize)r->cap * sizeof(tb_gpu_manifold);
    }
}

static void* rig_host(rig* r, int i, uint32_t parity)
{
    void* host[BUF_COUNT] = { &r->counters, r->body_pairs, r->pairs,
                              r->manifolds + parity * r->cap,
                              r->manifolds + (parity ^ 1u) * r->cap };
    return host[i];
}

static VkDeviceSize rig_offset(const rig* r, int i)
{
    VkDeviceSize offset = 0;
    for (int k = 0; k < i; k++) offset += rig_bytes(r, k);
    return offset;
}

/* A zero-gravity world with the kernel's pipeline and buffers for `cap` pairs a half. */
static rig* rig_create(uint32_t cap)
{
    rig* r = calloc(1, sizeof *r);
    assert_non_null(r);
    tb_world_def wd = tb_default_world_def();
    wd.gravity = th_v3(0, 0, 0);
    r->w = th_world_create(&wd);
    r->cap = cap;
    r->body_pairs = calloc(MAX_SLOTS, sizeof *r->body_pairs);
    r->pairs = calloc(2 * (size_t)cap, sizeof *r->pairs);
    r->manifolds = calloc(2 * (size_t)cap, sizeof *r->manifolds);
    assert_true(r->body_pairs && r->pairs && r->manifolds);
    tb_world* w = r->w;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    for (int i = 0; i < BUF_COUNT; i++) {
        VkBufferUsageFlags extra = i == BUF_COUNTERS ? VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT : 0;
        th_assert_ok(tb_buffer_create(&w->memory, rig_bytes(r, i), usage | extra, 0, &r->dev[i]));
        tb_pipelines_bind(&w->pipelines, rig_binding[i], r->dev[i].buffer);
    }
    tb_graph_invalidate(&w->graph);
    VkDeviceSize total = rig_offset(r, BUF_COUNT);
    th_assert_ok(tb_buffer_create(&w->memory, total, usage, 1, &r->up));
    th_assert_ok(tb_buffer_create(&w->memory, total, usage, 1, &r->down));
    th_assert_ok(tb_pipeline_create(&w->pipelines, "narrowphase/contacts", GROUP, &r->pipeline));
    th_assert_ok(tb_gpu_command_buffer(&w->gpu, &r->cb));
    return r;
}

static void rig_destroy(rig* r)
{
    tb_world* w = r->w;
    vkDeviceWaitIdle(w->gpu.device);
    vkDestroyPipeline(w->gpu.device, r->pipeline, NULL);
    vkFreeCommandBuffers(w->gpu.device, w->gpu.command_pool, 1, &r->cb);
    for (int i = 0; i < BUF_COUNT; i++) tb_buffer_destroy(&w->memory, &r->dev[i]);
    tb_buffer_destroy(&w->memory, &r->up);
    tb_buffer_destroy(&w->memory, &r->down);
    th_world_destroy(w);
    free(r->body_pairs);
    free(r->pairs);
    free(r->manifolds);
    free(r);
}

static void barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkAccessFlags src_access,
                    VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkMemoryBarrier b = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                          .srcAccessMask = src_access, .dstAccessMask = dst_access };
    vkCmdPipelineBarrier(cb, src, dst, 0, 1, &b, 0, NULL, 0, NULL);
}

/* Uploads the host images and params, runs the kernel over the first `count` pairs of half
 * `parity` (counters.state.x is left as the caller set it), and reads the images back. */
static void rig_run(rig* r, uint32_t parity, uint32_t count)
{
    tb_world* w = r->w;
    uint32_t groups = (count + GROUP - 1) / GROUP;
    r->counters.pair_dispatch = (tb_gpu_uvec4){ groups ? groups : 1, 1, 1, 0 };
    r->counters.state.y = parity;
    r->counters.state.z = count;
    th_assert_ok(tb_world_flush(w));
    assert_true(w->store.slots <= MAX_SLOTS);
    tb_gpu_params params = w->params;
    params.counts.x = w->store.slots;
    params.capacity.x = r->cap;
    params.contact.x = MARGIN;
    for (int i = 0; i < BUF_COUNT; i++)
        memcpy((char*)r->up.mapped + rig_offset(r, i), rig_host(r, i, parity), rig_bytes(r, i));

    VkCommandBuffer cb = r->cb;
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT };
    vkBeginCommandBuffer(cb, &begin);
    /* The world's upload and the last run's dispatch and read-back come first. */
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    for (int i = 0; i < BUF_COUNT; i++) {
        VkBufferCopy copy = { rig_offset(r, i), 0, rig_bytes(r, i) };
        vkCmdCopyBuffer(cb, r->up.buffer, r->dev[i].buffer, 1, &copy);
    }
    vkCmdUpdateBuffer(cb, w->params_buffer.buffer, 0, sizeof params, &params);
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_UNIFORM_READ_BIT |
            VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, w->pipelines.layout, 0, 1,
                            &w->pipelines.set, 0, NULL);
    tb_pass pass = { .pipeline = r->pipeline, .rule = TB_DISPATCH_INDIRECT,
                     .indirect = r->dev[BUF_COUNTERS].buffer,
                     .indirect_offset = TB_COUNTERS_PAIR_DISPATCH_OFFSET };
    tb_passes_record(cb, w->pipelines.layout, &pass, 1, w->params_buffer.buffer);
    barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    for (int i = 0; i < BUF_COUNT; i++) {
        VkBufferCopy copy = { 0, rig_offset(r, i), rig_bytes(r, i) };
        vkCmdCopyBuffer(cb, r->dev[i].buffer, r->down.buffer, 1, &copy);
    }
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    vkEndCommandBuffer(cb);
    th_assert_ok(tb_gpu_submit_wait(&w->gpu, &cb, 1));
    for (int i = 0; i < BUF_COUNT; i++)
        memcpy(rig_host(r, i, parity), (const char*)r->down.mapped + rig_offset(r, i), rig_bytes(r, i));
}

static const tb_gpu_manifold* rig_manifold(const rig* r, uint32_t parity, uint32_t i)
{
    return &r->manifolds[parity * r->cap + i];
}

/* ---- bodies and their geometry in double ------------------------------------------------ */

typedef struct obj {
    tb_body_id id;
    uint32_t slot;
    tb_shape_type type;
    double size[3];     /* sphere: radius in [0]; box: half extents */
    double plane[4];    /* plane: unit normal and offset, body frame */
    double pos[3];      /* pose as the GPU has it */
    tb_quat rot;
    float friction, restitution;
} obj;

static const tb_quat identity = { 0, 0, 0, 1 };

static void obj_read_pose(rig* r, obj* o)
{
    tb_vec3 p;
    th_read_pose(r->w, o->id, &p, &o->rot);
    o->pos[0] = p.x;
    o->pos[1] = p.y;
    o->pos[2] = p.z;
}

static void obj_move(rig* r, obj* o, tb_vec3 pos, tb_quat rot)
{
    th_assert_ok(tb_body_set_pose(r->w, o->id, pos, rot));
    obj_read_pose(r, o);
}

/* size: sphere radius in x; box half extents; plane normal in xyz and offset in `offset`.
 * Materials differ from shape to shape so the combination rules are checked everywhere. */
static obj obj_make(rig* r, tb_shape_type type, tb_vec3 size, float offset, tb_vec3 pos,
                    tb_quat rot)
{
    obj o;
    memset(&o, 0, sizeof o);
    o.type = type;
    tb_shape_def sd = tb_default_shape_def();
    sd.friction = 0.2f + 0.1f * (float)(r->made % 7);
    sd.restitution = 0.125f * (float)(r->made % 5);
    r->made++;
    tb_shape_id s;
    if (type == TB_SHAPE_SPHERE) {
        o.size[0] = size.x;
        th_assert_ok(tb_shape_create_sphere(r->w, &sd, size.x, &s));
    } else if (type == TB_SHAPE_BOX) {
        o.size[0] = size.x, o.size[1] = size.y, o.size[2] = size.z;
        th_assert_ok(tb_shape_create_box(r->w, &sd, size, &s));
    } else {
        double n = sqrt((double)size.x * size.x + (double)size.y * size.y + (double)size.z * size.z);
        o.plane[0] = size.x / n, o.plane[1] = size.y / n, o.plane[2] = size.z / n;
        o.plane[3] = offset;
        th_assert_ok(tb_shape_create_plane(r->w, &sd, size, offset, &s));
    }
    tb_body_def d = type == TB_SHAPE_PLANE ? th_static_def(s, pos) : th_dynamic_def(s, pos);
    d.rotation = rot;
    o.id = th_body(r->w, &d);
    o.slot = o.id.index1 - 1;
    o.friction = sd.friction;
    o.restitution = sd.restitution;
    obj_read_pose(r, &o);
    return o;
}

static obj sphere(rig* r, float radius, tb_vec3 pos)
{
    return obj_make(r, TB_SHAPE_SPHERE, th_v3(radius, 0, 0), 0, pos, identity);
}

static obj box(rig* r, tb_vec3 half, tb_vec3 pos, tb_quat rot)
{
    return obj_make(r, TB_SHAPE_BOX, half, 0, pos, rot);
}

static obj plane(rig* r, tb_vec3 normal, float offset, tb_vec3 pos, tb_quat rot)
{
    return obj_make(r, TB_SHAPE_PLANE, normal, offset, pos, rot);
}

/* a * b: rotation b, then a. */
static tb_quat quat_mul(tb_quat a, tb_quat b)
{
    return th_q(a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
                a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dist3(const double a[3], const double b[3])
{
    double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
    return sqrt(dot3(d, d));
}

static void obj_to_world(const obj* o, const double local[3], double out[3])
{
    th_quat_rotate(o->rot, local, out);
    for (int i = 0; i < 3; i++) out[i] += o->pos[i];
}

static void obj_to_local(const obj* o, const double world[3], double out[3])
{
    double d[3] = { world[0] - o->pos[0], world[1] - o->pos[1], world[2] - o->pos[2] };
    th_quat_rotate(th_q(-o->rot.x, -o->rot.y, -o->rot.z, o->rot.w), d, out);
}

static void obj_axis(const obj* o, int i, double out[3])
{
    double e[3] = { i == 0, i == 1, i == 2 };
    th_quat_rotate(o->rot, e, out);
}

/* World half-space {p : dot(n, p) <= offset} of a plane body. */
static void plane_world(const obj* o, double n[3], double* offset)
{
    th_quat_rotate(o->rot, o->plane, n);
    *offset = o->plane[3] + dot3(n, o->pos);
}

static void box_corner(const obj* o, int c, double out[3])
{
    double local[3] = { (c & 1) ? o->size[0] : -o->size[0], (c & 2) ? o->size[1] : -o->size[1],
                        (c & 4) ? o->size[2] : -o->size[2] };
    obj_to_world(o, local, out);
}

/* Signed distance from p to the surface of o: negative inside. */
static double sdf(const obj* o, const double p[3])
{
    if (o->type == TB_SHAPE_SPHERE) return dist3(p, o->pos) - o->size[0];
    if (o->type == TB_SHAPE_PLANE) {
        double n[3], offset;
        plane_world(o, n, &offset);
        return dot3(n, p) - offset;
    }
    double l[3], outside = 0, inside = -INFINITY;
    obj_to_local(o, p, l);
    for (int i = 0; i < 3; i++) {
        double q = fabs(l[i]) - o->size[i];
        outside += q > 0 ? q * q : 0;
        inside = fmax(inside, q);
    }
    return sqrt(outside) + fmin(inside, 0);
}

static double box_radius(const obj* o, const double l[3])
{
    double r = 0, axis[3];
    for (int i = 0; i < 3; i++) {
        obj_axis(o, i, axis);
        r += o->size[i] * fabs(dot3(axis, l));
    }
    return r;
}

/* Largest separation over the 15 axes: the boxes' distance along the best separating axis
 * when apart, minus their smallest penetration depth when overlapping. */
static double sat_box_box(const obj* a, const obj* b)
{
    double axes_a[3][3], axes_b[3][3], d[3], best = -INFINITY;
    for (int i = 0; i < 3; i++) {
        obj_axis(a, i, axes_a[i]);
        obj_axis(b, i, axes_b[i]);
        d[i] = b->pos[i] - a->pos[i];
    }
    for (int k = 0; k < 15; k++) {
        double l[3];
        if (k < 3) memcpy(l, axes_a[k], sizeof l);
        else if (k < 6) memcpy(l, axes_b[k - 3], sizeof l);
        else cross3(axes_a[(k - 6) / 3], axes_b[(k - 6) % 3], l);
        double len = sqrt(dot3(l, l));
        if (len < 1e-6) continue;
        best = fmax(best, (fabs(dot3(d, l)) - box_radius(a, l) - box_radius(b, l)) / len);
    }
    return best;
}

/* Signed separation of two shapes (either order): distance apart, or minus the depth. */
static double separation(const obj* a, const obj* b)
{
    if (a->type > b->type) { const obj* t = a; a = b; b = t; }
    if (a->type == TB_SHAPE_SPHERE) {
        if (b->type == TB_SHAPE_PLANE || b->type == TB_SHAPE_BOX) return sdf(b, a->pos) - a->size[0];
        return dist3(a->pos, b->pos) - a->size[0] - b->size[0];
    }
    if (a->type == TB_SHAPE_BOX && b->type == TB_SHAPE_BOX) return sat_box_box(a, b);
    if (a->type == TB_SHAPE_BOX) {
        double lowest = INFINITY, corner[3];
        for (int c = 0; c < 8; c++) {
            box_corner(a, c, corner);
            lowest = fmin(lowest, sdf(b, corner));
        }
        return lowest;
    }
    return INFINITY; /* two planes */
}

/* ---- manifold checks -------------------------------------------------------------------- */

static uint32_t feature(const tb_gpu_manifold* m, uint32_t k)
{
    const uint32_t f[4] = { m->feature.x, m->feature.y, m->feature.z, m->feature.w };
    return f[k];
}

static float restitution_of(const tb_gpu_manifold* m)
{
    float e;
    memcpy(&e, &m->info.w, sizeof e);
    return e;
}

static void point_of(const tb_gpu_manifold* m, uint32_t k, double p[3])
{
    p[0] = m->point[k].x, p[1] = m->point[k].y, p[2] = m->point[k].z;
}

/* Every property a manifold of (a, b) must have, whatever the configuration. */
static void check_manifold(const tb_gpu_manifold* m, const obj* a, const obj* b, const char* what)
{
    if (m->info.y != a->slot || m->info.z != b->slot)
        fail_msg("%s: manifold of (%u, %u), pair (%u, %u)", what, m->info.y, m->info.z, a->slot, b->slot);
    uint32_t count = m->info.x;
    if (count > TB_MAX_MANIFOLD_POINTS) fail_msg("%s: %u points", what, count);
    th_assert_near(m->normal.w, sqrt((double)a->friction * b->friction), 1e-6, 1e-6);
    th_assert_near(restitution_of(m), fmax(a->restitution, b->restitution), 0, 0);
    if (count == 0) return;
    double n[3] = { m->normal.x, m->normal.y, m->normal.z };
    if (!th_near(sqrt(dot3(n, n)), 1, 1e-5, 0)) fail_msg("%s: normal of length %g", what, sqrt(dot3(n, n)));
    double deepest = INFINITY;
    for (uint32_t k = 0; k < count; k++) {
        double p[3], sep = m->point[k].w, pa[3], pb[3];
        point_of(m, k, p);
        if (!(sep < MARGIN)) fail_msg("%s: point %u separation %g beyond the margin", what, k, sep);
        for (int i = 0; i < 3; i++) {
            pa[i] = p[i] - n[i] * sep * 0.5;
            pb[i] = p[i] + n[i] * sep * 0.5;
        }
        double on_a = sdf(a, pa), on_b = sdf(b, pb);
        if (fabs(on_a) > SURFACE_TOL || fabs(on_b) > SURFACE_TOL)
            fail_msg("%s: point %u (separation %g) off the surfaces: %g from a's, %g from b's",
                     what, k, sep, on_a, on_b);
        /* The point itself is half the separation from each surface, or nearer. */
        if (fabs(sdf(a, p)) > fabs(sep) * 0.5 + SURFACE_TOL ||
            fabs(sdf(b, p)) > fabs(sep) * 0.5 + SURFACE_TOL)
            fail_msg("%s: point %u (separation %g) is %g from a's surface, %g from b's", what,
                     k, sep, sdf(a, p), sdf(b, p));
        deepest = fmin(deepest, sep);
    }
    if (deepest >= 0) return;
    /* Moving b by the deepest penetration along the normal makes them touch. */
    obj moved = *b;
    for (int i = 0; i < 3; i++) moved.pos[i] -= n[i] * deepest;
    double before = separation(a, b), after = separation(a, &moved);
    if (after < -PUSH_TOL || after > PUSH_TOL + AXIS_ABS_TOL + AXIS_REL_TOL * fabs(before))
        fail_msg("%s: separation %g; pushed out by %g along (%g %g %g) it is %g", what, before,
                 -deepest, n[0], n[1], n[2], after);
}

/* The manifold of (b, a) is the manifold of (a, b) with the normal negated, to the bit. */
static void check_swapped(const tb_gpu_manifold* m, const tb_gpu_manifold* s, const char* what)
{
    if (s->info.x != m->info.x || s->info.y != m->info.z || s->info.z != m->info.y ||
        s->info.w != m->info.w || s->normal.w != m->normal.w)
        fail_msg("%s: swapped pair: info (%u %u %u) against (%u %u %u)", what, s->info.x,
                 s->info.y, s->info.z, m->info.x, m->info.y, m->info.z);
    if (m->info.x == 0) return;
    if (s->normal.x != -m->normal.x || s->normal.y != -m->normal.y || s->normal.z != -m->normal.z)
        fail_msg("%s: swapped normal (%g %g %g) against (%g %g %g)", what, s->normal.x,
                 s->normal.y, s->normal.z, m->normal.x, m->normal.y, m->normal.z);
    for (uint32_t k = 0; k < m->info.x; k++)
        if (memcmp(&s->point[k], &m->point[k], sizeof m->point[k]) != 0 || feature(s, k) != feature(m, k))
            fail_msg("%s: swapped pair differs at point %u", what, k);
}

/* The point of m nearest to `want`, which must be within tol of it and separated by sep. */
static void expect_point(const tb_gpu_manifold* m, const double want[3], double sep, double tol,
                         const char* what)
{
    double best = INFINITY;
    uint32_t at = 0;
    for (uint32_t k = 0; k < m->info.x; k++) {
        double p[3];
        point_of(m, k, p);
        if (dist3(p, want) < best) { best = dist3(p, want); at = k; }
    }
    if (best > tol)
        fail_msg("%s: no point near (%g %g %g): nearest %g away", what, want[0], want[1], want[2], best);
    if (!th_near(m->point[at].w, sep, tol, 0))
        fail_msg("%s: point near (%g %g %g) separated by %g, want %g", what, want[0], want[1],
                 want[2], m->point[at].w, sep);
}

static void expect_normal(const tb_gpu_manifold* m, double x, double y, double z, const char* what)
{
    if (!th_near(m->normal.x, x, EXACT_TOL, 0) || !th_near(m->normal.y, y, EXACT_TOL, 0) ||
        !th_near(m->normal.z, z, EXACT_TOL, 0))
        fail_msg("%s: normal (%g %g %g), want (%g %g %g)", what, m->normal.x, m->normal.y,
                 m->normal.z, x, y, z);
}

static void expect_count(const tb_gpu_manifold* m, uint32_t count, const char* what)
{
    if (m->info.x != count) fail_msg("%s: %u points, want %u", what, m->info.x, count);
}

/* A list of pairs, each also swapped: pair i at i, (b, a) at n + i, in half `parity`. */
typedef struct pair_list {
    const obj* a[256];
    const obj* b[256];
    const char* what[256];
    uint32_t n;
} pair_list;

static void pair_add(pair_list* l, const obj* a, const obj* b, const char* what)
{
    assert_true(l->n < 256);
    l->a[l->n] = a;
    l->b[l->n] = b;
    l->what[l->n] = what;
    l->n++;
}

static void set_pair(rig* r, uint32_t parity, uint32_t i, const obj* a, const obj* b)
{
    r->pairs[parity * r->cap + i] = (tb_gpu_uvec4){ a->slot, b->slot, 0x5eedu + i, 0 };
}

/* Runs the list and its swapped copy; checks every manifold's properties and symmetry. */
static void run_pairs(rig* r, const pair_list* l)
{
    assert_true(2 * l->n <= r->cap);
    for (uint32_t i = 0; i < l->n; i++) {
        set_pair(r, 0, i, l->a[i], l->b[i]);
        set_pair(r, 0, l->n + i, l->b[i], l->a[i]);
    }
    rig_run(r, 0, 2 * l->n);
    for (uint32_t i = 0; i < l->n; i++) {
        check_manifold(rig_manifold(r, 0, i), l->a[i], l->b[i], l->what[i]);
        check_manifold(rig_manifold(r, 0, l->n + i), l->b[i], l->a[i], l->what[i]);
        check_swapped(rig_manifold(r, 0, i), rig_manifold(r, 0, l->n + i), l->what[i]);
    }
}

/* ---- analytic cases ----------------------------------------------------------------------- */

static void test_sphere_plane(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj deep = sphere(r, 0.5f, th_v3(1, 0.45f, 2));
    obj near = sphere(r, 0.5f, th_v3(-5, 0.51f, 0));
    obj far = sphere(r, 0.5f, th_v3(5, 0.53f, 0));
    /* A plane body with a pose: turned a quarter about z and lifted, offset 0.25, so its
     * solid side is x >= -0.25. */
    obj wall = plane(r, th_v3(0, 1, 0), 0.25f, th_v3(0, 1, 0), th_quat_axis_angle(th_v3(0, 0, 1), PI / 2));
    obj leaning = sphere(r, 0.5f, th_v3(-0.74f, 1, 0));
    pair_list l = { .n = 0 };
    pair_add(&l, &deep, &ground, "sphere 5 cm into the ground");
    pair_add(&l, &near, &ground, "sphere 1 cm above the ground");
    pair_add(&l, &far, &ground, "sphere 3 cm above the ground");
    pair_add(&l, &leaning, &wall, "sphere against a posed plane");
    run_pairs(r, &l);

    const tb_gpu_manifold* m = rig_manifold(r, 0, 0);
    expect_count(m, 1, "deep");
    expect_normal(m, 0, -1, 0, "deep");
    expect_point(m, (double[3]){ 1, -0.025, 2 }, -0.05, EXACT_TOL, "deep");
    expect_normal(rig_manifold(r, 0, l.n), 0, 1, 0, "deep, plane first");
    assert_int_equal(feature(m, 0), 0);
    m = rig_manifold(r, 0, 1);
    expect_count(m, 1, "near");
    expect_point(m, (double[3]){ -5, 0.005, 0 }, 0.01, EXACT_TOL, "near");
    expect_count(rig_manifold(r, 0, 2), 0, "far");
    m = rig_manifold(r, 0, 3);
    expect_count(m, 1, "wall");
    expect_normal(m, 1, 0, 0, "wall");
    expect_point(m, (double[3]){ -0.245, 1, 0 }, -0.01, EXACT_TOL, "wall");
    rig_destroy(r);
}

static void test_sphere_sphere(void** state)
{
    (void)state;
    rig* r = rig_create(16);
    obj s1 = sphere(r, 0.5f, th_v3(0, 0, 0));
    obj s2 = sphere(r, 0.3f, th_v3(0.6f * 0.77f, 0.8f * 0.77f, 0)); /* 3 cm deep */
    obj s3 = sphere(r, 0.3f, th_v3(0, 0, 0.815f));                   /* 1.5 cm apart */
    obj s4 = sphere(r, 0.3f, th_v3(0, 0, -0.825f));                  /* 2.5 cm apart */
    pair_list l = { .n = 0 };
    pair_add(&l, &s1, &s2, "3 cm deep");
    pair_add(&l, &s1, &s3, "1.5 cm apart");
    pair_add(&l, &s1, &s4, "2.5 cm apart");
    run_pairs(r, &l);
    const tb_gpu_manifold* m = rig_manifold(r, 0, 0);
    expect_count(m, 1, "deep");
    expect_normal(m, 0.6, 0.8, 0, "deep");
    expect_point(m, (double[3]){ 0.6 * 0.485, 0.8 * 0.485, 0 }, -0.03, EXACT_TOL, "deep");
    m = rig_manifold(r, 0, 1);
    expect_count(m, 1, "apart");
    expect_normal(m, 0, 0, 1, "apart");
    expect_point(m, (double[3]){ 0, 0, 0.5075 }, 0.015, EXACT_TOL, "apart");
    expect_count(rig_manifold(r, 0, 2), 0, "beyond the margin");
    rig_destroy(r);
}

/* A sphere of radius 0.2 at box-frame points near a face, an edge, a corner, and inside. */
static void test_sphere_box(void** state)
{
    (void)state;
    static const struct { double centre[3], surface[3], outward[3], sep; const char* what; } cases[] = {
        { { 0.3, 0.68, -0.1 }, { 0.3, 0.5, -0.1 }, { 0, 1, 0 }, -0.02, "face" },
        { { 1.1, 0.6, 0 }, { 1, 0.5, 0 }, { 0.70710678, 0.70710678, 0 }, 0.14142136 - 0.2, "edge" },
        { { 1.1, 0.6, 0.35 }, { 1, 0.5, 0.25 }, { 0.57735027, 0.57735027, 0.57735027 },
          0.17320508 - 0.2, "corner" },
        { { 0.9, 0.1, 0.05 }, { 1, 0.1, 0.05 }, { 1, 0, 0 }, -0.3, "centre inside" },
        { { -0.1, -0.2, -0.45 }, { -0.1, -0.2, -0.25 }, { 0, 0, -1 }, 0.0, "touching" },
        { { 0.2, 0.1, 0.48 }, { 0.2, 0.1, 0.25 }, { 0, 0, 1 }, 0.03, "beyond the margin" },
    };
    const int n = (int)(sizeof cases / sizeof cases[0]);
    rig* r = rig_create(32);
    obj b = box(r, th_v3(1, 0.5f, 0.25f), th_v3(0.5f, -0.2f, 0.3f),
                th_quat_axis_angle(th_v3(1, 2, 3), 0.7));
    obj s[8];
    pair_list l = { .n = 0 };
    for (int i = 0; i < n; i++) {
        double c[3];
        obj_to_world(&b, cases[i].centre, c);
        s[i] = sphere(r, 0.2f, th_v3((float)c[0], (float)c[1], (float)c[2]));
        pair_add(&l, &s[i], &b, cases[i].what);
    }
    run_pairs(r, &l);
    for (int i = 0; i < n; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, (uint32_t)i);
        if (cases[i].sep >= MARGIN) { expect_count(m, 0, cases[i].what); continue; }
        expect_count(m, 1, cases[i].what);
        double mid[3], want[3], normal[3];
        for (int k = 0; k < 3; k++) mid[k] = cases[i].surface[k] + cases[i].outward[k] * cases[i].sep * 0.5;
        obj_to_world(&b, mid, want);
        th_quat_rotate(b.rot, cases[i].outward, normal);
        expect_point(m, want, cases[i].sep, 1e-5, cases[i].what);
        expect_normal(m, -normal[0], -normal[1], -normal[2], cases[i].what);
    }
    rig_destroy(r);
}

/* Features of a manifold, sorted, for comparing sets. */
static void sorted_features(const tb_gpu_manifold* m, uint32_t out[4])
{
    uint32_t n = m->info.x;
    for (uint32_t k = 0; k < n; k++) out[k] = feature(m, k);
    for (uint32_t i = 1; i < n; i++)
        for (uint32_t j = i; j > 0 && out[j - 1] > out[j]; j--) {
            uint32_t t = out[j];
            out[j] = out[j - 1];
            out[j - 1] = t;
        }
}

/* Every corner of `corners` (bit c = corner c) has a point at its depth below the plane. */
static void expect_corners(const tb_gpu_manifold* m, const obj* b, const obj* ground,
                           unsigned corners, const char* what)
{
    uint32_t want[4], n = 0, got[4];
    for (int c = 0; c < 8; c++) {
        if (!(corners & (1u << c))) continue;
        double k[3], depth, mid[3];
        box_corner(b, c, k);
        depth = sdf(ground, k);
        double nrm[3], offset;
        plane_world(ground, nrm, &offset);
        for (int i = 0; i < 3; i++) mid[i] = k[i] - nrm[i] * depth * 0.5;
        expect_point(m, mid, depth, EXACT_TOL, what);
        want[n++] = (uint32_t)c;
    }
    expect_count(m, n, what);
    sorted_features(m, got);
    for (uint32_t k = 0; k < n; k++)
        if (got[k] != want[k]) fail_msg("%s: feature %u is %u, want corner %u", what, k, got[k], want[k]);
}

static void test_box_plane(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    const double s2 = sqrt(0.5);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj flat = box(r, th_v3(0.5f, 0.3f, 0.4f), th_v3(0, 0.29f, 0), identity);
    obj edge = box(r, th_v3(0.5f, 0.3f, 0.4f), th_v3(3, (float)(0.8 * s2 - 0.01), 0),
                   th_quat_axis_angle(th_v3(0, 0, 1), PI / 4));
    obj thin = box(r, th_v3(0.5f, 0.005f, 0.4f), th_v3(-3, 0.002f, 0), identity);
    obj above = box(r, th_v3(0.5f, 0.3f, 0.4f), th_v3(6, 0.33f, 0), identity);
    /* On a corner: a general rotation, lifted so that its lowest corner is 1 cm deep. */
    tb_quat tilt = th_quat_axis_angle(th_v3(1, 0.3f, 0.8f), 0.9);
    obj corner = box(r, th_v3(0.5f, 0.3f, 0.4f), th_v3(0, 0, 5), tilt);
    double lowest = INFINITY, second = INFINITY;
    int low_corner = 0;
    for (int c = 0; c < 8; c++) {
        double k[3];
        box_corner(&corner, c, k);
        if (k[1] < lowest) { second = lowest; lowest = k[1]; low_corner = c; }
        else if (k[1] < second) second = k[1];
    }
    obj_move(r, &corner, th_v3(0, (float)(-lowest - 0.01), 5), tilt);
    assert_true(second - lowest > 0.1); /* exactly one corner within the margin */
    pair_list l = { .n = 0 };
    pair_add(&l, &flat, &ground, "flat");
    pair_add(&l, &edge, &ground, "on an edge");
    pair_add(&l, &corner, &ground, "on a corner");
    pair_add(&l, &thin, &ground, "thin box, all corners within the margin");
    pair_add(&l, &above, &ground, "3 cm above");
    run_pairs(r, &l);
    expect_normal(rig_manifold(r, 0, 0), 0, -1, 0, "flat");
    expect_corners(rig_manifold(r, 0, 0), &flat, &ground, 0x33, "flat");
    th_assert_near(rig_manifold(r, 0, 0)->point[0].w, -0.01, EXACT_TOL, 0);
    expect_corners(rig_manifold(r, 0, 1), &edge, &ground, 0x11, "on an edge");
    expect_corners(rig_manifold(r, 0, 2), &corner, &ground, 1u << low_corner, "on a corner");
    th_assert_near(rig_manifold(r, 0, 2)->point[0].w, -0.01, EXACT_TOL, 0);
    expect_corners(rig_manifold(r, 0, 3), &thin, &ground, 0x33, "thin");
    expect_count(rig_manifold(r, 0, 4), 0, "above");
    rig_destroy(r);
}

/* Points at (x, z) = xz[2k], xz[2k + 1], half the depth below the top face at y = top. */
static void expect_top_points(const tb_gpu_manifold* m, const double* xz, uint32_t n,
                              double top, double depth, const char* what)
{
    expect_count(m, n, what);
    for (uint32_t k = 0; k < n; k++)
        expect_point(m, (double[3]){ xz[2 * k], top + depth * 0.5, xz[2 * k + 1] }, depth, 1e-5, what);
}

static void test_box_on_box(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    const double h = 0.5;
    obj ground = box(r, th_v3(2, 0.5f, 2), th_v3(0, 0, 0), identity);
    tb_quat turn = th_quat_axis_angle(th_v3(0, 1, 0), 0.3);
    obj small = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0.3f, 0.99f, -0.2f), turn);
    /* Equal boxes stacked exactly: the corners meet within rounding. */
    obj base = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(10, 0, 0), identity);
    obj equal = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(10, 0.99f, 0), identity);
    /* Overhanging by 0.6 in x and 0.2 in z: the overlap is [0.1, 0.5] x [-0.3, 0.5]. */
    obj base2 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 0, 10), identity);
    obj over = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0.6f, 0.99f, 10.2f), identity);
    /* Turned by 45 degrees: an octagon of 8 clip points, reduced to 4. */
    obj base3 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 0, 0), identity);
    obj star = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 0.99f, 0),
                   th_quat_axis_angle(th_v3(0, 1, 0), PI / 4));
    obj lifted = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 0, 10), identity);
    obj apart = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 1.025f, 10), turn);
    /* Equal boxes stacked along a turned axis: the corners meet only within rounding. */
    tb_quat skew = th_quat_axis_angle(th_v3(0.3f, 1, 0.2f), 0.9);
    obj base4 = box(r, th_v3(0.4f, 0.3f, 0.7f), th_v3(3.3f, -1.7f, 7.1f), skew);
    double up[3];
    obj_to_world(&base4, (double[3]){ 0, 0.59, 0 }, up);
    obj equal2 = box(r, th_v3(0.4f, 0.3f, 0.7f), th_v3((float)up[0], (float)up[1], (float)up[2]), skew);
    pair_list l = { .n = 0 };
    pair_add(&l, &ground, &small, "small box turned on a large one");
    pair_add(&l, &base, &equal, "equal boxes stacked");
    pair_add(&l, &base2, &over, "overhanging");
    pair_add(&l, &base3, &star, "turned by 45 degrees");
    pair_add(&l, &lifted, &apart, "2.5 cm apart");
    pair_add(&l, &base4, &equal2, "equal boxes stacked, turned");
    run_pairs(r, &l);

    double corners[8];
    for (int c = 0; c < 4; c++) {
        double local[3] = { (c & 1) ? h : -h, -h, (c & 2) ? h : -h }, world[3];
        obj_to_world(&small, local, world);
        corners[2 * c] = world[0], corners[2 * c + 1] = world[2];
    }
    expect_top_points(rig_manifold(r, 0, 0), corners, 4, 0.5, -0.01, "small on large");
    expect_normal(rig_manifold(r, 0, 0), 0, 1, 0, "small on large");
    static const double equal_xz[8] = { 9.5, -0.5, 10.5, -0.5, 9.5, 0.5, 10.5, 0.5 };
    expect_top_points(rig_manifold(r, 0, 1), equal_xz, 4, 0.5, -0.01, "equal");
    static const double over_xz[8] = { 0.1, 9.7, 0.5, 9.7, 0.1, 10.5, 0.5, 10.5 };
    expect_top_points(rig_manifold(r, 0, 2), over_xz, 4, 0.5, -0.01, "overhanging");
    const tb_gpu_manifold* m = rig_manifold(r, 0, 3);
    expect_count(m, 4, "45 degrees");
    for (uint32_t k = 0; k < 4; k++) th_assert_near(m->point[k].w, -0.01, EXACT_TOL, 0);
    expect_count(rig_manifold(r, 0, 4), 0, "apart");
    m = rig_manifold(r, 0, 5);
    expect_count(m, 4, "equal, turned");
    for (int c = 0; c < 4; c++) {
        double local[3] = { (c & 1) ? 0.4 : -0.4, 0.295, (c & 2) ? 0.7 : -0.7 }, want[3];
        obj_to_world(&base4, local, want);
        expect_point(m, want, -0.01, 1e-5, "equal, turned");
        /* each point is an incident corner, not a crossing or a reference corner */
        if ((feature(m, (uint32_t)c) & 0xffu) >= 4)
            fail_msg("equal, turned: point %d has clip feature %u", c, feature(m, (uint32_t)c) & 0xffu);
    }
    rig_destroy(r);
}

/* Two cubes turned into ridges: a's along x on top, b's along z underneath; they cross. */
static void test_crossed_edges(void** state)
{
    (void)state;
    rig* r = rig_create(16);
    const double ridge = 0.5 * sqrt(2.0);
    tb_quat ax = th_quat_axis_angle(th_v3(1, 0, 0), PI / 4), az = th_quat_axis_angle(th_v3(0, 0, 1), PI / 4);
    obj a = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 0, 0), ax);
    obj b = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0.2f, (float)(2 * ridge - 0.02), 0.1f), az);
    obj a2 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(5, 0, 0), ax);
    obj b2 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(5.2f, (float)(2 * ridge + 0.03), 0.1f), az);
    pair_list l = { .n = 0 };
    pair_add(&l, &a, &b, "crossed edges 2 cm deep");
    pair_add(&l, &a2, &b2, "crossed edges 3 cm apart");
    run_pairs(r, &l);
    const tb_gpu_manifold* m = rig_manifold(r, 0, 0);
    expect_count(m, 1, "crossed");
    expect_normal(m, 0, 1, 0, "crossed");
    expect_point(m, (double[3]){ 0.2, b.pos[1] * 0.5, 0 }, -0.02, 1e-5, "crossed");
    assert_true(feature(m, 0) & 0x80000000u); /* an edge-edge key */
    /* Only an edge axis separates these: faces alone would see them overlap. */
    expect_count(rig_manifold(r, 0, 1), 0, "apart");
    rig_destroy(r);
}

static void test_separated(void** state)
{
    (void)state;
    rig* r = rig_create(16);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj wall = plane(r, th_v3(1, 0, 0), 2, th_v3(0, 0, 0), identity);
    tb_quat q = th_quat_axis_angle(th_v3(1, 1, 0), 0.4);
    obj b1 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 3, 0), q);
    obj b2 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 3, 0), q);
    obj s1 = sphere(r, 0.5f, th_v3(0, 0.521f, 0));
    obj s2 = sphere(r, 0.25f, th_v3(0, 0.521f + 0.75f + 0.021f, 0));
    obj hover = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 0.521f, -4), identity);
    obj s3 = sphere(r, 0.25f, th_v3(0.3f, 0.521f + 0.5f + 0.25f + 0.021f, -4));
    /* b2 right of b1 by their radii along x plus 2.1 cm. */
    obj_move(r, &b2, th_v3((float)(box_radius(&b1, (double[3]){ 1, 0, 0 }) * 2 + 0.021), 3, 0), q);
    /* Sunk below the ground (its solid side is y <= 0): deep, the deepest 4 corners. */
    obj sunk = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, -0.521f, 4), identity);
    pair_list l = { .n = 0 };
    pair_add(&l, &b1, &b2, "boxes 2.1 cm apart");
    pair_add(&l, &s1, &ground, "sphere 2.1 cm over the ground");
    pair_add(&l, &s1, &s2, "spheres 2.1 cm apart");
    pair_add(&l, &hover, &ground, "box 2.1 cm over the ground");
    pair_add(&l, &s3, &hover, "sphere 2.1 cm over a box");
    pair_add(&l, &ground, &wall, "two planes");
    pair_add(&l, &sunk, &ground, "box sunk below the ground");
    run_pairs(r, &l);
    for (uint32_t i = 0; i + 1 < l.n; i++) expect_count(rig_manifold(r, 0, i), 0, l.what[i]);
    expect_corners(rig_manifold(r, 0, l.n - 1), &sunk, &ground, 0x33, l.what[l.n - 1]);
    rig_destroy(r);
}

/* ---- random configurations ---------------------------------------------------------------- */

typedef enum kind { BOX_BOX, BOX_STACK, SPHERE_BOX, BOX_PLANE, SPHERE_SPHERE, SPHERE_PLANE, KIND_COUNT } kind;

/* Moves b along `dir` from a's centre (or a plane's origin) until separation(a, b) equals
 * target, by bisection: the separation only grows along the ray. */
static void place_at(obj* b, const obj* a, const double dir[3], double target)
{
    double lo = 0, hi = 1;
    obj t = *b;
    for (int i = 0; i < 3; i++) t.pos[i] = a->pos[i];
    while (separation(a, &t) > target) {
        lo -= 4;
        for (int i = 0; i < 3; i++) t.pos[i] = a->pos[i] + dir[i] * lo;
    }
    for (;;) {
        for (int i = 0; i < 3; i++) t.pos[i] = a->pos[i] + dir[i] * hi;
        if (separation(a, &t) >= target) break;
        hi *= 2;
    }
    for (int it = 0; it < 80; it++) {
        double mid = 0.5 * (lo + hi);
        for (int i = 0; i < 3; i++) t.pos[i] = a->pos[i] + dir[i] * mid;
        if (separation(a, &t) < target) lo = mid; else hi = mid;
    }
    for (int i = 0; i < 3; i++) b->pos[i] = a->pos[i] + dir[i] * hi;
}

static void random_dir(th_rng* g, double out[3])
{
    double len;
    do {
        for (int i = 0; i < 3; i++) out[i] = th_rng_range(g, -1, 1);
        len = sqrt(dot3(out, out));
    } while (len < 0.1 || len > 1);
    for (int i = 0; i < 3; i++) out[i] /= len;
}

/* A pair of kind k from seed: a at a random pose, b at a random rotation, placed along a
 * random direction at a random separation (a quarter of them beyond the margin). */
static void random_pair(rig* r, kind k, uint64_t seed, obj* a, obj* b, double* target)
{
    th_rng g = th_rng_seed(seed);
    tb_vec3 pa = th_v3(th_rng_range(&g, -2, 2), th_rng_range(&g, -2, 2), th_rng_range(&g, -2, 2));
    tb_vec3 ha = th_v3(th_rng_range(&g, 0.1f, 1), th_rng_range(&g, 0.1f, 1), th_rng_range(&g, 0.1f, 1));
    tb_vec3 hb = th_v3(th_rng_range(&g, 0.1f, 1), th_rng_range(&g, 0.1f, 1), th_rng_range(&g, 0.1f, 1));
    tb_quat qa = th_rng_quat(&g), qb = th_rng_quat(&g);
    *target = th_rng_u32(&g) % 4 == 0 ? th_rng_range(&g, MARGIN + 0.005f, 0.3f)
                                      : th_rng_range(&g, -0.04f, 0.015f);
    double dir[3];
    random_dir(&g, dir);
    int a_plane = k == BOX_PLANE || k == SPHERE_PLANE;
    if (a_plane) {
        tb_vec3 n = th_v3((float)dir[0], (float)dir[1], (float)dir[2]);
        *a = plane(r, n, th_rng_range(&g, -0.5f, 0.5f), pa, qa);
        double offset;
        plane_world(a, dir, &offset); /* b leaves the plane along its world normal */
    } else if (k == SPHERE_BOX || k == SPHERE_SPHERE) {
        *a = sphere(r, ha.x, pa);
    } else {
        *a = box(r, ha, pa, qa);
    }
    if (k == BOX_STACK) {
        /* b turned about a face normal of a and tilted by up to 3 degrees, leaving that
         * face off centre: face on face, often overhanging, many clip points. */
        double n[3];
        obj_axis(a, (int)(th_rng_u32(&g) % 3), n);
        if (th_rng_u32(&g) & 1) for (int i = 0; i < 3; i++) n[i] = -n[i];
        tb_quat spin = th_quat_axis_angle(th_v3((float)n[0], (float)n[1], (float)n[2]),
                                          th_rng_range(&g, 0, 6.2831853f));
        tb_quat tilt = th_quat_axis_angle(th_v3((float)dir[0], (float)dir[1], (float)dir[2]),
                                          th_rng_range(&g, 0, 0.05f));
        qb = quat_mul(tilt, quat_mul(spin, a->rot));
        double lateral[3];
        random_dir(&g, lateral);
        for (int i = 0; i < 3; i++) dir[i] = n[i] + 0.4 * lateral[i];
        double len = sqrt(dot3(dir, dir));
        for (int i = 0; i < 3; i++) dir[i] /= len;
    }
    *b = (k == SPHERE_SPHERE || k == SPHERE_PLANE) ? sphere(r, hb.x, pa) : box(r, hb, pa, qb);
    place_at(b, a, dir, *target);
    obj_move(r, b, th_v3((float)b->pos[0], (float)b->pos[1], (float)b->pos[2]), b->rot);
    *target = separation(a, b); /* of the pose as rounded to float */
}

static void check_random(kind k, uint32_t n, uint64_t seed)
{
    static const char* names[KIND_COUNT] = { "box-box", "box on box", "sphere-box", "box-plane",
                                             "sphere-sphere", "sphere-plane" };
    rig* r = rig_create(2 * n);
    obj* a = calloc(n, sizeof *a);
    obj* b = calloc(n, sizeof *b);
    double* target = calloc(n, sizeof *target);
    assert_true(a && b && target);
    pair_list l = { .n = 0 };
    for (uint32_t i = 0; i < n; i++) {
        random_pair(r, k, seed + i, &a[i], &b[i], &target[i]);
        pair_add(&l, &a[i], &b[i], names[k]);
    }
    r->counters.solver.w = 7;
    run_pairs(r, &l);
    uint32_t total = 0, touching = 0;
    for (uint32_t i = 0; i < 2 * n; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i);
        uint32_t j = i % n;
        total += m->info.x;
        if (r->pairs[i].z != 0x5eedu + i) fail_msg("the kernel wrote pair %u's colour", i);
        if (target[j] >= MARGIN && m->info.x != 0)
            fail_msg("%s seed %llu: %g apart, %u points", names[k],
                     (unsigned long long)(seed + j), target[j], m->info.x);
        if (target[j] <= 0 && m->info.x == 0)
            fail_msg("%s seed %llu: %g deep, no points", names[k],
                     (unsigned long long)(seed + j), -target[j]);
        touching += target[j] <= 0;
    }
    assert_true(touching > n / 3);
    assert_int_equal(r->counters.solver.w, 7 + total);
    /* The same input again gives the same bits. */
    size_t bytes = 2 * (size_t)n * sizeof(tb_gpu_manifold);
    tb_gpu_manifold* first = malloc(bytes);
    assert_non_null(first);
    memcpy(first, r->manifolds, bytes);
    memset(r->manifolds, 0, bytes);
    rig_run(r, 0, 2 * n);
    assert_memory_equal(first, r->manifolds, bytes);
    free(first);
    free(a);
    free(b);
    free(target);
    rig_destroy(r);
}

static void test_random_box_box(void** state)
{
    (void)state;
    check_random(BOX_BOX, 128, 1000);
    check_random(BOX_BOX, 128, 5000);
}

static void test_random_box_on_box(void** state)
{
    (void)state;
    check_random(BOX_STACK, 128, 6000);
    check_random(BOX_STACK, 128, 7000);
}

static void test_random_sphere_box(void** state)
{
    (void)state;
    check_random(SPHERE_BOX, 96, 2000);
}

static void test_random_box_plane(void** state)
{
    (void)state;
    check_random(BOX_PLANE, 96, 3000);
}

static void test_random_spheres(void** state)
{
    (void)state;
    check_random(SPHERE_SPHERE, 48, 4000);
    check_random(SPHERE_PLANE, 48, 4500);
}

/* ---- feature keys and warm start ---------------------------------------------------------- */

/* The same contact at two slightly different poses has the same feature keys. */
static void test_feature_keys_stable(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    const double ridge = 0.5 * sqrt(2.0);
    tb_quat nudge = th_quat_axis_angle(th_v3(0.3f, 1, -0.5f), 2e-3);
    tb_quat ax = th_quat_axis_angle(th_v3(1, 0, 0), PI / 4), az = th_quat_axis_angle(th_v3(0, 0, 1), PI / 4);
    tb_quat turn = th_quat_axis_angle(th_v3(0, 1, 0), 0.3);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj o[16];
    int n = 0;
    /* Two copies of four contacts; in the second the upper box is moved by a millimetre or
     * two and turned by 2 mrad about a skew axis. */
    for (int copy = 0; copy < 2; copy++) {
        float dx = copy ? 1.5e-3f : 0, dy = copy ? -1e-3f : 0;
        o[n++] = box(r, th_v3(0.5f, 0.3f, 0.4f), th_v3(dx, 0.29f + dy, 0), identity);
        o[n++] = box(r, th_v3(2, 0.5f, 2), th_v3(20, 0, 0), identity);
        o[n++] = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(20.3f + dx, 0.99f + dy, -0.2f), turn);
        o[n++] = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0, 0, 10), identity);
        o[n++] = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0.6f + dx, 0.99f + dy, 10.2f), identity);
        o[n++] = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 0, 0), ax);
        o[n++] = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-9.8f + dx, (float)(2 * ridge - 0.02) + dy, 0.1f), az);
    }
    for (int i = 7; i < 14; i++) {
        if (i == 8 || i == 10 || i == 12) continue; /* the supports stay */
        obj_move(r, &o[i], th_v3((float)o[i].pos[0], (float)o[i].pos[1], (float)o[i].pos[2]),
                 quat_mul(nudge, o[i].rot));
    }
    pair_list l = { .n = 0 };
    for (int copy = 0; copy < 2; copy++) {
        const obj* c = &o[7 * copy];
        pair_add(&l, &c[0], &ground, "box on the ground");
        pair_add(&l, &c[1], &c[2], "box on a box");
        pair_add(&l, &c[3], &c[4], "overhanging box");
        pair_add(&l, &c[5], &c[6], "crossed edges");
    }
    run_pairs(r, &l);
    static const uint32_t counts[4] = { 4, 4, 4, 1 };
    for (uint32_t i = 0; i < 4; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i), *m2 = rig_manifold(r, 0, 4 + i);
        expect_count(m, counts[i], l.what[i]);
        expect_count(m2, counts[i], l.what[i]);
        uint32_t f[4], f2[4];
        sorted_features(m, f);
        sorted_features(m2, f2);
        for (uint32_t k = 0; k < counts[i]; k++)
            if (f[k] != f2[k]) fail_msg("%s: feature %u is %#x, nudged %#x", l.what[i], k, f[k], f2[k]);
        for (uint32_t k = 1; k < counts[i]; k++)
            if (f[k] == f[k - 1]) fail_msg("%s: two points share feature %#x", l.what[i], f[k]);
    }
    rig_destroy(r);
}

static tb_gpu_vec4 impulse_for(uint32_t feature_key)
{
    float base = (float)(feature_key % 97u) + 1.0f;
    return (tb_gpu_vec4){ base, base + 0.25f, base + 0.5f, 9.0f };
}

/* The previous half (1 - parity) holds pairs (a, decoy1), (a, decoy2), (a, b) as a's run,
 * with manifolds that carry the given features; decoys carry huge impulses. */
static void prepare_previous(rig* r, uint32_t parity, const obj* a, const obj* b,
                             const obj* decoy1, const obj* decoy2, const tb_gpu_manifold* now,
                             uint32_t run_count)
{
    uint32_t prev = parity ^ 1u, first = 5; /* a's run starts at pair 5 of the half */
    tb_gpu_uvec4* owned = &r->body_pairs[a->slot];
    if (prev == 0) { owned->x = first; owned->y = run_count; }
    else { owned->z = first; owned->w = run_count; }
    const obj* others[3] = { decoy1, decoy2, b };
    for (uint32_t i = 0; i < 3; i++) {
        set_pair(r, prev, first + i, a, others[i]);
        tb_gpu_manifold* m = &r->manifolds[prev * r->cap + first + i];
        *m = *now;
        m->info.y = a->slot;
        m->info.z = others[i]->slot;
        /* Points in reverse order: matching must go by key, not by index. */
        uint32_t n = now->info.x;
        uint32_t keys[4] = { 0 };
        for (uint32_t k = 0; k < n; k++) {
            keys[k] = feature(now, n - 1 - k);
            m->point[k] = now->point[n - 1 - k];
        }
        m->feature = (tb_gpu_uvec4){ keys[0], keys[1], keys[2], keys[3] };
        for (uint32_t k = 0; k < n; k++) {
            m->impulse[k] = impulse_for(keys[k]);
            if (i < 2) m->impulse[k].x = 1000.0f;
        }
    }
}

static void expect_impulses(const tb_gpu_manifold* m, int carried, uint32_t except, const char* what)
{
    for (uint32_t k = 0; k < m->info.x; k++) {
        tb_gpu_vec4 want = carried && feature(m, k) != except ? impulse_for(feature(m, k))
                                                                : (tb_gpu_vec4){ 0, 0, 0, 0 };
        want.w = 0; /* the split impulse starts again */
        if (m->impulse[k].x != want.x || m->impulse[k].y != want.y || m->impulse[k].z != want.z ||
            m->impulse[k].w != want.w)
            fail_msg("%s: point %u (feature %#x) impulse (%g %g %g %g), want (%g %g %g %g)", what,
                     k, feature(m, k), m->impulse[k].x, m->impulse[k].y, m->impulse[k].z,
                     m->impulse[k].w, want.x, want.y, want.z, want.w);
    }
}

static void test_warm_start(void** state)
{
    (void)state;
    rig* r = rig_create(16);
    obj a = box(r, th_v3(2, 0.5f, 2), th_v3(0, 0, 0), identity);
    obj b = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(0.3f, 0.99f, -0.2f),
                th_quat_axis_angle(th_v3(0, 1, 0), 0.3));
    obj d1 = sphere(r, 0.5f, th_v3(10, 0, 0)), d2 = sphere(r, 0.5f, th_v3(-10, 0, 0));
    /* First step: nothing to start from. */
    set_pair(r, 0, 0, &a, &b);
    rig_run(r, 0, 1);
    tb_gpu_manifold now = *rig_manifold(r, 0, 0);
    expect_count(&now, 4, "first step");
    expect_impulses(&now, 0, 0, "first step");

    /* Odd step after an even one: the run of a in half 0 (body_pairs x, y). */
    prepare_previous(r, 1, &a, &b, &d1, &d2, &now, 3);
    set_pair(r, 1, 0, &a, &b);
    rig_run(r, 1, 1);
    expect_impulses(rig_manifold(r, 1, 0), 1, ~0u, "odd step");
    /* Even step after an odd one: the run of a in half 1 (body_pairs z, w). */
    memset(&r->body_pairs[a.slot], 0, sizeof r->body_pairs[a.slot]);
    prepare_previous(r, 0, &a, &b, &d1, &d2, &now, 3);
    set_pair(r, 0, 0, &a, &b);
    rig_run(r, 0, 1);
    expect_impulses(rig_manifold(r, 0, 0), 1, ~0u, "even step");
    /* A point whose feature changed and that moved beyond the margin starts from zero; the
     * others still carry over. */
    uint32_t changed = feature(&now, 1);
    tb_gpu_manifold* prev_b = &r->manifolds[1 * r->cap + 5 + 2];
    uint32_t* keys = &prev_b->feature.x;
    uint32_t moved = 0;
    for (uint32_t k = 0; k < 4; k++)
        if (keys[k] == changed) { keys[k] ^= 0x00ff0000u; moved = k; }
    prev_b->point[moved].x += 1.0f;
    rig_run(r, 0, 1);
    expect_impulses(rig_manifold(r, 0, 0), 1, changed, "one feature changed");
    /* A relabelled point in the same place (coinciding corners) takes the impulse of last
     * step's nearest point within the contact margin. */
    prev_b->point[moved].x -= 1.0f;
    rig_run(r, 0, 1);
    expect_impulses(rig_manifold(r, 0, 0), 1, ~0u, "relabelled in place");
    /* The pair outside a's run (count 2 leaves out (a, b)): nothing carries over. */
    r->body_pairs[a.slot].w = 2;
    rig_run(r, 0, 1);
    expect_impulses(rig_manifold(r, 0, 0), 0, 0, "pair not in the run");
    rig_destroy(r);
}

/* ---- dispatch contract -------------------------------------------------------------------- */

static void test_abandoned_step_and_range(void** state)
{
    (void)state;
    rig* r = rig_create(64);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj s[3];
    for (int i = 0; i < 3; i++) {
        s[i] = sphere(r, 0.5f, th_v3((float)i * 2, 0.49f, 0));
        set_pair(r, 1, (uint32_t)i, &s[i], &ground);
    }
    memset(r->manifolds, 0xab, 2 * r->cap * sizeof *r->manifolds);
    tb_gpu_manifold* pattern = malloc(2 * r->cap * sizeof *r->manifolds);
    assert_non_null(pattern);
    memcpy(pattern, r->manifolds, 2 * r->cap * sizeof *r->manifolds);
    /* An abandoned step writes nothing. */
    r->counters.state.x = TB_ABORT_PAIRS;
    r->counters.solver.w = 11;
    rig_run(r, 1, 3);
    assert_memory_equal(pattern, r->manifolds, 2 * r->cap * sizeof *r->manifolds);
    assert_int_equal(r->counters.solver.w, 11);
    /* A live step writes its 3 pairs of half 1, nothing beyond them, nothing in half 0. */
    r->counters.state.x = 0;
    rig_run(r, 1, 3);
    for (uint32_t i = 0; i < 3; i++) {
        expect_count(rig_manifold(r, 1, i), 1, "live step");
        check_manifold(rig_manifold(r, 1, i), &s[i], &ground, "live step");
    }
    size_t manifold_bytes = sizeof(tb_gpu_manifold);
    assert_memory_equal(&pattern[r->cap + 3], rig_manifold(r, 1, 3), (r->cap - 3) * manifold_bytes);
    assert_memory_equal(pattern, r->manifolds, r->cap * manifold_bytes);
    assert_int_equal(r->counters.solver.w, 11 + 3);
    free(pattern);
    rig_destroy(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_plane),
        cmocka_unit_test(test_sphere_sphere),
        cmocka_unit_test(test_sphere_box),
        cmocka_unit_test(test_box_plane),
        cmocka_unit_test(test_box_on_box),
        cmocka_unit_test(test_crossed_edges),
        cmocka_unit_test(test_separated),
        cmocka_unit_test(test_random_box_box),
        cmocka_unit_test(test_random_box_on_box),
        cmocka_unit_test(test_random_sphere_box),
        cmocka_unit_test(test_random_box_plane),
        cmocka_unit_test(test_random_spheres),
        cmocka_unit_test(test_feature_keys_stable),
        cmocka_unit_test(test_warm_start),
        cmocka_unit_test(test_abandoned_step_and_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
