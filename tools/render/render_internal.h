/* tools/render internals shared by its .c files (prefix tr_ as well, never exported). */
#ifndef TUMBLE_RENDER_INTERNAL_H
#define TUMBLE_RENDER_INTERNAL_H

#include <stdarg.h>

#include "layout.h"        /* TB_GPU_SHAPE_* */
#include "render.h"
#include "tumble_vulkan.h"

/* Shape types the renderer knows: TB_GPU_SHAPE_SPHERE .. TB_GPU_SHAPE_CONE. */
#define TR_SHAPE_TYPES (TB_GPU_SHAPE_CONE + 1)

/* The clear colour, in exact 8-bit steps so that a cleared pixel reads back exactly. */
#define TR_SKY_R 204
#define TR_SKY_G 219
#define TR_SKY_B 235

#include "render_layout.h" /* tr_push and TR_FLAG_*, shared with the shaders */

/* Every stage sees the one push constant block (mesh_lists.comp too). */
#define TR_PUSH_STAGES (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | \
                        VK_SHADER_STAGE_COMPUTE_BIT)

/* Double-precision 3-vectors for the host-side geometry (camera framing, hull meshes). */
static inline void tr_sub3(const double* a, const double* b, double out[3])
{
    for (int i = 0; i < 3; i++) out[i] = a[i] - b[i];
}

static inline void tr_cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double tr_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

typedef struct tr_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
} tr_image;

typedef struct tr_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void* mapped;         /* host-visible buffers stay mapped */
} tr_buffer;

/* A mesh inside the shared vertex and index buffers. */
typedef struct tr_mesh {
    uint32_t first_index, index_count;
    int32_t vertex_offset;
} tr_mesh;

/* A vertex of the unit meshes and of the hull and triangle-mesh shapes' meshes. */
typedef struct tr_vertex { float position[3], normal[3]; } tr_vertex;

/* One hull or triangle-mesh shape's mesh (render_hulls.c), after the unit meshes in the
 * shared vertex and index buffers: drawn from the same bindings (lavapipe at 128-bit
 * vectors crashed, now and then, on draws from a second vertex buffer bound in the same
 * render pass). */
typedef struct tr_shape_draw {
    uint32_t shape_slot;
    uint32_t shape_type;        /* TB_GPU_SHAPE_HULL, _COMPOUND or _MESH */
    uint32_t first_index, index_count;
    int32_t vertex_offset;
} tr_shape_draw;

/* What the host knows of the scene for one frame. */
typedef struct tr_scene {
    int has_plane;            /* a live body with an unbounded AABB */
    int has_bounds;           /* at least one finite AABB */
    double lo[3], hi[3];      /* bounding box of the finite AABBs */
} tr_scene;

/* A camera resolved to matrices. */
typedef struct tr_view {
    tr_camera camera;
    double near_plane, far_plane;
    double floor_y;       /* height of the default grid: the scene's lowest point, else 0 */
    float view_proj[16];
} tr_view;

struct tr_renderer {
    tb_world* world;
    tb_vulkan_device dev;
    tr_options options;
    VkPhysicalDeviceMemoryProperties memory_properties;
    VkFormat depth_format;
    uint32_t max_image_size;
    VkDeviceSize max_storage_range;   /* maxStorageBufferRange: one binding's most bytes */

    VkCommandPool command_pool;
    VkCommandBuffer cb;
    VkFence fence;
    VkRenderPass render_pass;

    /* Size-dependent: re-created by tr_set_options. */
    tr_image color, depth;
    VkFramebuffer framebuffer;
    tr_buffer readback;

    tr_buffer vertices, indices;
    /* The unit meshes by shape type (TB_GPU_SHAPE_*; index_count 0: none for that type),
     * first in the vertex and index buffers. */
    tr_mesh units[TR_SHAPE_TYPES];

