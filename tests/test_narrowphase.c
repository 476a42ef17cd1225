/* The narrowphase's kernels for the shapes without round ones (narrowphase/contacts,
 * hull_sat, then hull_points) driven alone, without the rest of the step.
 *
 * Bodies are made through the public API and uploaded with tb_world_flush; the test owns
 * the other buffers the kernels use (counters, body_pairs, pairs, colour_work and manifolds
 * with both halves), writes the pair list and params, records the kernels' indirect
 * dispatches and reads the manifolds back.
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

#include "world/world.h"
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

enum { BUF_COUNTERS, BUF_BODY_PAIRS, BUF_PAIRS, BUF_MANIFOLDS, BUF_PREV_MANIFOLDS,
       BUF_COLOUR_WORK, BUF_COUNT };
/* The manifolds are no bindings: the kernels find them at the params' addresses. */
static const uint32_t rig_binding[BUF_COUNT] = { TB_BIND_COUNTERS, TB_BIND_BODY_PAIRS,
                                                 TB_BIND_PAIRS, UINT32_MAX, UINT32_MAX,
                                                 TB_BIND_COLOUR_WORK };
/* Most hull and box shapes a rig keeps the geometry of, in double. */
#define HULL_CAP 1024u

/* A convex hull in double, body frame, with the topology conventions of src/geom/hull.h:
 * faces counter-clockwise from outside, edges (v0, v1, left, right). */
#define TH_MAXV 72
#define TH_MAXF 72
#define TH_MAXE 144
#define TH_MAXI 320
typedef struct thull {
    uint32_t nv, nf, ne, ni;
    double v[TH_MAXV][3];
    double plane[TH_MAXF][4];
    uint32_t first[TH_MAXF], count[TH_MAXF];
    uint32_t idx[TH_MAXI];
    uint32_t edge[TH_MAXE][4];
} thull;

typedef struct rig {
    tb_world* w;
    uint32_t cap;                 /* pairs per half */
    VkPipeline pipeline, hull_sat, hull_points;   /* the narrowphase's three passes */
    VkCommandBuffer cb;
    tb_buffer dev[BUF_COUNT];     /* device-local, bound to the world's set or addressed */
    tb_buffer up, down;           /* host-visible images of the four, back to back */
    /* Host images of the four buffers: uploaded whole by rig_run, read back whole after. */
    tb_gpu_counters counters;
    tb_gpu_uvec4* body_pairs;     /* MAX_SLOTS */
    tb_gpu_uvec4* pairs;          /* 2 * cap; half h starts at h * cap */
    uint32_t* colour_work;        /* 2 * cap: contacts lists hull_sat's pairs in it */
    tb_gpu_manifold* manifolds;   /* 2 * cap: the manifolds of each half's pairs; a run
                                     binds its half's as this step's, the other's as last
                                     step's */
    uint32_t made;                /* shapes made, to vary their materials */
    thull* hulls;                 /* HULL_CAP, the geometry of every hull and box shape as
                                     the world built it (body frame) */
    uint32_t hulls_used;
} rig;

static VkDeviceSize rig_bytes(const rig* r, int i)
{
    switch (i) {
    case BUF_COUNTERS: return sizeof(tb_gpu_counters);
    case BUF_BODY_PAIRS: return MAX_SLOTS * sizeof(tb_gpu_uvec4);
    case BUF_PAIRS: return 2 * (VkDeviceSize)r->cap * sizeof(tb_gpu_uvec4);
    case BUF_COLOUR_WORK: return 2 * (VkDeviceSize)r->cap * sizeof(uint32_t);
    default: return (VkDeviceSize)r->cap * sizeof(tb_gpu_manifold);
    }
}

static void* rig_host(rig* r, int i, uint32_t parity)
{
    void* host[BUF_COUNT] = { &r->counters, r->body_pairs, r->pairs,
                              r->manifolds + parity * r->cap,
                              r->manifolds + (parity ^ 1u) * r->cap, r->colour_work };
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
    r->colour_work = calloc(2 * (size_t)cap, sizeof *r->colour_work);
    r->hulls = calloc(HULL_CAP, sizeof *r->hulls);
    assert_true(r->body_pairs && r->pairs && r->manifolds && r->colour_work && r->hulls);
    tb_world* w = r->w;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    for (int i = 0; i < BUF_COUNT; i++) {
        VkBufferUsageFlags extra = i == BUF_COUNTERS ? VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT : 0;
        th_assert_ok(tb_buffer_create(&w->memory, rig_bytes(r, i), usage | extra, 0, &r->dev[i]));
        if (rig_binding[i] != UINT32_MAX)
            tb_pipelines_bind(&w->pipelines, rig_binding[i], r->dev[i].buffer);
    }
    tb_graph_invalidate(&w->graph);
    VkDeviceSize total = rig_offset(r, BUF_COUNT);
    th_assert_ok(tb_buffer_create(&w->memory, total, usage, 1, &r->up));
    th_assert_ok(tb_buffer_create(&w->memory, total, usage, 1, &r->down));
    th_assert_ok(tb_pipeline_create(&w->pipelines, "narrowphase/contacts", GROUP, &r->pipeline));
    th_assert_ok(tb_pipeline_create(&w->pipelines, "narrowphase/hull_sat",
                                    TB_WIDE_WORKGROUP_SIZE, &r->hull_sat));
    th_assert_ok(tb_pipeline_create(&w->pipelines, "narrowphase/hull_points", GROUP,
                                    &r->hull_points));
    th_assert_ok(tb_gpu_command_buffer(&w->gpu, &r->cb));
    return r;
}

