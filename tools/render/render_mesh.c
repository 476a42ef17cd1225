/* The two unit meshes drawn instanced: a UV sphere of radius 1 with smooth normals and a
 * cube of half extent 1 with flat normals (4 vertices per face). Both are drawn without
 * face culling, so triangle winding does not matter. */
#include <math.h>

#include "render_internal.h"

static void set_vertex(tr_vertex* v, double x, double y, double z, double nx, double ny,
                       double nz)
{
    v->position[0] = (float)x; v->position[1] = (float)y; v->position[2] = (float)z;
    v->normal[0] = (float)nx; v->normal[1] = (float)ny; v->normal[2] = (float)nz;
}

uint32_t tr_sphere_mesh(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count)
{
    const double pi = 3.14159265358979323846;
    const uint32_t row = TR_SPHERE_SLICES + 1;
    for (uint32_t i = 0; i <= TR_SPHERE_STACKS; i++) {
        double phi = pi * i / TR_SPHERE_STACKS;
        for (uint32_t j = 0; j <= TR_SPHERE_SLICES; j++) {
            double theta = 2.0 * pi * j / TR_SPHERE_SLICES;
            double x = sin(phi) * cos(theta), y = cos(phi), z = sin(phi) * sin(theta);
            set_vertex(&vertices[i * row + j], x, y, z, x, y, z);
        }
    }
    uint32_t n = 0;
    for (uint32_t i = 0; i < TR_SPHERE_STACKS; i++) {
        for (uint32_t j = 0; j < TR_SPHERE_SLICES; j++) {
            uint32_t a = i * row + j, b = a + row;
            uint32_t quad[6] = { a, b, a + 1, a + 1, b, b + 1 };
            for (int k = 0; k < 6; k++) indices[n++] = quad[k];
        }
    }
    *index_count = n;
    return TR_SPHERE_VERTICES;
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
