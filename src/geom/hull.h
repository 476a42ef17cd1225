/* Convex hulls on the host: quickhull from a point cloud, merged polygon faces, unique
 * edges, mass properties, and the hull re-expressed in its principal frame (centre of mass
 * at the origin, axes along the principal axes of inertia) as the GPU uses it.
 *
 * Topology conventions (glsl/common/layout.h, TB_BIND_HULL_TOPOLOGY, follows them):
 * - faces are convex polygons, vertices counter-clockwise seen from outside, with an
 *   outward unit normal n and offset d (dot(n, x) = d on the face, < d inside);
 * - every undirected edge appears once, as (v0, v1, left, right): `left` is the face on
 *   whose boundary v0 -> v1 runs counter-clockwise, `right` the face where it runs v1 -> v0.
 */
#ifndef TB_GEOM_HULL_H
#define TB_GEOM_HULL_H

#include <stddef.h>
#include <stdint.h>

typedef struct tb_hull_edge { uint16_t v0, v1, left, right; } tb_hull_edge;
typedef struct tb_hull_face { uint32_t first, count; } tb_hull_face; /* into indices */

typedef struct tb_hull {
    uint32_t vertex_count, face_count, edge_count, index_count;
    float (*vertices)[3];     /* principal frame */
    float (*planes)[4];       /* per face: xyz outward unit normal, w offset (principal frame) */
    tb_hull_face* faces;
    uint16_t* indices;        /* face vertex indices, faces[f].first .. + count */
    tb_hull_edge* edges;
    double volume;            /* m^3 */
    double center[3];         /* centre of mass, in the input frame */
    double rotation[4];       /* quaternion (x, y, z, w): principal frame -> input frame */
    double unit_inertia[3];   /* principal moments per kg of mass (ascending not required) */
    float aabb_min[3], aabb_max[3]; /* principal frame */
} tb_hull;

/* Build the hull of `count` points (xyz triples). Returns 0 and fills *out, or returns -1
 * and writes a sentence to `error` (never touching *out) when a point is not finite or
 * the points span no volume. Duplicate, coplanar and nearly coplanar points are handled:
 * points within a tolerance scaled to the cloud's extent count as on a plane, and faces
 * whose normals agree within it merge into one polygon. */
int tb_hull_build(const float* xyz, uint32_t count, tb_hull* out, char* error, size_t error_size);

/* The hull of a box with half extents h (already centred and principal). */
int tb_hull_box(const float h[3], tb_hull* out, char* error, size_t error_size);

void tb_hull_free(tb_hull* hull);

#endif