static void rig_destroy(rig* r)
{
    tb_world* w = r->w;
    vkDeviceWaitIdle(w->gpu.device);
    tb_pipeline_destroy(&w->pipelines, r->pipeline);
    tb_pipeline_destroy(&w->pipelines, r->hull_sat);
    tb_pipeline_destroy(&w->pipelines, r->hull_points);
    vkFreeCommandBuffers(w->gpu.device, w->gpu.command_pool, 1, &r->cb);
    for (int i = 0; i < BUF_COUNT; i++) tb_buffer_destroy(&w->memory, &r->dev[i]);
    tb_buffer_destroy(&w->memory, &r->up);
    tb_buffer_destroy(&w->memory, &r->down);
    th_world_destroy(w);
    free(r->body_pairs);
    free(r->pairs);
    free(r->manifolds);
    free(r->colour_work);
    free(r->hulls);
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
    uint32_t wide = (count + TB_WIDE_WORKGROUP_SIZE - 1) / TB_WIDE_WORKGROUP_SIZE;
    r->counters.pair_dispatch = (tb_gpu_uvec4){ groups ? groups : 1, 1, 1, 0 };
    r->counters.wide_pair_dispatch = (tb_gpu_uvec4){ wide ? wide : 1, 1, 1, 0 };
    r->counters.hull_sat = (tb_gpu_uvec4){ 0, 0, 0, 0 };
    r->counters.state.y = parity;
    r->counters.state.z = count;
    th_assert_ok(tb_world_flush(w));
    assert_true(w->store.slots <= MAX_SLOTS);
    tb_gpu_params params = w->params;
    params.counts.x = w->store.slots;
    params.capacity.x = r->cap;
    params.contact.x = MARGIN;
    params.contact.w = -1.0f;   /* no contact reuse: the rig checks what the narrowphase finds */
    params.contact_arrays[0] = tb_gpu_addresses(r->dev[BUF_MANIFOLDS].address,
                                                r->dev[BUF_PREV_MANIFOLDS].address);
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
    /* Over every pair (push constant x 0), as a world without round shapes runs them. */
    VkBuffer counters = r->dev[BUF_COUNTERS].buffer;
    tb_pass passes[3] = {
        tb_pass_with_args(r->pipeline, TB_DISPATCH_INDIRECT, counters,
                          TB_COUNTERS_PAIR_DISPATCH_OFFSET, 0, 0, 0),
        tb_pass_with_args(r->hull_sat, TB_DISPATCH_INDIRECT, counters,
                          TB_COUNTERS_WIDE_PAIR_DISPATCH_OFFSET, 0, 0, 0),
        tb_pass_with_args(r->hull_points, TB_DISPATCH_INDIRECT, counters,
                          TB_COUNTERS_PAIR_DISPATCH_OFFSET, 0, 0, 0),
    };
    tb_passes_record(cb, w->pipelines.layout, passes, 3, w->params_buffer.buffer);
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
    const thull* hull;  /* box and hull: the hull data the GPU has, body frame */
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

static void thull_box(thull* h, const double half[3]);
static tb_quat quat_mul(tb_quat a, tb_quat b);
static const thull* rig_take_hull(rig* r, tb_shape_id s);

/* size: sphere radius in x; box half extents; plane normal in xyz and offset in `offset`;
 * a hull's geometry is `shape` (its size is the half extents of its bounding box).
 * Materials differ from shape to shape so the combination rules are checked everywhere. */
static obj obj_make_hull(rig* r, tb_shape_type type, tb_vec3 size, float offset, tb_vec3 pos,
                         tb_quat rot, const thull* shape)
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
        o.hull = rig_take_hull(r, s);
    } else if (type == TB_SHAPE_HULL) {
        /* The hull of the shape's vertices; its body frame is the principal frame, so the
         * pose asked for (of the vertices' frame) becomes that frame's. */
        tb_vec3 points[TH_MAXV];
        for (uint32_t k = 0; k < shape->nv; k++)
            points[k] = th_v3((float)shape->v[k][0], (float)shape->v[k][1], (float)shape->v[k][2]);
        th_assert_ok(tb_shape_create_hull(r->w, &sd, points, shape->nv, &s));
        o.hull = rig_take_hull(r, s);
        tb_hull_info info;
        th_assert_ok(tb_shape_get_hull_info(r->w, s, &info));
        double c[3] = { info.center_of_mass.x, info.center_of_mass.y, info.center_of_mass.z }, rc[3];
        th_quat_rotate(rot, c, rc);
        pos = th_v3(pos.x + (float)rc[0], pos.y + (float)rc[1], pos.z + (float)rc[2]);
        rot = quat_mul(rot, info.principal_axes);
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

static obj obj_make(rig* r, tb_shape_type type, tb_vec3 size, float offset, tb_vec3 pos,
                    tb_quat rot)
{
    return obj_make_hull(r, type, size, offset, pos, rot, NULL);
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

/* ---- hulls in double: construction, upload, distances ------------------------------------ */

static void sub3(const double a[3], const double b[3], double out[3])
{
    for (int i = 0; i < 3; i++) out[i] = a[i] - b[i];
}

static void normalize3(double v[3])
{
    double len = sqrt(dot3(v, v));
    for (int i = 0; i < 3; i++) v[i] /= len;
}

static uint32_t thull_vertex(thull* h, double x, double y, double z)
{
    assert_true(h->nv < TH_MAXV);
    h->v[h->nv][0] = x, h->v[h->nv][1] = y, h->v[h->nv][2] = z;
    return h->nv++;
}

/* A face from its vertices in any order: ordered counter-clockwise seen from outside (the
 * hull's vertex centroid, at the origin once thull_finish ran, is inside). */
static void thull_face(thull* h, const uint32_t* vs, uint32_t n)
{
    assert_true(h->nf < TH_MAXF && h->ni + n <= TH_MAXI && n >= 3);
    double c[3] = { 0, 0, 0 }, centre[3] = { 0, 0, 0 };
    for (uint32_t k = 0; k < n; k++)
        for (int i = 0; i < 3; i++) c[i] += h->v[vs[k]][i] / n;
    for (uint32_t k = 0; k < h->nv; k++)
        for (int i = 0; i < 3; i++) centre[i] += h->v[k][i] / h->nv;
    /* the normal: the largest cross product of two corners about the centroid, outward */
    double e1[3], e2[3], x[3], nrm[3] = { 0, 0, 0 }, out[3];
    sub3(h->v[vs[0]], c, e1);
    for (uint32_t k = 1; k < n; k++) {
        sub3(h->v[vs[k]], c, e2);
        cross3(e1, e2, x);
        if (dot3(x, x) > dot3(nrm, nrm)) memcpy(nrm, x, sizeof x);
    }
    sub3(c, centre, out);
    if (dot3(nrm, out) < 0) for (int i = 0; i < 3; i++) nrm[i] = -nrm[i];
    normalize3(nrm);
    double t1[3], t2[3];
    sub3(h->v[vs[0]], c, t1);
    for (int i = 0; i < 3; i++) t1[i] -= nrm[i] * dot3(t1, nrm);
    normalize3(t1);
    cross3(nrm, t1, t2);
    uint32_t order[TH_MAXV];
    double angle[TH_MAXV];
    for (uint32_t k = 0; k < n; k++) {
        double d[3];
        sub3(h->v[vs[k]], c, d);
        angle[k] = atan2(dot3(d, t2), dot3(d, t1));
        order[k] = vs[k];
        for (uint32_t j = k; j > 0 && angle[j - 1] > angle[j]; j--) {
            double ta = angle[j]; angle[j] = angle[j - 1]; angle[j - 1] = ta;
            uint32_t to = order[j]; order[j] = order[j - 1]; order[j - 1] = to;
        }
    }
    h->first[h->nf] = h->ni;
    h->count[h->nf] = n;
    for (uint32_t k = 0; k < n; k++) h->idx[h->ni++] = order[k];
    h->nf++;
}

/* Face planes (Newell normals, mean offsets) and edges with their left and right faces. */
static void thull_finish(thull* h)
{
    h->ne = 0;
    for (uint32_t f = 0; f < h->nf; f++) {
        double n[3] = { 0, 0, 0 }, d = 0;
        uint32_t cnt = h->count[f];
        for (uint32_t k = 0; k < cnt; k++) {
            const double* a = h->v[h->idx[h->first[f] + k]];
            const double* b = h->v[h->idx[h->first[f] + (k + 1) % cnt]];
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        }
        normalize3(n);
        for (uint32_t k = 0; k < cnt; k++) d += dot3(n, h->v[h->idx[h->first[f] + k]]) / cnt;
        memcpy(h->plane[f], n, sizeof n);
        h->plane[f][3] = d;
        for (uint32_t k = 0; k < cnt; k++) {
            uint32_t a = h->idx[h->first[f] + k], b = h->idx[h->first[f] + (k + 1) % cnt];
            uint32_t e = 0;
            while (e < h->ne && !(h->edge[e][0] == b && h->edge[e][1] == a)) e++;
            if (e < h->ne) { h->edge[e][3] = f; continue; }
            assert_true(h->ne < TH_MAXE);
            h->edge[h->ne][0] = a, h->edge[h->ne][1] = b, h->edge[h->ne][2] = f;
            h->edge[h->ne][3] = ~0u;
            h->ne++;
        }
    }
    for (uint32_t e = 0; e < h->ne; e++) assert_true(h->edge[e][3] != ~0u); /* closed */
}

static void thull_box(thull* h, const double half[3])
{
    memset(h, 0, sizeof *h);
    for (int c = 0; c < 8; c++)
        thull_vertex(h, (c & 1) ? half[0] : -half[0], (c & 2) ? half[1] : -half[1],
                     (c & 4) ? half[2] : -half[2]);
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            uint32_t vs[4], n = 0;
            for (uint32_t c = 0; c < 8; c++)
                if (((c >> axis) & 1u) == (uint32_t)side) vs[n++] = c;
            thull_face(h, vs, 4);
        }
    thull_finish(h);
}

/* Moves the vertices so their centroid is the origin (inside: the body's centre). */
static void thull_centre(thull* h)
{
    double c[3] = { 0, 0, 0 };
    for (uint32_t k = 0; k < h->nv; k++)
        for (int i = 0; i < 3; i++) c[i] += h->v[k][i] / h->nv;
    for (uint32_t k = 0; k < h->nv; k++)
        for (int i = 0; i < 3; i++) h->v[k][i] -= c[i];
}

/* n corners at increasing angles on an ellipse (so the polygon is convex) at height z,
 * scaled by s and moved by (dx, dy). */
static void ring(thull* h, const double* angle, uint32_t n, double rx, double ry, double s,
                 double dx, double dy, double z)
{
    for (uint32_t k = 0; k < n; k++)
        thull_vertex(h, s * rx * cos(angle[k]) + dx, s * ry * sin(angle[k]) + dy, z);
}

static void random_angles(th_rng* g, double* angle, uint32_t n)
{
    /* evenly spread, each jittered by up to a third of the spacing: never coincident */
    double phase = th_rng_range(g, 0, 6.2831853f);
    for (uint32_t k = 0; k < n; k++)
        angle[k] = phase + 2 * PI * (k + th_rng_range(g, -0.33f, 0.33f)) / n;
}

typedef enum hull_family { PRISM, FRUSTUM, BIPYRAMID, FAMILY_BOX, FAMILY_COUNT } hull_family;

/* A convex polyhedron: an n-gon prism or frustum (quads and two n-gons), a bipyramid
 * (2n triangles) or a box, n corners on the ellipse of radii rx, ry, height 2 hz. */
static void thull_make(thull* h, hull_family family, uint32_t n, double rx, double ry, double hz,
                       th_rng* g)
{
    memset(h, 0, sizeof *h);
    if (family == FAMILY_BOX) {
        thull_box(h, (double[3]){ rx, ry, hz });
        return;
    }
    double angle[TH_MAXV];
    random_angles(g, angle, n);
    uint32_t vs[TH_MAXV];
    if (family == BIPYRAMID) {
        ring(h, angle, n, rx, ry, 1, 0, 0, 0);
        uint32_t top = thull_vertex(h, 0.1 * rx, 0, hz), bottom = thull_vertex(h, 0, -0.1 * ry, -hz);
        for (uint32_t k = 0; k < n; k++) {
            uint32_t tri[3] = { k, (k + 1) % n, top };
            thull_face(h, tri, 3);
            tri[2] = bottom;
            thull_face(h, tri, 3);
        }
    } else {
        double s = family == FRUSTUM ? 0.6 : 1, d = family == FRUSTUM ? 0.1 : 0;
        ring(h, angle, n, rx, ry, 1, 0, 0, -hz);
        ring(h, angle, n, rx, ry, s, d * rx, -d * ry, hz);
        for (uint32_t k = 0; k < n; k++) vs[k] = k;
        thull_face(h, vs, n);
        for (uint32_t k = 0; k < n; k++) vs[k] = n + k;
        thull_face(h, vs, n);
        for (uint32_t k = 0; k < n; k++) {
            uint32_t quad[4] = { k, (k + 1) % n, n + (k + 1) % n, n + k };
            thull_face(h, quad, 4);
        }
    }
    thull_centre(h);
    /* faces were ordered around the old centroid, still inside: only the planes move */
    thull_finish(h);
}

static void random_dir(th_rng* g, double out[3]);

/* A rock as games make them: the hull (built by tb_shape_create_hull; only the points are
 * set here) of 20 points on an ellipsoid of semi-axes 0.15-0.3 m, each point's radius
 * jittered by 15 %: some 36 small faces, none much better than its neighbours as an axis. */
static void thull_rock(thull* h, th_rng* g)
{
    memset(h, 0, sizeof *h);
    double axes[3];
    for (int i = 0; i < 3; i++) axes[i] = th_rng_range(g, 0.15f, 0.3f);
    h->nv = 20;
    for (uint32_t k = 0; k < h->nv; k++) {
        double d[3];
        random_dir(g, d);
        double radius = th_rng_range(g, 0.85f, 1.15f);
        for (int i = 0; i < 3; i++) h->v[k][i] = d[i] * axes[i] * radius;
    }
}

static void thull_random(thull* h, th_rng* g)
{
    hull_family family = (hull_family)(th_rng_u32(g) % FAMILY_COUNT);
    uint32_t n = 3 + th_rng_u32(g) % 6;
    thull_make(h, family, n, th_rng_range(g, 0.15f, 0.8f), th_rng_range(g, 0.15f, 0.8f),
               th_rng_range(g, 0.1f, 0.6f), g);
}

/* The hull the world built for shape s (boxes have one too), in double. */
static const thull* rig_take_hull(rig* r, tb_shape_id s)
{
    const tb_hull* h = r->w->shapes[s.index1 - 1].hull;
    assert_non_null(h);
    assert_true(r->hulls_used < HULL_CAP && h->vertex_count <= TH_MAXV && h->face_count <= TH_MAXF &&
                h->edge_count <= TH_MAXE && h->index_count <= TH_MAXI);
    thull* t = &r->hulls[r->hulls_used++];
    memset(t, 0, sizeof *t);
    t->nv = h->vertex_count, t->nf = h->face_count, t->ne = h->edge_count, t->ni = h->index_count;
    for (uint32_t k = 0; k < t->nv; k++)
        for (int i = 0; i < 3; i++) t->v[k][i] = h->vertices[k][i];
    for (uint32_t f = 0; f < t->nf; f++) {
        for (int i = 0; i < 4; i++) t->plane[f][i] = h->planes[f][i];
        t->first[f] = h->faces[f].first;
        t->count[f] = h->faces[f].count;
    }
    for (uint32_t k = 0; k < t->ni; k++) t->idx[k] = h->indices[k];
    for (uint32_t e = 0; e < t->ne; e++) {
        t->edge[e][0] = h->edges[e].v0, t->edge[e][1] = h->edges[e].v1;
        t->edge[e][2] = h->edges[e].left, t->edge[e][3] = h->edges[e].right;
    }
    return t;
}

/* A hull body of the given geometry. */
static obj hull(rig* r, const thull* h, tb_vec3 pos, tb_quat rot)
{
    float half = 0;
    for (uint32_t k = 0; k < h->nv; k++)
        for (int i = 0; i < 3; i++) half = fmaxf(half, (float)fabs(h->v[k][i]));
    return obj_make_hull(r, TB_SHAPE_HULL, th_v3(half, half, half), 0, pos, rot, h);
}

/* Signed distance from a point (body frame) to the hull's surface: inside, the largest
 * face plane distance; outside, the distance to the nearest face or edge point. */
static double thull_sdf(const thull* h, const double p[3])
{
    double inside = -INFINITY;
    for (uint32_t f = 0; f < h->nf; f++) inside = fmax(inside, dot3(h->plane[f], p) - h->plane[f][3]);
    if (inside <= 0) return inside;
    double best = INFINITY;
    for (uint32_t f = 0; f < h->nf; f++) {
        double d = dot3(h->plane[f], p) - h->plane[f][3];
        if (d <= 0) continue;
        double q[3];
        for (int i = 0; i < 3; i++) q[i] = p[i] - h->plane[f][i] * d;
        int in = 1;
        for (uint32_t k = 0; k < h->count[f] && in; k++) {
            const double* a = h->v[h->idx[h->first[f] + k]];
            const double* b = h->v[h->idx[h->first[f] + (k + 1) % h->count[f]]];
            double e[3], x[3], s[3];
            sub3(b, a, e);
            cross3(e, h->plane[f], s);
            sub3(q, a, x);
            in = dot3(s, x) <= 0;
        }
        if (in) best = fmin(best, d);
    }
    for (uint32_t e = 0; e < h->ne; e++) {
        const double* a = h->v[h->edge[e][0]];
        double d[3], x[3], q[3];
        sub3(h->v[h->edge[e][1]], a, d);
        sub3(p, a, x);
        double t = fmin(1, fmax(0, dot3(x, d) / dot3(d, d)));
        for (int i = 0; i < 3; i++) q[i] = a[i] + d[i] * t;
        best = fmin(best, dist3(p, q));
    }
    return best;
}

static void hull_world_vertices(const obj* o, double out[][3])
{
    for (uint32_t k = 0; k < o->hull->nv; k++) obj_to_world(o, o->hull->v[k], out[k]);
}

/* Separation of two vertex sets along unit l, either way round. */
static double sets_apart(const double (*va)[3], uint32_t na, const double (*vb)[3], uint32_t nb,
                         const double l[3])
{
    double lo_a = INFINITY, hi_a = -INFINITY, lo_b = INFINITY, hi_b = -INFINITY;
    for (uint32_t k = 0; k < na; k++) lo_a = fmin(lo_a, dot3(l, va[k])), hi_a = fmax(hi_a, dot3(l, va[k]));
    for (uint32_t k = 0; k < nb; k++) lo_b = fmin(lo_b, dot3(l, vb[k])), hi_b = fmax(hi_b, dot3(l, vb[k]));
    return fmax(lo_b - hi_a, lo_a - hi_b);
}

/* The separating axis test over every face normal and every edge pair, without any
 * pruning: the distance apart along the best axis, or minus the smallest penetration. */
static double sat_hull_hull(const obj* a, const obj* b)
{
    double va[TH_MAXV][3], vb[TH_MAXV][3], best = -INFINITY, l[3];
    hull_world_vertices(a, va);
    hull_world_vertices(b, vb);
    const thull* h[2] = { a->hull, b->hull };
    const obj* o[2] = { a, b };
    for (int s = 0; s < 2; s++)
        for (uint32_t f = 0; f < h[s]->nf; f++) {
            th_quat_rotate(o[s]->rot, h[s]->plane[f], l);
            best = fmax(best, sets_apart((const double (*)[3])va, a->hull->nv,
                                         (const double (*)[3])vb, b->hull->nv, l));
        }
    double (*ea)[3] = malloc(sizeof(double[3]) * a->hull->ne);
    double (*eb)[3] = malloc(sizeof(double[3]) * b->hull->ne);
    assert_true(ea && eb);
    for (uint32_t e = 0; e < a->hull->ne; e++) sub3(va[a->hull->edge[e][1]], va[a->hull->edge[e][0]], ea[e]);
    for (uint32_t e = 0; e < b->hull->ne; e++) sub3(vb[b->hull->edge[e][1]], vb[b->hull->edge[e][0]], eb[e]);
    for (uint32_t i = 0; i < a->hull->ne; i++)
        for (uint32_t j = 0; j < b->hull->ne; j++) {
            cross3(ea[i], eb[j], l);
            double len = sqrt(dot3(l, l));
            if (len < 1e-6 * sqrt(dot3(ea[i], ea[i]) * dot3(eb[j], eb[j]))) continue;
            for (int k = 0; k < 3; k++) l[k] /= len;
            best = fmax(best, sets_apart((const double (*)[3])va, a->hull->nv,
                                         (const double (*)[3])vb, b->hull->nv, l));
        }
    free(ea);
    free(eb);
    return best;
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
    if (o->type == TB_SHAPE_HULL) return thull_sdf(o->hull, l);
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
        if (b->type != TB_SHAPE_SPHERE) return sdf(b, a->pos) - a->size[0];
        return dist3(a->pos, b->pos) - a->size[0] - b->size[0];
    }
    if (a->type == TB_SHAPE_BOX && b->type == TB_SHAPE_BOX) return sat_box_box(a, b);
    if (b->type == TB_SHAPE_HULL && a->type == TB_SHAPE_PLANE) {
        double lowest = INFINITY, v[3];
        for (uint32_t k = 0; k < b->hull->nv; k++) {
            obj_to_world(b, b->hull->v[k], v);
            lowest = fmin(lowest, sdf(a, v));
        }
        return lowest;
    }
    if (b->type == TB_SHAPE_HULL) return sat_hull_hull(a, b);
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
            fail_msg("%s: point %u (separation %g) off the surfaces: %g from a's, %g from b's "
                     "(key %#x, cached axis %#x)", what, k, sep, on_a, on_b, feature(m, k), m->axis.x);
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

typedef enum kind { BOX_BOX, BOX_STACK, SPHERE_BOX, BOX_PLANE, SPHERE_SPHERE, SPHERE_PLANE,
                    HULL_HULL, HULL_STACK, BOX_HULL, SPHERE_HULL, PLANE_HULL, ROCK_ROCK,
                    KIND_COUNT } kind;

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
static void random_hull_pair(rig* r, kind k, th_rng* g, obj* a, obj* b, double* target);

static void random_pair(rig* r, kind k, uint64_t seed, obj* a, obj* b, double* target)
{
    th_rng g = th_rng_seed(seed);
    if (k >= HULL_HULL) {
        random_hull_pair(r, k, &g, a, b, target);
        return;
    }
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
                                             "sphere-sphere", "sphere-plane", "hull-hull",
                                             "hull on hull", "box-hull", "sphere-hull",
                                             "plane-hull", "rock-rock" };
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
        want.w = 0; /* the step's total starts again */
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

/* ---- hulls -------------------------------------------------------------------------------- */

/* The rotation taking unit u onto unit v. */
static tb_quat quat_between(const double u[3], const double v[3])
{
    double c[3], d = dot3(u, v);
    cross3(u, v, c);
    if (d < -0.999999) { /* opposite: half a turn about any perpendicular axis */
        double x[3] = { 1, 0, 0 };
        if (fabs(u[0]) > 0.9) x[0] = 0, x[1] = 1;
        cross3(u, x, c);
        normalize3(c);
        return th_q((float)c[0], (float)c[1], (float)c[2], 0);
    }
    double w = 1 + d, len = sqrt(w * w + dot3(c, c));
    return th_q((float)(c[0] / len), (float)(c[1] / len), (float)(c[2] / len), (float)(w / len));
}

static void random_hull_pair(rig* r, kind k, th_rng* g, obj* a, obj* b, double* target)
{
    tb_vec3 pa = th_v3(th_rng_range(g, -2, 2), th_rng_range(g, -2, 2), th_rng_range(g, -2, 2));
    tb_quat qa = th_rng_quat(g), qb = th_rng_quat(g);
    *target = th_rng_u32(g) % 4 == 0 ? th_rng_range(g, MARGIN + 0.005f, 0.3f)
                                     : th_rng_range(g, -0.04f, 0.015f);
    double dir[3];
    random_dir(g, dir);
    thull ha, hb;
    if (k == ROCK_ROCK) {
        thull_rock(&ha, g);
        thull_rock(&hb, g);
    } else {
        thull_random(&ha, g);
        thull_random(&hb, g);
    }
    if (k == PLANE_HULL) {
        double offset;
        *a = plane(r, th_v3((float)dir[0], (float)dir[1], (float)dir[2]), th_rng_range(g, -0.5f, 0.5f), pa, qa);
        plane_world(a, dir, &offset);
    } else if (k == SPHERE_HULL) {
        *a = sphere(r, th_rng_range(g, 0.1f, 0.8f), pa);
    } else if (k == BOX_HULL) {
        *a = box(r, th_v3(th_rng_range(g, 0.1f, 1), th_rng_range(g, 0.1f, 1), th_rng_range(g, 0.1f, 1)), pa, qa);
    } else {
        *a = hull(r, &ha, pa, qa);
    }
    if (k == HULL_STACK) {
        /* a face of b turned onto a face of a, spun about its normal, tilted by up to 3
         * degrees: face on face, often overhanging, many clip points. */
        double n[3], nb[3];
        th_quat_rotate(a->rot, a->hull->plane[th_rng_u32(g) % a->hull->nf], n);
        memcpy(nb, hb.plane[th_rng_u32(g) % hb.nf], sizeof nb);
        double down[3] = { -n[0], -n[1], -n[2] };
        tb_quat align = quat_between(nb, down);
        tb_quat spin = th_quat_axis_angle(th_v3((float)n[0], (float)n[1], (float)n[2]),
                                          th_rng_range(g, 0, 6.2831853f));
        tb_quat tilt = th_quat_axis_angle(th_v3((float)dir[0], (float)dir[1], (float)dir[2]),
                                          th_rng_range(g, 0, 0.05f));
        qb = quat_mul(tilt, quat_mul(spin, align));
        double lateral[3];
        random_dir(g, lateral);
        for (int i = 0; i < 3; i++) dir[i] = n[i] + 0.4 * lateral[i];
        normalize3(dir);
    }
    *b = hull(r, &hb, pa, qb);
    place_at(b, a, dir, *target);
    obj_move(r, b, th_v3((float)b->pos[0], (float)b->pos[1], (float)b->pos[2]), b->rot);
    *target = separation(a, b);
}

static void test_random_hulls(void** state)
{
    (void)state;
    check_random(HULL_HULL, 64, 11000);
    check_random(HULL_STACK, 64, 12000);
    check_random(BOX_HULL, 64, 13000);
    /* Pressed together past the edge of the best face, many-faced rocks once got no point
     * (the clipped polygon was empty) and sank centimetres into each other in a pile. */
    check_random(ROCK_ROCK, 256, 16000);
}

static void test_random_hull_sphere_plane(void** state)
{
    (void)state;
    check_random(SPHERE_HULL, 64, 14000);
    check_random(PLANE_HULL, 64, 15000);
}

/* A regular n-gon prism, circumradius rad, half height hz, its caps facing +-z. */
static void regular_prism(thull* h, uint32_t n, double rad, double hz)
{
    memset(h, 0, sizeof *h);
    double angle[TH_MAXV];
    for (uint32_t k = 0; k < n; k++) angle[k] = 2 * PI * k / n;
    ring(h, angle, n, rad, rad, 1, 0, 0, -hz);
    ring(h, angle, n, rad, rad, 1, 0, 0, hz);
    uint32_t vs[TH_MAXV];
    for (uint32_t k = 0; k < n; k++) vs[k] = k;
    thull_face(h, vs, n);
    for (uint32_t k = 0; k < n; k++) vs[k] = n + k;
    thull_face(h, vs, n);
    for (uint32_t k = 0; k < n; k++) {
        uint32_t quad[4] = { k, (k + 1) % n, n + (k + 1) % n, n + k };
        thull_face(h, quad, 4);
    }
    thull_finish(h);
}

static uint32_t clip_type(uint32_t key)
{
    return (key >> 10) & 3u;
}

/* Hulls resting face down on hulls: exactly four points at the incident corners. */
static void test_hull_on_hull(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    thull ground_h, cube, wide_h, flat_hex, big_prism;
    thull_box(&ground_h, (double[3]){ 2, 0.5, 2 });
    thull_box(&cube, (double[3]){ 0.5, 0.5, 0.5 });
    thull_box(&wide_h, (double[3]){ 0.5, 0.5, 0.5 });
    regular_prism(&flat_hex, 6, 0.4, 0.2);
    regular_prism(&big_prism, 32, 0.6, 0.3); /* caps of 32 corners: the clipper's limit */
    tb_quat turn = th_quat_axis_angle(th_v3(0, 1, 0), 0.3);
    tb_quat caps_up = th_quat_axis_angle(th_v3(1, 0, 0), PI / 2); /* caps facing -y and +y */
    obj ground = hull(r, &ground_h, th_v3(0, 0, 0), identity);
    obj small = hull(r, &cube, th_v3(0.3f, 0.99f, -0.2f), turn);
    obj base = hull(r, &cube, th_v3(10, 0, 0), identity);
    obj equal = hull(r, &wide_h, th_v3(10, 0.99f, 0), identity);
    obj ground2 = hull(r, &ground_h, th_v3(0, 0, 10), identity);
    obj hex = hull(r, &flat_hex, th_v3(0.2f, 0.69f, 10), quat_mul(turn, caps_up));
    obj ground3 = hull(r, &ground_h, th_v3(10, 0, 10), identity);
    obj disc = hull(r, &big_prism, th_v3(10.1f, 0.79f, 10), caps_up);
    obj block = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-10, 0.99f, 0), turn); /* a box on a hull */
    obj ground4 = hull(r, &ground_h, th_v3(-10, 0, 0), identity);
    obj disc2 = hull(r, &big_prism, th_v3(20, 0, 0), caps_up);              /* cap on cap */
    obj disc3 = hull(r, &big_prism, th_v3(20.05f, 0.59f, 0.1f), quat_mul(turn, caps_up));
    pair_list l = { .n = 0 };
    pair_add(&l, &ground, &small, "cube turned on a slab");
    pair_add(&l, &base, &equal, "equal cubes stacked");
    pair_add(&l, &ground2, &hex, "hexagonal prism on a slab");
    pair_add(&l, &ground3, &disc, "32-gon prism on a slab");
    pair_add(&l, &ground4, &block, "box on a hull slab");
    pair_add(&l, &disc2, &disc3, "32-gon caps, turned");
    run_pairs(r, &l);

    double corners[8];
    for (int c = 0; c < 4; c++) {
        double local[3] = { (c & 1) ? 0.5 : -0.5, -0.5, (c & 2) ? 0.5 : -0.5 }, world[3];
        obj_to_world(&small, local, world);
        corners[2 * c] = world[0], corners[2 * c + 1] = world[2];
    }
    expect_top_points(rig_manifold(r, 0, 0), corners, 4, 0.5, -0.01, "cube on slab");
    expect_normal(rig_manifold(r, 0, 0), 0, 1, 0, "cube on slab");
    for (int c = 0; c < 4; c++) {
        double local[3] = { (c & 1) ? 0.5 : -0.5, -0.5, (c & 2) ? 0.5 : -0.5 }, world[3];
        obj_to_world(&block, local, world);
        corners[2 * c] = world[0], corners[2 * c + 1] = world[2];
    }
    expect_top_points(rig_manifold(r, 0, 4), corners, 4, 0.5, -0.01, "box on hull slab");
    static const double equal_xz[8] = { 9.5, -0.5, 10.5, -0.5, 9.5, 0.5, 10.5, 0.5 };
    const tb_gpu_manifold* m = rig_manifold(r, 0, 1);
    expect_top_points(m, equal_xz, 4, 0.5, -0.01, "equal cubes");
    for (uint32_t k = 0; k < 4; k++) /* corners meet within rounding: incident corners win */
        if (clip_type(feature(m, k)) != 0)
            fail_msg("equal cubes: point %u has clip feature %#x", k, feature(m, k) & 0xfffu);
    for (uint32_t i = 2; i < 4; i++) {
        m = rig_manifold(r, 0, i);
        expect_count(m, 4, l.what[i]);
        expect_normal(m, 0, 1, 0, l.what[i]);
        for (uint32_t k = 0; k < 4; k++) {
            th_assert_near(m->point[k].w, -0.01, EXACT_TOL, 0);
            if (clip_type(feature(m, k)) != 0) fail_msg("%s: point %u is no incident corner", l.what[i], k);
        }
    }
    /* Two 32-gons: a clipped polygon of up to 64 corners, reduced to the 4 spanning most. */
    m = rig_manifold(r, 0, 5);
    expect_count(m, 4, "32-gon caps");
    for (uint32_t k = 0; k < 4; k++) th_assert_near(m->point[k].w, -0.01, EXACT_TOL, 0);
    rig_destroy(r);
}

