/* Compound mass properties and the GPU image (compound.h). The inertia tensor is summed in
 * double; poses are turned with cglm. */
#include <math.h>
#include <string.h>

#include <cglm/cglm.h>

#include "geom/compound.h"
#include "geom/hull_mesh.h"
#include "geom/report.h"

/* Child weights: mass, or volume when nothing has a density. */
static double total_weight(const tb_compound_input* in, uint32_t count, double* weights,
                           double* volume, double* mass)
{
    *volume = 0;
    *mass = 0;
    for (uint32_t i = 0; i < count; i++) {
        *volume += in[i].volume;
        *mass += in[i].volume * in[i].density;
    }
    double total = 0;
    for (uint32_t i = 0; i < count; i++) {
        weights[i] = *mass > 0 ? in[i].volume * in[i].density : in[i].volume;
        total += weights[i];
    }
    return total;
}

/* Child i's inertia about the common centre c, added to tensor (per unit weight sum). */
static void add_child_inertia(const tb_compound_input* child, double weight, const double c[3],
                              double tensor[3][3])
{
    /* cglm's vec4 and versor are 16-byte aligned: the stored quaternion is copied first. */
    versor q;
    memcpy(q, child->rotation, sizeof q);
    mat3 r;
    glm_quat_mat3(q, r);   /* r[col][row] */
    double d[3] = { child->position[0] - c[0], child->position[1] - c[1],
                    child->position[2] - c[2] };
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            double own = 0;
            for (int k = 0; k < 3; k++) own += r[k][i] * weight * child->unit_inertia[k] * r[k][j];
            tensor[i][j] += own + weight * ((i == j ? dd : 0) - d[i] * d[j]);
        }
    }
}

/* The child's pose and box in the principal frame (centre c, rotation q from it). */
static void place_part(const tb_compound_input* in, const double c[3], versor q,
                       tb_compound_part* part)
{
    versor inverse, turned, own;
    memcpy(own, in->rotation, sizeof own);
    glm_quat_inv(q, inverse);
    vec3 offset = { (float)(in->position[0] - c[0]), (float)(in->position[1] - c[1]),
                    (float)(in->position[2] - c[2]) };
    glm_quat_rotatev(inverse, offset, part->position);
    glm_quat_mul(inverse, own, turned);
    glm_quat_normalize(turned);
    memcpy(part->rotation, turned, sizeof turned);
    part->shape = in->shape;
    mat3 r;
    glm_quat_mat3(turned, r);
    vec3 center, box_center = { in->box_center[0], in->box_center[1], in->box_center[2] };
    glm_mat3_mulv(r, box_center, center);
    glm_vec3_add(center, part->position, part->box_center);
    for (int i = 0; i < 3; i++)
        part->box_half[i] = fabsf(r[0][i]) * in->box_half[0] + fabsf(r[1][i]) * in->box_half[1] +
                            fabsf(r[2][i]) * in->box_half[2];
}

static void union_box(tb_compound* out)
{
    for (uint32_t i = 0; i < out->count; i++) {
        for (int k = 0; k < 3; k++) {
            float lo = out->parts[i].box_center[k] - out->parts[i].box_half[k];
            float hi = out->parts[i].box_center[k] + out->parts[i].box_half[k];
            out->box_min[k] = i == 0 || lo < out->box_min[k] ? lo : out->box_min[k];
            out->box_max[k] = i == 0 || hi > out->box_max[k] ? hi : out->box_max[k];
        }
    }
}

void tb_compound_build(const tb_compound_input* in, uint32_t count, tb_compound* out)
{
    memset(out, 0, sizeof *out);
    double weights[TB_COMPOUND_MAX_CHILDREN], mass;
    double total = total_weight(in, count, weights, &out->volume, &mass);
    out->mass_per_volume = out->volume > 0 ? mass / out->volume : 0;
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) out->center[k] += weights[i] / total * in[i].position[k];
    double tensor[3][3] = { { 0 } }, axes[3][3];
    for (uint32_t i = 0; i < count; i++)
        add_child_inertia(&in[i], weights[i] / total, out->center, tensor);
    tb_sym3_eigen(tensor, axes, out->unit_inertia);
    tb_mat3_to_quat(axes, out->rotation);
    versor q = { (float)out->rotation[0], (float)out->rotation[1], (float)out->rotation[2],
                 (float)out->rotation[3] };
    out->count = count;
    for (uint32_t i = 0; i < count; i++) place_part(&in[i], out->center, q, &out->parts[i]);
    union_box(out);
}

size_t tb_compound_image_size(const tb_compound* c)
{
    return 1 + c->count * (sizeof(tb_gpu_compound_child) / sizeof(tb_gpu_uvec4));
}

void tb_compound_pack(const tb_compound* c, void* dst)
{
    tb_gpu_uvec4 header = { c->count, 0, 0, 0 };
    memcpy(dst, &header, sizeof header);
    tb_gpu_compound_child* children = (tb_gpu_compound_child*)((tb_gpu_uvec4*)dst + 1);
    for (uint32_t i = 0; i < c->count; i++) {
        const tb_compound_part* p = &c->parts[i];
        children[i] = (tb_gpu_compound_child){
            .position = { p->position[0], p->position[1], p->position[2],
                          tb_geom_bits_float(p->shape) },
            .rotation = { p->rotation[0], p->rotation[1], p->rotation[2], p->rotation[3] },
            .box_center = { p->box_center[0], p->box_center[1], p->box_center[2], 0 },
            .box_half = { p->box_half[0], p->box_half[1], p->box_half[2], 0 },
        };
    }
}
