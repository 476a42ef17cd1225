/* Compound shapes' meshes: each child's mesh (its type's unit mesh sized by the child's
 * params as mesh.vert sizes it, or the hull's own mesh) placed by the child's pose in the
 * compound's body frame, all in one flat list drawn like a hull shape's (render_hulls.c). */
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "render_internal.h"

/* Vertex v (in the child's frame) placed by the child's pose. */
static tr_vertex place(const tr_vertex* v, const tb_compound_child* c)
{
    versor q = { c->rotation.x, c->rotation.y, c->rotation.z, c->rotation.w };
    vec3 p = { v->position[0], v->position[1], v->position[2] };
    vec3 n = { v->normal[0], v->normal[1], v->normal[2] };
    tr_vertex out;
    glm_quat_rotatev(q, p, out.position);
    glm_quat_rotatev(q, n, out.normal);
    glm_vec3_add(out.position, (vec3){ c->position.x, c->position.y, c->position.z },
                 out.position);
    return out;
}

/* The size of a child with a unit mesh, as its GPU shape's params hold it (sphere: x the
 * radius; box: xyz the half extents; capsule, cylinder, cone: x the radius, y the half
 * height). */
static tb_result unit_params(tr_renderer* r, tb_shape_id shape, tb_shape_type type,
                             float params[4])
{
    tb_result res;
    if (type == TB_SHAPE_SPHERE) {
        res = tb_shape_get_sphere_radius(r->world, shape, &params[0]);
    } else if (type == TB_SHAPE_BOX) {
        tb_vec3 half = { 0, 0, 0 };
        res = tb_shape_get_box_half_extents(r->world, shape, &half);
        params[0] = half.x; params[1] = half.y; params[2] = half.z;
    } else {
        res = tb_shape_get_round_size(r->world, shape, &params[0], &params[1]);
    }
    if (res)
        return tr_fail(r, res, "a compound child's size: %s", tb_world_last_error(r->world));
    return TB_OK;
}

/* A unit mesh's triangles sized by `params`, vertex by vertex. */
static tb_result unit_child(tr_renderer* r, tb_shape_type type, const float params[4],
                            const tb_compound_child* c, tr_vertex** out, uint32_t* count)
{
    const tr_mesh* m = &r->units[type];
    const tr_vertex* vertices = r->vertices.mapped;
    const uint32_t* indices = r->indices.mapped;
    tr_vertex* v = malloc((m->index_count ? m->index_count : 1) * sizeof *v);
    if (!v) return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for a compound mesh");
    for (uint32_t k = 0; k < m->index_count; k++) {
        int32_t at = m->vertex_offset + (int32_t)indices[m->first_index + k];
        tr_vertex sized = tr_sized_vertex((uint32_t)type, params, &vertices[at]);
        v[k] = place(&sized, c);
    }
    *out = v;
    *count = m->index_count;
    return TB_OK;
}

/* Child c's mesh in the compound's body frame. */
static tb_result child_vertices(tr_renderer* r, const tb_compound_child* c, tr_vertex** out,
                                uint32_t* count)
{
    tb_shape_type type;
    *out = NULL;
    *count = 0;
    tb_result res = tb_shape_get_type(r->world, c->shape, &type);
    if (res)
        return tr_fail(r, res, "a compound child's type: %s", tb_world_last_error(r->world));
    if ((uint32_t)type < TR_SHAPE_TYPES && r->units[type].index_count) {
        float params[4] = { 0, 0, 0, 0 };
        res = unit_params(r, c->shape, type, params);
        return res ? res : unit_child(r, type, params, c, out, count);
    }
    res = tr_hull_vertices(r, c->shape, out, count);
    for (uint32_t k = 0; !res && k < *count; k++) (*out)[k] = place(&(*out)[k], c);
    return res;
}

/* Appends `add` (count vertices, freed) to the list. */
static tb_result append(tr_renderer* r, tr_vertex** list, uint32_t* total, tr_vertex* add,
                        uint32_t count)
{
    tr_vertex* grown = realloc(*list, ((size_t)*total + count + 1) * sizeof *grown);
    if (!grown) {
        free(add);
        return tr_fail(r, TB_ERROR_OUT_OF_MEMORY, "no host memory for a compound mesh");
    }
    memcpy(grown + *total, add, (size_t)count * sizeof *add);
    free(add);
    *list = grown;
    *total += count;
    return TB_OK;
}

tb_result tr_compound_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** out,
                               uint32_t* vertex_count)
{
    tb_compound_child children[TB_COMPOUND_MAX_CHILDREN];
    uint32_t n = 0, total = 0;
    *out = NULL;
    *vertex_count = 0;
    tb_result res = tb_shape_get_compound_children(r->world, id, children,
                                                   TB_COMPOUND_MAX_CHILDREN, &n);
    if (res) return tr_fail(r, res, "tb_shape_get_compound_children: %s",
                            tb_world_last_error(r->world));
    tr_vertex* list = NULL;
    for (uint32_t i = 0; i < n && !res; i++) {
        tr_vertex* v;
        uint32_t count;
        res = child_vertices(r, &children[i], &v, &count);
        if (!res) res = append(r, &list, &total, v, count);
    }
    if (res) {
        free(list);
        return res;
    }
    *out = list;
    *vertex_count = total;
    return TB_OK;
}