/* Two cube hulls turned into crossed ridges: one edge-edge point. */
static void test_hull_crossed_edges(void** state)
{
    (void)state;
    rig* r = rig_create(16);
    const double ridge = 0.5 * sqrt(2.0);
    thull cube;
    thull_box(&cube, (double[3]){ 0.5, 0.5, 0.5 });
    tb_quat ax = th_quat_axis_angle(th_v3(1, 0, 0), PI / 4), az = th_quat_axis_angle(th_v3(0, 0, 1), PI / 4);
    obj a = hull(r, &cube, th_v3(0, 0, 0), ax);
    obj b = hull(r, &cube, th_v3(0.2f, (float)(2 * ridge - 0.02), 0.1f), az);
    obj a2 = hull(r, &cube, th_v3(5, 0, 0), ax);
    obj b2 = hull(r, &cube, th_v3(5.2f, (float)(2 * ridge + 0.03), 0.1f), az);
    obj a3 = box(r, th_v3(0.5f, 0.5f, 0.5f), th_v3(-5, 0, 0), ax); /* box under a hull */
    obj b3 = hull(r, &cube, th_v3(-4.8f, (float)(2 * ridge - 0.02), 0.1f), az);
    pair_list l = { .n = 0 };
    pair_add(&l, &a, &b, "crossed hull edges 2 cm deep");
    pair_add(&l, &a2, &b2, "crossed hull edges 3 cm apart");
    pair_add(&l, &a3, &b3, "box edge crossing a hull edge");
    run_pairs(r, &l);
    for (uint32_t i = 0; i < 3; i += 2) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i);
        expect_count(m, 1, l.what[i]);
        expect_normal(m, 0, 1, 0, l.what[i]);
        double x = i == 0 ? 0.2 : -4.8;
        expect_point(m, (double[3]){ x, b.pos[1] * 0.5, 0 }, -0.02, 1e-5, l.what[i]);
        if (!(feature(m, 0) & 0x80000000u)) fail_msg("%s: key %#x is no edge key", l.what[i], feature(m, 0));
    }
    expect_count(rig_manifold(r, 0, 1), 0, "apart");
    /* Only an edge axis separates the second pair, and that is the axis it caches. */
    if (rig_manifold(r, 0, 1)->axis.x >> 30 != 3u)
        fail_msg("apart: cached axis %#x is no edge pair", rig_manifold(r, 0, 1)->axis.x);
    rig_destroy(r);
}

