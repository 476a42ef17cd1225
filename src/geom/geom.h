/* src/geom/: host geometry in plain C, with no Vulkan: what shapes are made of before the
 * GPU sees them.
 *
 *   hull.h        convex hulls: quickhull from a point cloud, faces, edges, mass properties
 *                 in the principal frame (quickhull.c, hull.c, hull_mass.c)
 *   compound.h    compounds: composed mass properties, children in the principal frame,
 *                 the GPU image (compound.c)
 *   bvh.h         a triangle mesh's bounding volume hierarchy: median splits, depth-first
 *                 nodes with skip indices, boxes quantized to 16 bits (bvh.c)
 *   heightfield.h heightfields: a grid of heights cut into triangles, holes, active edges
 *                 (the mesh's rule), the GPU image (heightfield.c)
 *   report.h      what the builders share: a refusal's sentence, floats as GPU bits
 *   mesh.h        triangle meshes: checked copies, active edges and degenerate triangles,
 *                 the BVH, and the GPU image of a mesh shape (mesh.c)
 *
 * It reads the caller's points and writes hulls the caller owns; errors come back as a
 * sentence in the caller's buffer. The narrowphase's hull table packs these hulls for the
 * GPU.
 */
#ifndef TB_GEOM_GEOM_H
#define TB_GEOM_GEOM_H

#include "geom/bvh.h"
#include "geom/compound.h"
#include "geom/heightfield.h"
#include "geom/hull.h"
#include "geom/mesh.h"

#endif
