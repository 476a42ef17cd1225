/* Internal to the hull module: the polygon mesh that quickhull hands to the code that
 * computes mass properties and writes a tb_hull. Double precision throughout, so that the
 * principal frame is found from the same numbers the hull was built from. */
#ifndef TB_GEOM_HULL_MESH_H
#define TB_GEOM_HULL_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "geom/hull.h"

typedef struct tb_hull_mesh {
    uint32_t vertex_count, face_count, index_count;
    double (*vertices)[3];
    tb_hull_face* faces;      /* counter-clockwise loops seen from outside, into indices */
    uint32_t* indices;        /* 32-bit: the GPU limits are checked after, by tb_hull_fill */
} tb_hull_mesh;

void tb_hull_mesh_free(tb_hull_mesh* mesh);

/* Face f's plane by Newell's method (the normal is the sum of the projected areas, robust
 * for polygons planar only within tolerance) through the mean c of its corners: writes n
 * unnormalised (its length is twice the face's area) and c. */
void tb_hull_mesh_face_normal(const tb_hull_mesh* mesh, uint32_t f, double n[3], double c[3]);

/* Quickhull of n finite points, with coplanar faces merged and vertices that are not
 * corners of the merged polyhedron removed. eps is the distance below which points count
 * as on a plane. Returns 0, or with a sentence in error (mesh then left empty)
 * TB_QUICKHULL_NOISY when the points are too noisy at the scale of eps to give a consistent
 * hull (a larger eps may), or -1 on anything else (degenerate input, no memory). */
#define TB_QUICKHULL_NOISY (-2)
int tb_quickhull(const double (*points)[3], uint32_t n, double eps, tb_hull_mesh* mesh,
                 char* error, size_t error_size);

/* Volume, centre of mass and the covariance (second moment about the centre, unit
 * density) of the solid bounded by a closed mesh. */
void tb_hull_mass(const tb_hull_mesh* mesh, double* volume, double center[3],
                  double covariance[3][3]);

/* Principal axes of a symmetric 3x3 matrix: columns of axes (a proper rotation) and the
 * eigenvalues along them. */
void tb_sym3_eigen(const double m[3][3], double axes[3][3], double values[3]);

/* The unit quaternion (x, y, z, w) of a proper rotation matrix. */
void tb_mat3_to_quat(const double r[3][3], double q[4]);

/* Allocate and fill out's arrays (vertices, planes, faces, indices, edges, AABB) from a
 * mesh already in its final frame; checks the GPU limits. Mass fields are left alone. */
int tb_hull_fill(const tb_hull_mesh* mesh, tb_hull* out, char* error, size_t error_size);

#endif