static void test_hull_plane(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    thull cube, hex, tri, bip;
    thull_box(&cube, (double[3]){ 0.5, 0.3, 0.4 });
    regular_prism(&hex, 6, 0.4, 0.2);
    regular_prism(&tri, 3, 0.4, 0.5);
    th_rng g = th_rng_seed(77);
    thull_make(&bip, BIPYRAMID, 5, 0.4, 0.3, 0.5, &g);
    tb_quat caps_up = th_quat_axis_angle(th_v3(1, 0, 0), PI / 2);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj flat = hull(r, &cube, th_v3(0, 0.29f, 0), identity);
    obj hexo = hull(r, &hex, th_v3(3, 0.19f, 0), caps_up);
    /* a triangular prism on a side: that quad's outward normal turned to -y */
    double side[3];
    memcpy(side, tri.plane[2], sizeof side);
    tb_quat lay = quat_between(side, (double[3]){ 0, -1, 0 });
    obj trio = hull(r, &tri, th_v3(-3, 0, 0), lay);
    /* a bipyramid on its lowest vertex, 1 cm deep */
    tb_quat tilt = quat_mul(th_quat_axis_angle(th_v3(0.3f, 0, 1), 0.2),
                            th_quat_axis_angle(th_v3(1, 0, 0), -PI / 2)); /* apex down */
    obj bipo = hull(r, &bip, th_v3(0, 0, 5), tilt);
    double lowest[2] = { INFINITY, INFINITY };
    for (uint32_t k = 0; k < bipo.hull->nv; k++) {
        double w[3];
        obj_to_world(&bipo, bipo.hull->v[k], w);
        if (w[1] < lowest[0]) lowest[1] = lowest[0], lowest[0] = w[1];
        else if (w[1] < lowest[1]) lowest[1] = w[1];
    }
    assert_true(lowest[1] - lowest[0] > 0.1);
    /* moved (not turned: its body frame is the principal frame) until 1 cm deep */
    obj_move(r, &bipo, th_v3((float)bipo.pos[0], (float)(bipo.pos[1] - lowest[0] - 0.01),
                             (float)bipo.pos[2]), bipo.rot);
    double low = INFINITY;
    for (uint32_t k = 0; k < trio.hull->nv; k++) {
        double w[3];
        obj_to_world(&trio, trio.hull->v[k], w);
        low = fmin(low, w[1]);
    }
    obj_move(r, &trio, th_v3((float)trio.pos[0], (float)(trio.pos[1] - low - 0.01),
                             (float)trio.pos[2]), trio.rot);
    pair_list l = { .n = 0 };
    pair_add(&l, &ground, &flat, "box hull flat");
    pair_add(&l, &ground, &hexo, "hexagonal prism on its cap");
    pair_add(&l, &ground, &trio, "triangular prism on a side");
    pair_add(&l, &ground, &bipo, "bipyramid on a vertex");
    run_pairs(r, &l);
    static const uint32_t counts[4] = { 4, 4, 4, 1 };
    const obj* bodies[4] = { &flat, &hexo, &trio, &bipo };
    for (uint32_t i = 0; i < 4; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i);
        expect_count(m, counts[i], l.what[i]);
        expect_normal(m, 0, 1, 0, l.what[i]);
        for (uint32_t k = 0; k < m->info.x; k++) {
            /* each point is a vertex of the hull (its key), 1 cm deep, half way up */
            uint32_t v = feature(m, k);
            assert_true(v < bodies[i]->hull->nv);
            double w[3];
            obj_to_world(bodies[i], bodies[i]->hull->v[v], w);
            w[1] -= 0.5 * w[1];
            expect_point(m, w, -0.01, 2e-5, l.what[i]);
        }
    }
    rig_destroy(r);
}

