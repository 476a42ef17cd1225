/* The unit meshes drawn instanced, one per shape type that mesh.vert sizes by the shape's
 * params (tr_sized_vertex does the same on the host, for compound children):
 *  - sphere: a UV sphere of radius 1 with smooth normals;
 *  - box: a cube of half extent 1 with flat normals (4 vertices per face);
 *  - capsule: the capsule of radius 1 and half height 1 along y, each vertex at its normal
 *    plus (0, +-1, 0) (the sphere's rows with the equator doubled and the halves moved
 *    apart), so that the normal, scaled by the radius, and the rest, scaled by the half
 *    height, size it without stretching the caps;
 *  - cylinder: radius 1 from y = -1 to 1, smooth sides and flat caps;
 *  - cone: base radius 1 at y = -1/2, apex at y = 3/2 (the centre of mass at the origin, as
 *    the shape's), smooth sides and a flat base.
 * Round meshes have TR_ROUND_SLICES slices about y. All are drawn without face culling, so
 * triangle winding does not matter. */
#include <math.h>

#include "render_internal.h"

static void set_vertex(tr_vertex* v, double x, double y, double z, double nx, double ny,
                       double nz)
{
    v->position[0] = (float)x; v->position[1] = (float)y; v->position[2] = (float)z;
    v->normal[0] = (float)nx; v->normal[1] = (float)ny; v->normal[2] = (float)nz;
}

/* A ring of TR_ROUND_SLICES + 1 vertices about y (the seam twice, so the last slice closes
 * on its own vertex) of `radius` at height y, each with the normal (nx, ny) of the profile
 * turned to its angle, normalized. `phase` shifts the angles by that share of a slice.
 * Returns the vertices written. */
static uint32_t ring(tr_vertex* out, double radius, double y, double nx, double ny,
                     double phase)
{
    const double pi = 3.14159265358979323846;
    double len = sqrt(nx * nx + ny * ny);
    for (uint32_t j = 0; j <= TR_ROUND_SLICES; j++) {
        double theta = 2.0 * pi * (j + phase) / TR_ROUND_SLICES;
        double c = cos(theta), s = sin(theta);
        set_vertex(&out[j], radius * c, y, radius * s, nx * c / len, ny / len, nx * s / len);
    }
    return TR_ROUND_SLICES + 1;
}

/* Two triangles per slice between each pair of consecutive rings of `rings` rings from
 * vertex `first` on. Returns the indices written. */
static uint32_t bands(uint32_t* out, uint32_t first, uint32_t rings)
{
    const uint32_t row = TR_ROUND_SLICES + 1;
    uint32_t n = 0;
    for (uint32_t i = 0; i + 1 < rings; i++) {
        for (uint32_t j = 0; j < TR_ROUND_SLICES; j++) {
            uint32_t a = first + i * row + j, b = a + row;
            uint32_t quad[6] = { a, b, a + 1, a + 1, b, b + 1 };
            for (int k = 0; k < 6; k++) out[n++] = quad[k];
        }
    }
    return n;
}

/* A triangle per slice from vertex `tip` to the ring from vertex `first` on. Returns the
 * indices written. */
static uint32_t fan(uint32_t* out, uint32_t tip, uint32_t first)
{
    uint32_t n = 0;
    for (uint32_t j = 0; j < TR_ROUND_SLICES; j++) {
        out[n++] = tip;
        out[n++] = first + j;
        out[n++] = first + j + 1;
    }
    return n;
}

/* The sphere's rings from the top pole down; `split` doubles the equator ring and moves the
 * rings above it (the first equator included) up by 1 and the others down by 1: the unit
 * capsule. Returns the rings written. */
static uint32_t sphere_rings(tr_vertex* vertices, int split)
{
    const double pi = 3.14159265358979323846;
    const uint32_t half = TR_SPHERE_STACKS / 2, rings = TR_SPHERE_STACKS + 1 + (split != 0);
    for (uint32_t i = 0; i < rings; i++) {
        uint32_t stack = split && i > half ? i - 1 : i;
        double phi = pi * stack / TR_SPHERE_STACKS;
        double lift = !split ? 0.0 : i <= half ? 1.0 : -1.0;
        ring(vertices + i * (TR_ROUND_SLICES + 1), sin(phi), cos(phi) + lift, sin(phi),
             cos(phi), 0.0);
    }
    return rings;
}