    /* Hull and triangle-mesh shapes (render_hulls.c): a mesh per shape, and what the last
     * scan saw. */
    tr_shape_draw* hull_draws;
    uint32_t hull_draw_count;
    tr_shape_draw* mesh_draws;
    uint32_t mesh_draw_count;
    tb_shape_id* shape_ids;        /* per shape slot; index1 0: no live shape */
    uint32_t shape_types;          /* bit 1 << TB_SHAPE_* of each type among those shapes */
    uint32_t shape_capacity;
    int hulls_scanned;
    uint32_t scan_slots, scan_live;

    /* The bodies of each mesh shape, listed on the GPU each frame (render_meshes.c). */
    int mesh_lists_stale;         /* mesh_draws changed since the tables below were written */
    tr_buffer mesh_of_shape;      /* uint per shape slot: its mesh draw, or TR_NO_MESH */
    tr_buffer mesh_commands;      /* an indexed indirect draw per mesh draw */
    tr_buffer mesh_instances;     /* per mesh draw, mesh_capacity body slots */
    uint32_t mesh_capacity;

    VkDescriptorSetLayout set_layout;
    VkDescriptorPool descriptor_pool;
    VkDescriptorSet set;
    int set_written;
    uint64_t set_generation;
    /* The manifold binding, written apart from the bodies' (only when contacts are shown). */
    int contacts_written;
    uint64_t contacts_generation;
    VkBuffer contacts_buffer;
    /* The joint overlay's segments, written by the host each frame (render_joints.c). */
    tr_buffer joint_lines;
    uint32_t joint_line_capacity;   /* vertices it holds */

    VkPipelineLayout pipeline_layout;
    VkPipeline mesh_pipeline, plane_pipeline, line_pipeline, contact_pipeline, joint_pipeline;
    VkPipeline static_pipeline;   /* see-through static bodies: blended, no depth writes */
    VkPipeline mesh_list_pipeline; /* compute: the bodies of each mesh shape */

    tr_camera last_camera;
    int has_frame;
    char error[256];
};

/* render.c */
tb_result tr_fail(tr_renderer* r, tb_result code, const char* fmt, ...);
tb_result tr_vk(tr_renderer* r, VkResult vr, const char* what);

/* render_gpu.c: memory, images, buffers, render pass */
tb_result tr_gpu_init(tr_renderer* r);
tb_result tr_targets_create(tr_renderer* r);
void tr_targets_destroy(tr_renderer* r);
tb_result tr_host_buffer(tr_renderer* r, VkDeviceSize size, VkBufferUsageFlags usage,
                         tr_buffer* out);
void tr_buffer_destroy(tr_renderer* r, tr_buffer* b);
tb_result tr_meshes_create(tr_renderer* r);
void tr_gpu_destroy(tr_renderer* r);

/* render_mesh.c: unit meshes. Each writes its vertices and indices (from its own first
 * vertex) and returns its vertex count. */
typedef uint32_t tr_unit_mesh_fn(tr_vertex* vertices, uint32_t* indices, uint32_t* index_count);
tr_unit_mesh_fn tr_sphere_mesh, tr_cube_mesh, tr_capsule_mesh, tr_cylinder_mesh, tr_cone_mesh;
/// Unit-mesh vertex v of a shape of `type` (TB_GPU_SHAPE_*) sized by the shape's params
/// (tb_gpu_shape.params), in its body frame, as mesh.vert sizes it.
tr_vertex tr_sized_vertex(uint32_t type, const float params[4], const tr_vertex* v);
#define TR_ROUND_SLICES 24
#define TR_SPHERE_STACKS 16     /* even: the capsule splits the sphere at its equator */
#define TR_SPHERE_VERTICES ((TR_ROUND_SLICES + 1) * (TR_SPHERE_STACKS + 1))
#define TR_SPHERE_INDICES (TR_ROUND_SLICES * TR_SPHERE_STACKS * 6)
#define TR_CUBE_VERTICES 24
#define TR_CUBE_INDICES 36
#define TR_CAPSULE_VERTICES ((TR_ROUND_SLICES + 1) * (TR_SPHERE_STACKS + 2))
#define TR_CAPSULE_INDICES (TR_ROUND_SLICES * (TR_SPHERE_STACKS + 1) * 6)
#define TR_CYLINDER_VERTICES (4 * TR_ROUND_SLICES + 6)  /* side 2 rings, caps a ring + centre */
#define TR_CYLINDER_INDICES (12 * TR_ROUND_SLICES)
#define TR_CONE_VERTICES (3 * TR_ROUND_SLICES + 4)      /* side 2 rings, base ring + centre */
#define TR_CONE_INDICES (6 * TR_ROUND_SLICES)
#define TR_UNIT_VERTICES (TR_SPHERE_VERTICES + TR_CUBE_VERTICES + TR_CAPSULE_VERTICES + \
                          TR_CYLINDER_VERTICES + TR_CONE_VERTICES)