/* A sphere of radius 0.2 at hull-frame points near a face, an edge, a vertex, and inside;
 * the hull is the box of test_sphere_box, so the answers are the same. */
static void test_hull_sphere(void** state)
{
    (void)state;
    static const struct { double centre[3], surface[3], outward[3], sep; const char* what; } cases[] = {
        { { 0.3, 0.68, -0.1 }, { 0.3, 0.5, -0.1 }, { 0, 1, 0 }, -0.02, "face" },
        { { 1.1, 0.6, 0 }, { 1, 0.5, 0 }, { 0.70710678, 0.70710678, 0 }, 0.14142136 - 0.2, "edge" },
        { { 1.1, 0.6, 0.35 }, { 1, 0.5, 0.25 }, { 0.57735027, 0.57735027, 0.57735027 },
          0.17320508 - 0.2, "vertex" },
        { { 0.9, 0.1, 0.05 }, { 1, 0.1, 0.05 }, { 1, 0, 0 }, -0.3, "centre inside" },
        { { -0.1, -0.2, -0.45 }, { -0.1, -0.2, -0.25 }, { 0, 0, -1 }, 0.0, "touching" },
        { { 0.2, 0.1, 0.48 }, { 0.2, 0.1, 0.25 }, { 0, 0, 1 }, 0.03, "beyond the margin" },
        { { 1.3, 0.8, 0.55 }, { 1, 0.5, 0.25 }, { 0.57735027, 0.57735027, 0.57735027 },
          0.51961524 - 0.2, "far beyond a vertex" },
    };
    const int n = (int)(sizeof cases / sizeof cases[0]);
    rig* r = rig_create(32);
    thull slab;
    thull_box(&slab, (double[3]){ 1, 0.5, 0.25 });
    obj b = hull(r, &slab, th_v3(0.5f, -0.2f, 0.3f), th_quat_axis_angle(th_v3(1, 2, 3), 0.7));
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

/* A box against a hull goes through the box's hull data; against the same geometry as a
 * box it takes box_box's path. Both must agree. */
static void check_box_hull_like_box_box(kind k, uint32_t n, uint64_t seed)
{
    rig* r = rig_create(2 * n);
    obj* a = calloc(n, sizeof *a);
    obj* b = calloc(n, sizeof *b);
    obj* hb = calloc(n, sizeof *hb);
    assert_true(a && b && hb);
    pair_list l = { .n = 0 };
    for (uint32_t i = 0; i < n; i++) {
        double target;
        random_pair(r, k, seed + i, &a[i], &b[i], &target);
        hb[i] = hull(r, b[i].hull, th_v3((float)b[i].pos[0], (float)b[i].pos[1], (float)b[i].pos[2]), b[i].rot);
    }
    for (uint32_t i = 0; i < n; i++) pair_add(&l, &a[i], &b[i], "box-box");
    set_pair(r, 0, 0, &a[0], &b[0]);
    for (uint32_t i = 0; i < n; i++) {
        set_pair(r, 0, i, &a[i], &b[i]);
        set_pair(r, 0, n + i, &a[i], &hb[i]);
    }
    rig_run(r, 0, 2 * n);
    uint32_t touching = 0;
    for (uint32_t i = 0; i < n; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i), *h = rig_manifold(r, 0, n + i);
        check_manifold(h, &a[i], &hb[i], "box-hull");
        if (m->info.x != h->info.x)
            fail_msg("seed %llu: box-box %u points, box-hull %u", (unsigned long long)(seed + i),
                     m->info.x, h->info.x);
        if (m->info.x == 0) continue;
        touching++;
        if (!th_near(m->normal.x, h->normal.x, 1e-4, 0) || !th_near(m->normal.y, h->normal.y, 1e-4, 0) ||
            !th_near(m->normal.z, h->normal.z, 1e-4, 0))
            fail_msg("seed %llu: normals (%g %g %g) and (%g %g %g)", (unsigned long long)(seed + i),
                     m->normal.x, m->normal.y, m->normal.z, h->normal.x, h->normal.y, h->normal.z);
        float dm = INFINITY, dh = INFINITY;
        for (uint32_t p = 0; p < m->info.x; p++) dm = fminf(dm, m->point[p].w), dh = fminf(dh, h->point[p].w);
        if (!th_near(dm, dh, 1e-4, 0))
            fail_msg("seed %llu: deepest %g and %g", (unsigned long long)(seed + i), dm, dh);
    }
    assert_true(touching > n / 3);
    free(a);
    free(b);
    free(hb);
    rig_destroy(r);
}