uint32_t tr_sphere_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    uint32_t rings = sphere_rings(vertices, 0);
    *index_count = bands(indices, 0, rings);
    return TR_SPHERE_VERTICES;
}

uint32_t tr_capsule_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    uint32_t rings = sphere_rings(vertices, 1);
    *index_count = bands(indices, 0, rings);
    return TR_CAPSULE_VERTICES;
}

uint32_t tr_cube_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    /* Per face: normal axis and sign; u and v are the two other axes. */
    uint32_t nv = 0, ni = 0;
    for (int axis = 0; axis < 3; axis++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const double su[4] = { -1, 1, 1, -1 }, sv[4] = { -1, -1, 1, 1 };
            for (int k = 0; k < 4; k++) {
                double p[3] = { 0, 0, 0 }, nrm[3] = { 0, 0, 0 };
                p[axis] = sign; p[u] = su[k]; p[v] = sv[k];
                nrm[axis] = sign;
                set_vertex(&vertices[nv + k], p[0], p[1], p[2], nrm[0], nrm[1], nrm[2]);
            }
            const uint32_t quad[6] = { 0, 1, 2, 0, 2, 3 };
            for (int k = 0; k < 6; k++) indices[ni++] = nv + quad[k];
            nv += 4;
        }
    }
    *index_count = ni;
    return nv;
}

/* A flat disc of radius 1 at height y facing `facing` (+1 up, -1 down): its centre, then
 * its ring. Returns the vertices written; *ni grows by its indices. */
static uint32_t disc(tr_vertex* vertices, uint32_t first, uint32_t* indices, uint32_t* ni,
                     double y, double facing)
{
    set_vertex(&vertices[first], 0, y, 0, 0, facing, 0);
    uint32_t n = 1 + ring(vertices + first + 1, 1.0, y, 0.0, facing, 0.0);
    *ni += fan(indices + *ni, first, first + 1);
    return n;
}

uint32_t tr_cylinder_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    uint32_t nv = ring(vertices, 1.0, -1.0, 1.0, 0.0, 0.0);
    nv += ring(vertices + nv, 1.0, 1.0, 1.0, 0.0, 0.0);
    uint32_t ni = bands(indices, 0, 2);
    nv += disc(vertices, nv, indices, &ni, -1.0, -1.0);
    nv += disc(vertices, nv, indices, &ni, 1.0, 1.0);
    *index_count = ni;
    return nv;
}

uint32_t tr_cone_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    /* The side's normal leans up by the radius over the height (1 over 2). Each slice's
     * apex vertex takes the normal half way round the slice, so the side shades evenly. */
    uint32_t nv = ring(vertices, 1.0, -0.5, 2.0, 1.0, 0.0);
    uint32_t apex = nv;
    nv += ring(vertices + nv, 0.0, 1.5, 2.0, 1.0, 0.5);
    uint32_t ni = 0;
    for (uint32_t j = 0; j < TR_ROUND_SLICES; j++) {
        indices[ni++] = apex + j;
        indices[ni++] = j;
        indices[ni++] = j + 1;
    }
    nv += disc(vertices, nv, indices, &ni, -0.5, -1.0);
    *index_count = ni;
    return nv;
}

tr_vertex tr_sized_vertex(uint32_t type, const float params[4], const tr_vertex* v)
{
    tr_vertex out;
    if (type == TB_GPU_SHAPE_CAPSULE) {
        for (int i = 0; i < 3; i++) {
            float segment = v->position[i] - v->normal[i];
            out.position[i] = params[0] * v->normal[i] + params[1] * segment;
            out.normal[i] = v->normal[i];
        }
        return out;
    }
    float scale[3] = { params[0], params[0], params[0] };
    if (type == TB_GPU_SHAPE_BOX) for (int i = 0; i < 3; i++) scale[i] = params[i];
    if (type == TB_GPU_SHAPE_CYLINDER || type == TB_GPU_SHAPE_CONE) scale[1] = params[1];
    /* Normals by the inverse scale (the inverse transpose), so a cone's side stays square to
     * its surface at any proportions. */
    float len = 0;
    for (int i = 0; i < 3; i++) {
        out.position[i] = v->position[i] * scale[i];
        out.normal[i] = v->normal[i] / scale[i];
        len += out.normal[i] * out.normal[i];
    }
    len = sqrtf(len);
    for (int i = 0; i < 3; i++) out.normal[i] = len > 0 ? out.normal[i] / len : 0.0f;
    return out;
}
