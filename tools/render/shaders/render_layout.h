/* The renderer's push constants and flags, included by its C files and its shaders, so the
 * two sides cannot drift (the world's own layouts are in glsl/common/layout.h). */
#ifndef TUMBLE_RENDER_LAYOUT_H
#define TUMBLE_RENDER_LAYOUT_H

#if defined(__STDC__) || defined(__cplusplus)
#include <stdint.h>
#define TR_MAT4(name) float name[16]
#define TR_VEC4(name) float name[4]
#define TR_UVEC4(name) uint32_t name[4]
#define TR_STRUCT(name) typedef struct name name; struct name
#define TR_U(x) x##u
#else
#define TR_MAT4(name) mat4 name
#define TR_VEC4(name) vec4 name
#define TR_UVEC4(name) uvec4 name
#define TR_STRUCT(name) struct name
#define TR_U(x) uint(x)
#endif

/* mode.z: flags in the low byte, the see-through pass's opacity (0..255) above them */
#define TR_FLAG_GRID          TR_U(1)  /* draw grid lines on planes */
#define TR_FLAG_DEFAULT_PLANE TR_U(2)  /* one horizontal grid under the scene, not a body */
#define TR_FLAG_SEE_THROUGH   TR_U(4)  /* opaque body draws keep only the faces of static
                                          bodies that look up; the others come last,
                                          see-through (TR_FLAG_STATIC_PASS) */
#define TR_FLAG_STATIC_PASS   TR_U(8)  /* this body draw shows static bodies only, their faces
                                          that neither look up nor away from the eye,
                                          blended at the opacity in bits TR_OPACITY_SHIFT.. */
#define TR_OPACITY_SHIFT      8

/* The renderer's binding of the world's manifolds (its own set; the world reaches them by
 * address): past the world's bindings, so the body arrays keep the world's numbers. */
#define TR_BIND_MANIFOLDS TB_BIND_COUNT

/* Triangle-mesh shapes (mesh_lists.comp, mesh.vert): each frame a compute pass lists the
 * bodies of every mesh shape for that shape's indirect draw, since a mesh is too large to
 * draw once per body slot as the hulls are. Bindings past the manifolds'. */
#define TR_BIND_MESH_OF_SHAPE  (TB_BIND_COUNT + 1) /* uint per shape slot: its mesh draw */
#define TR_BIND_MESH_COMMANDS  (TB_BIND_COUNT + 2) /* VkDrawIndexedIndirectCommand per mesh
                                                      draw, as 5 uints (instance count 2nd) */
#define TR_BIND_MESH_INSTANCES (TB_BIND_COUNT + 3) /* per mesh draw, a list of body slots
                                                      with room for every body slot */
#define TR_NO_MESH             TR_U(0xffffffff)   /* a shape slot that is no mesh shape */
#define TR_MESH_COMMAND_UINTS  5
#define TR_MESH_LIST_GROUP     64                 /* body slots per workgroup */

/* Contact overlay (contacts.vert). One instance per manifold, LINE_LIST: first the normals
 * of its TB_MAX_MANIFOLD_POINTS points (2 vertices each), then their crosses (3 axis-aligned
 * segments, 6 vertices each), so a point's cross is drawn over the normals. */
#define TR_CONTACT_VERTICES_PER_POINT 8
/* Cross arm: this share of the distance from the eye to the point, so a cross keeps about
 * the same size on screen (a few pixels) near and far. */
#define TR_CONTACT_CROSS_SHARE 0.012
/* Normal line length: this share of the eye-target distance, so it scales with the view. */
#define TR_CONTACT_NORMAL_SHARE 0.03
/* The overlay is depth-tested against the scene (and writes depth, so see-through static
 * bodies drawn later blend over it only where they are in front). A contact lies on the
 * surfaces that touch, so each vertex is first moved towards the eye along its view ray
 * (where it projects stays the same) by this share of its distance from the eye, about
 * twice a cross arm: the cross of a contact on a visible surface shows whole, a contact
 * behind anything thicker than that stays hidden (a normal may dip into the body it
 * points into). */
#define TR_CONTACT_LIFT_SHARE 0.025
/* Colours in exact 8-bit steps (a test finds them in the image): points magenta, normals
 * yellow; no lit surface, the sky or the AABB lines come out in either. */
#define TR_CONTACT_POINT_R 255
#define TR_CONTACT_POINT_G 0
#define TR_CONTACT_POINT_B 255
#define TR_CONTACT_NORMAL_R 255
#define TR_CONTACT_NORMAL_G 230
#define TR_CONTACT_NORMAL_B 0

/* Joint overlay (joints.vert, render_joints.c). The host writes each joint's three
 * segments every frame, LINE_LIST, as vec4s (the point, and in w TR_JOINT_ARM or
 * TR_JOINT_GAP): body a's centre to its anchor and b's anchor to b's centre (arms, dark
 * blue), and anchor to anchor (the gap, red: the joint's error, or a distance joint's rod).
 * Drawn over the scene without the depth test, so a chain or ragdoll shows as its skeleton
 * through its bodies. Binding past the mesh lists'. */
#define TR_BIND_JOINT_LINES (TB_BIND_COUNT + 4)
#define TR_JOINT_VERTICES_PER_JOINT 6
#define TR_JOINT_ARM 0.0
#define TR_JOINT_GAP 1.0
/* Colours in exact 8-bit steps, neither of them the contact overlay's. */
#define TR_JOINT_ARM_R 20
#define TR_JOINT_ARM_G 40
#define TR_JOINT_ARM_B 140
#define TR_JOINT_GAP_R 230
#define TR_JOINT_GAP_G 20
#define TR_JOINT_GAP_B 20

/* 128 bytes, the least every device allows; the same block in every stage. */
TR_STRUCT(tr_push) {
    TR_MAT4(view_proj);   /* column-major, Vulkan clip space */
    TR_VEC4(eye);         /* xyz camera position, w far plane distance */
    TR_VEC4(target);      /* xyz point looked at, w speed that maps to full red */
    TR_VEC4(light);       /* xyz unit direction towards the light, w height of the default grid */
    TR_UVEC4(mode);       /* x shape type drawn, y TR_COLOR_*, z TR_FLAG_* and opacity,
                             w: hull draws, the shape slot drawn; mesh draws, where their
                             body list starts; contact overlay, the first manifold of the
                             last step (its index in the manifold buffer, whose halves
                             alternate by step parity). mesh_lists.comp: x body slots, y
                             room per body list, z shape slots */
};

#endif