static void test_box_hull_like_box_box(void** state)
{
    (void)state;
    check_box_hull_like_box_box(BOX_BOX, 96, 1000);
    check_box_hull_like_box_box(BOX_STACK, 96, 6000);
}

static uint32_t axis_code(uint32_t type, uint32_t i, uint32_t j)
{
    return type << 30 | i << 15 | j;
}

/* Pairs (a[i], b[i]) at i of half `parity`; last step's manifolds are those of the other
 * half at the same index when `warm`, else there are none. */
static void run_single(rig* r, uint32_t parity, const obj* a, const obj* b, uint32_t n, int warm)
{
    for (uint32_t i = 0; i < n; i++) {
        set_pair(r, parity, i, &a[i], &b[i]);
        set_pair(r, parity ^ 1u, i, &a[i], &b[i]);
        tb_gpu_uvec4* owned = &r->body_pairs[a[i].slot];
        *owned = (tb_gpu_uvec4){ 0, 0, 0, 0 };
        if (!warm) continue;
        if (parity == 1) owned->x = i, owned->y = 1;
        else owned->z = i, owned->w = 1;
    }
    rig_run(r, parity, n);
}

static int same_contact(const tb_gpu_manifold* x, const tb_gpu_manifold* y)
{
    return x->info.x == y->info.x && memcmp(&x->normal, &y->normal, sizeof x->normal) == 0 &&
           memcmp(x->point, y->point, sizeof x->point) == 0 &&
           memcmp(&x->feature, &y->feature, sizeof x->feature) == 0;
}