#define TR_UNIT_INDICES (TR_SPHERE_INDICES + TR_CUBE_INDICES + TR_CAPSULE_INDICES + \
                         TR_CYLINDER_INDICES + TR_CONE_INDICES)

/* render_hulls.c: hull meshes, and the meshes of hull and triangle-mesh shapes */
/// Triangles (counter-clockwise seen from outside) of the convex hull of `points`, as
/// point indices in a malloc'd *out (3 per triangle); 0 when the points span no volume.
uint32_t tr_hull_triangles(const tb_vec3* points, uint32_t count, uint32_t** out);
/// Bring the hull and triangle-mesh shapes' meshes up to date with the world's shapes.
tb_result tr_hulls_update(tr_renderer* r, const tb_vulkan_bodies* bodies);
void tr_hulls_destroy(tr_renderer* r);

/* render_meshes.c: triangle-mesh shapes */
/// The flat-shaded triangle a, b, c: three vertices, each with the normal of the side from
/// which they run counter-clockwise (zero for a triangle of no area).
void tr_flat_triangle(const tb_vec3* a, const tb_vec3* b, const tb_vec3* c, tr_vertex out[3]);
/// A hull shape's triangles, flat shaded, in a malloc'd *out (3 vertices per triangle).
tb_result tr_hull_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** out,
                           uint32_t* vertex_count);
/// A compound shape's children's triangles in its body frame, likewise (render_compounds.c).
tb_result tr_compound_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** out,
                               uint32_t* vertex_count);
/// A mesh shape's triangles, flat shaded, in a malloc'd *out (3 vertices per triangle).
tb_result tr_mesh_shape_vertices(tr_renderer* r, tb_shape_id id, tr_vertex** out,
                                 uint32_t* vertex_count);
/// Size and fill the mesh draws' tables for a frame of `slots` body slots.
tb_result tr_mesh_lists_prepare(tr_renderer* r, uint32_t slots);
/// Record the pass that lists each mesh shape's bodies (outside the render pass).
void tr_mesh_lists_record(tr_renderer* r, uint32_t slots);
void tr_mesh_lists_destroy(tr_renderer* r);

/* render_joints.c: the joint overlay */
/// Write this frame's joint segments; *vertices receives how many to draw (0: none).
tb_result tr_joints_prepare(tr_renderer* r, uint32_t* vertices);
void tr_joints_destroy(tr_renderer* r);

/* render_pipelines.c: descriptor set, the six graphics pipelines and the compute one */
tb_result tr_pipelines_create(tr_renderer* r);
tb_result tr_bind_bodies(tr_renderer* r, const tb_vulkan_bodies* bodies);
tb_result tr_bind_contacts(tr_renderer* r, const tb_vulkan_contacts* contacts);
void tr_pipelines_destroy(tr_renderer* r);

/* render_camera.c: scene bounds and camera matrices */
tb_result tr_scene_scan(tr_renderer* r, tr_scene* out);
void tr_view_resolve(const tr_options* o, const tr_scene* scene, tr_view* out);
int tr_camera_valid(const tr_camera* c);

#endif
