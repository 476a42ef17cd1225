/* The joint overlay: every joint of the world drawn as lines, written on the host each
 * frame into a host-visible storage buffer that joints.vert reads (TR_BIND_JOINT_LINES).
 *
 * A joint is three segments: from body a's centre to its anchor, from that anchor to body
 * b's anchor, and from there to body b's centre. The middle one is the joint's error (the
 * anchors of a ball, hinge, weld or slider meet, so it shows only where they have come
 * apart; a distance joint's is its rod or rope); the outer ones show what the joint holds
 * together, so a chain or a ragdoll shows as its skeleton. Anchors come from
 * tb_joint_read_anchors and the bodies' centres from tb_world_read_transforms, both from
 * the world's poses after its last step. Joints are few beside contacts, so the host's
 * loop over them is cheap; a joint whose points are not finite is left out.
 */
#include <math.h>
#include <stdlib.h>

#include "render_internal.h"

/* Each vertex is a vec4: the point, and in w which kind of segment it ends. */
typedef struct joint_vertex { float x, y, z, kind; } joint_vertex;

/* What one frame reads from the world: the joints, their anchors, and their bodies a and b
 * (joint i's at 2i and 2i + 1) with the bodies' poses. */
typedef struct joint_scratch {
    tb_joint_id* ids;
    tb_vec3 *anchors_a, *anchors_b;
    tb_body_id* bodies;
    tb_vec3* centres;
    tb_quat* rotations;
} joint_scratch;

static void scratch_free(joint_scratch* s)
{
    free(s->ids);
    free(s->anchors_a);
    free(s->anchors_b);
    free(s->bodies);
    free(s->centres);
    free(s->rotations);
}

static int finite3(tb_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static joint_vertex vertex(tb_vec3 p, float kind)
{
    return (joint_vertex){ p.x, p.y, p.z, kind };
}

/* The anchors of the first `count` joints and the centres of their bodies. */
static tb_result read_joints(tr_renderer* r, uint32_t count, joint_scratch* s)
{
    s->ids = malloc(count * sizeof *s->ids);
    s->anchors_a = malloc(count * sizeof *s->anchors_a);
    s->anchors_b = malloc(count * sizeof *s->anchors_b);
    s->bodies = malloc(2 * (size_t)count * sizeof *s->bodies);
    s->centres = malloc(2 * (size_t)count * sizeof *s->centres);
    s->rotations = malloc(2 * (size_t)count * sizeof *s->rotations);
    if (!s->ids || !s->anchors_a || !s->anchors_b || !s->bodies || !s->centres || !s->rotations)
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for %u joints", count);
    tb_world* w = r->world;
    tb_world_joint_ids(w, s->ids, count);
    tb_result res = tb_joint_read_anchors(w, s->ids, count, s->anchors_a, s->anchors_b);
    for (uint32_t i = 0; !res && i < count; i++)
        res = tb_joint_get_bodies(w, s->ids[i], &s->bodies[2 * i], &s->bodies[2 * i + 1]);
    if (!res) res = tb_world_read_transforms(w, s->bodies, 2 * count, s->centres, s->rotations);
    if (res) return tr_fail(r, res, "reading the joints: %s", tb_world_last_error(w));
    return TB_OK;
}

/* A buffer for at least `vertices`, pointed at by the set (not in use: every frame waits
 * for its fence). */
static tb_result reserve(tr_renderer* r, uint32_t vertices)
{
    if (vertices <= r->joint_line_capacity && r->joint_lines.buffer) return TB_OK;
    uint32_t doubled = 2 * r->joint_line_capacity;
    uint32_t capacity = vertices > doubled ? vertices : doubled;
    tr_buffer fresh = { 0 };
    tb_result res = tr_host_buffer(r, (VkDeviceSize)capacity * sizeof(joint_vertex),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &fresh);
    if (res) {
        tr_buffer_destroy(r, &fresh);
        return res;
    }
    tr_buffer_destroy(r, &r->joint_lines);
    r->joint_lines = fresh;
    r->joint_line_capacity = capacity;
    VkDescriptorBufferInfo info = { fresh.buffer, 0, VK_WHOLE_SIZE };
    VkWriteDescriptorSet write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = r->set,
        .dstBinding = TR_BIND_JOINT_LINES, .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &info,
    };
    vkUpdateDescriptorSets(r->dev.device, 1, &write, 0, NULL);
    return TB_OK;
}

/* The three segments of each joint whose points are all finite; returns the vertices. */
static uint32_t write_segments(const joint_scratch* s, uint32_t count, joint_vertex* out)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < count; i++) {
        tb_vec3 ca = s->centres[2 * i], cb = s->centres[2 * i + 1];
        tb_vec3 a = s->anchors_a[i], b = s->anchors_b[i];
        if (!finite3(ca) || !finite3(cb) || !finite3(a) || !finite3(b)) continue;
        out[n++] = vertex(ca, TR_JOINT_ARM);
        out[n++] = vertex(a, TR_JOINT_ARM);
        out[n++] = vertex(a, TR_JOINT_GAP);
        out[n++] = vertex(b, TR_JOINT_GAP);
        out[n++] = vertex(b, TR_JOINT_ARM);
        out[n++] = vertex(cb, TR_JOINT_ARM);
    }
    return n;
}

tb_result tr_joints_prepare(tr_renderer* r, uint32_t* vertices)
{
    *vertices = 0;
    uint32_t count = tb_world_joint_ids(r->world, NULL, 0);
    /* As many as one binding can show. */
    uint64_t most = r->max_storage_range / (TR_JOINT_VERTICES_PER_JOINT * sizeof(joint_vertex));
    if (count > most) count = (uint32_t)most;
    if (count == 0) return TB_OK;
    joint_scratch s = { 0 };
    tb_result res = read_joints(r, count, &s);
    if (!res) res = reserve(r, count * TR_JOINT_VERTICES_PER_JOINT);
    if (!res) *vertices = write_segments(&s, count, r->joint_lines.mapped);
    scratch_free(&s);
    return res;
}

void tr_joints_destroy(tr_renderer* r)
{
    tr_buffer_destroy(r, &r->joint_lines);
    r->joint_line_capacity = 0;
}