/* The cached axis: separated pairs stay separated at the cost of one axis, pairs that come
 * into contact get their points, and no cached axis, however wrong, hides a contact. */
static void test_hull_cached_axis(void** state)
{
    (void)state;
    const uint32_t n = 64;
    rig* r = rig_create(256);
    obj a[256], b[256];
    double target[256];
    uint32_t separated = 0;
    for (uint32_t i = 0; i < n; i++) {
        random_pair(r, i % 2 ? HULL_HULL : BOX_HULL, 21000 + i, &a[i], &b[i], &target[i]);
        separated += target[i] >= MARGIN;
    }
    assert_true(separated > 4);
    run_single(r, 0, a, b, n, 0);
    for (uint32_t i = 0; i < n; i++) {
        const tb_gpu_manifold* m = rig_manifold(r, 0, i);
        float sep;
        memcpy(&sep, &m->axis.y, sizeof sep);
        if (m->axis.x == 0) fail_msg("pair %u: no axis cached", i);
        if ((m->info.x == 0) != (sep >= MARGIN))
            fail_msg("pair %u: %u points, cached axis %#x separates by %g", i, m->info.x, m->axis.x, sep);
        if (target[i] >= MARGIN && !th_near(sep, target[i], 1e-4, 0) && sep > target[i])
            fail_msg("pair %u: cached separation %g beyond the true %g", i, sep, target[i]);
    }
    /* The next step from the same poses: the same manifolds, cached axis and all. */
    run_single(r, 1, a, b, n, 1);
    for (uint32_t i = 0; i < n; i++) {
        const tb_gpu_manifold* m0 = rig_manifold(r, 0, i), *m1 = rig_manifold(r, 1, i);
        if (!same_contact(m0, m1) || m0->axis.x != m1->axis.x || m0->axis.y != m1->axis.y)
            fail_msg("pair %u: the warm step changed the manifold", i);
    }
    /* Every separated pair moved into contact along its direction: points despite the
     * cached separating axis, the same as without any cache. */
    for (uint32_t i = 0; i < n; i++) {
        if (target[i] < MARGIN) continue;
        double dir[3];
        sub3(b[i].pos, a[i].pos, dir);
        normalize3(dir);
        obj moved = b[i];
        place_at(&moved, &a[i], dir, -0.01);
        obj_move(r, &b[i], th_v3((float)moved.pos[0], (float)moved.pos[1], (float)moved.pos[2]), b[i].rot);
    }
    run_single(r, 0, a, b, n, 1);
    tb_gpu_manifold cached[256];
    memcpy(cached, rig_manifold(r, 0, 0), n * sizeof *cached);
    run_single(r, 0, a, b, n, 0);
    for (uint32_t i = 0; i < n; i++) {
        if (target[i] >= MARGIN && cached[i].info.x == 0) fail_msg("pair %u: the cache hid a contact", i);
        if (!same_contact(&cached[i], rig_manifold(r, 0, i)))
            fail_msg("pair %u: with and without the cache the manifolds differ", i);
        check_manifold(&cached[i], &a[i], &b[i], "moved into contact");
    }

    /* Forged caches: copies of a touching pair, each with last step's axis set to one face
     * of a, of b, or one edge pair (Minkowski face or not), or out of range. */
    rig_destroy(r);
    r = rig_create(256);
    thull cube, prism;
    thull_box(&cube, (double[3]){ 0.5, 0.5, 0.5 });
    th_rng g = th_rng_seed(5);
    thull_make(&prism, FRUSTUM, 5, 0.5, 0.4, 0.3, &g);
    const double ridge = 0.5 * sqrt(2.0);
    tb_quat ax = th_quat_axis_angle(th_v3(1, 0, 0), PI / 4), az = th_quat_axis_angle(th_v3(0, 0, 1), PI / 4);
    /* the hulls as the world built them: their face and edge counts */
    obj probe_a = hull(r, &cube, th_v3(-50, 0, 0), identity);
    obj probe_b = hull(r, &prism, th_v3(-60, 0, 0), identity);
    const thull* ha = probe_a.hull, *hb = probe_b.hull;
    uint32_t codes[256], m = 0;
    for (uint32_t f = 0; f < ha->nf; f++) codes[m++] = axis_code(1, 0, f);
    for (uint32_t f = 0; f < hb->nf; f++) codes[m++] = axis_code(2, 0, f);
    for (uint32_t i = 0; i < ha->ne; i++)
        for (uint32_t j = 0; j < hb->ne && m < 200; j += 2) codes[m++] = axis_code(3, i, j);
    codes[m++] = axis_code(1, 0, 999);
    codes[m++] = axis_code(3, 999, 0);
    codes[m++] = axis_code(2, 0, 77);
    for (int config = 0; config < 2; config++) {
        for (uint32_t i = 0; i < m; i++) {
            float x = 3.0f * (float)i;
            if (config == 0) { /* crossed ridges: an edge contact */
                a[i] = hull(r, &cube, th_v3(x, 0, 0), ax);
                b[i] = hull(r, &prism, th_v3(x + 0.1f, (float)(ridge + 0.28), 0.05f), az);
            } else {           /* the frustum resting on the cube: a face contact */
                a[i] = hull(r, &cube, th_v3(x, 0, 0), identity);
                b[i] = hull(r, &prism, th_v3(x + 0.1f, 0.5f, 0.05f), th_quat_axis_angle(th_v3(1, 0, 0), -PI / 2));
            }
        }
        for (uint32_t i = 0; i < m; i++) { /* placed 1 cm deep along y */
            obj moved = b[i];
            place_at(&moved, &a[i], (double[3]){ 0, 1, 0 }, -0.01);
            obj_move(r, &b[i], th_v3((float)moved.pos[0], (float)moved.pos[1], (float)moved.pos[2]), b[i].rot);
        }
        run_single(r, 1, a, b, m, 0);
        tb_gpu_manifold fresh = *rig_manifold(r, 1, 0);
        assert_true(fresh.info.x > 0);
        for (uint32_t i = 0; i < m; i++) {
            r->manifolds[1 * r->cap + i].axis = (tb_gpu_uvec4){ codes[i], 0, 0, 0 };
            memset(&r->manifolds[1 * r->cap + i].impulse, 0, sizeof fresh.impulse);
        }
        run_single(r, 0, a, b, m, 1);
        for (uint32_t i = 0; i < m; i++) {
            const tb_gpu_manifold* got = rig_manifold(r, 0, i);
            if (got->info.x != fresh.info.x)
                fail_msg("config %d: cached axis %#x: %u points, %u without", config, codes[i],
                         got->info.x, fresh.info.x);
            check_manifold(got, &a[i], &b[i], "forged cache");
        }
    }
    rig_destroy(r);
}

/* The same hull contacts at two slightly different poses have the same feature keys. */
static void test_hull_feature_keys_stable(void** state)
{
    (void)state;
    rig* r = rig_create(32);
    thull slab, cube, tri;
    thull_box(&slab, (double[3]){ 2, 0.5, 2 });
    thull_box(&cube, (double[3]){ 0.5, 0.5, 0.5 });
    regular_prism(&tri, 3, 0.4, 0.2);
    tb_quat nudge = th_quat_axis_angle(th_v3(0.3f, 1, -0.5f), 2e-3);
    tb_quat turn = th_quat_axis_angle(th_v3(0, 1, 0), 0.3);
    tb_quat caps_up = th_quat_axis_angle(th_v3(1, 0, 0), PI / 2);
    tb_quat ax = th_quat_axis_angle(th_v3(1, 0, 0), PI / 4), az = th_quat_axis_angle(th_v3(0, 0, 1), PI / 4);
    const double ridge = 0.5 * sqrt(2.0);
    obj ground = plane(r, th_v3(0, 1, 0), 0, th_v3(0, 0, 0), identity);
    obj o[16];
    int n = 0;
    for (int copy = 0; copy < 2; copy++) {
        float dx = copy ? 1.5e-3f : 0, dy = copy ? -1e-3f : 0, z = copy ? 40.0f : 0;
        o[n++] = hull(r, &slab, th_v3(0, 0, z), identity);
        o[n++] = hull(r, &cube, th_v3(0.3f + dx, 0.99f + dy, z - 0.2f), turn);
        o[n++] = hull(r, &slab, th_v3(10, 0, z), identity);
        o[n++] = hull(r, &tri, th_v3(10.2f + dx, 0.39f + dy, z), quat_mul(turn, caps_up));
        o[n++] = hull(r, &cube, th_v3(20, 0, z), ax);
        o[n++] = hull(r, &cube, th_v3(20.2f + dx, (float)(2 * ridge - 0.02) + dy, z + 0.1f), az);
        o[n++] = hull(r, &cube, th_v3(30 + dx, 0.49f + dy, z), turn);
    }
    for (int i = 7; i < 14; i++) {
        if (i == 7 || i == 9 || i == 11) continue; /* the supports stay */
        obj_move(r, &o[i], th_v3((float)o[i].pos[0], (float)o[i].pos[1], (float)o[i].pos[2]),
                 quat_mul(nudge, o[i].rot));
    }
    pair_list l = { .n = 0 };
    for (int copy = 0; copy < 2; copy++) {
        const obj* c = &o[7 * copy];
        pair_add(&l, &c[0], &c[1], "cube on a slab");
        pair_add(&l, &c[2], &c[3], "triangular prism on its cap on a slab");
        pair_add(&l, &c[4], &c[5], "crossed edges");
        pair_add(&l, &ground, &c[6], "cube hull on the ground");
    }
    run_pairs(r, &l);
    /* Four clip corners or fewer: more would leave the choice to the reduction, and the
     * deepest of a face lying flat is whichever the nudge tilts lowest. */
    static const uint32_t counts[4] = { 4, 3, 1, 4 };
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
        cmocka_unit_test(test_hull_on_hull),
        cmocka_unit_test(test_hull_crossed_edges),
        cmocka_unit_test(test_hull_plane),
        cmocka_unit_test(test_hull_sphere),
        cmocka_unit_test(test_random_hulls),
        cmocka_unit_test(test_random_hull_sphere_plane),
        cmocka_unit_test(test_box_hull_like_box_box),
        cmocka_unit_test(test_hull_cached_axis),
        cmocka_unit_test(test_hull_feature_keys_stable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
