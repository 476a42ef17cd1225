/* tools/render: draws a Tumble world with Vulkan graphics on the world's own device,
 * reading poses straight from the world's GPU buffers (no round trip through the host, but
 * for the joint overlay's lines).
 *
 * Headless: frames go to an offscreen image, read back as RGBA8 or written as PNG.
 * With GLFW and a display, tr_window_run shows the simulation live.
 * Not part of libtumble's ABI: tools, tests and examples compile it in (prefix tr_).
 */
#ifndef TUMBLE_RENDER_H
#define TUMBLE_RENDER_H

#include <stdint.h>
#include "tumble.h"

typedef struct tr_renderer tr_renderer;

typedef enum tr_color_mode {
    TR_COLOR_BY_ID = 0,     ///< a fixed colour per body slot (hashed)
    TR_COLOR_BY_SPEED = 1,  ///< blue (at rest) to red (fast, >= speed_scale m/s)
    TR_COLOR_BY_SHAPE = 2,  ///< one colour per shape type
} tr_color_mode;

typedef struct tr_camera {
    tb_vec3 eye;           ///< m, world space
    tb_vec3 target;        ///< point looked at
    tb_vec3 up;            ///< usually (0, 1, 0)
    float fov_y_degrees;   ///< vertical field of view, usually 45
    int automatic;         ///< 1: frame every finite body's AABB from a fixed direction
} tr_camera;

typedef struct tr_options {
    uint32_t width, height;    ///< pixels; default 960 x 540
    tr_camera camera;          ///< default automatic
    tr_color_mode color;       ///< default TR_COLOR_BY_ID
    float speed_scale;         ///< m/s that maps to full red in TR_COLOR_BY_SPEED; default 10
    int show_aabbs;            ///< draw world AABBs as lines; default 0
    int show_grid;             ///< ground grid on planes (or at y = 0 without one); default 1
    /// Draw the last step's contacts: each point a small magenta cross, its normal (from
    /// body a towards b) a short yellow line; depth-tested against the scene (lifted a
    /// little towards the eye, so contacts on visible surfaces show whole). Default 0.
    int show_contacts;
    /// Draw the joints (render_joints.c): each a dark blue line from body a's centre to its
    /// anchor and from b's anchor to b's centre, and a red one between the two anchors
    /// (where a joint has come apart, or a distance joint's rod); over the scene, not
    /// depth-tested, so a chain or ragdoll shows as its skeleton. Default 1.
    int show_joints;
    /// Opacity of static bodies other than planes (container walls, floors), 0..1. Below 1
    /// their faces that look up (within about 45 degrees: floors, tops of walls) stay
    /// opaque and the others are drawn last, blended over what they hide (only those turned
    /// towards the eye), so a pile inside a container shows through the walls. Default
    /// 0.3; 1 draws them opaque.
    float static_opacity;
} tr_options;

tr_options tr_default_options(void);

/// A renderer for `world` (the world must outlive it).
tb_result tr_create(tb_world* world, const tr_options* options, tr_renderer** out);
void tr_destroy(tr_renderer* r);
/// Change camera, colours, overlays (size changes re-create the images).
tb_result tr_set_options(tr_renderer* r, const tr_options* options);
/// Draw the world as it is now into the offscreen image.
tb_result tr_render(tr_renderer* r);
/// Copy the last frame out as width*height RGBA8, rows top to bottom.
tb_result tr_read_pixels(tr_renderer* r, uint8_t* rgba);
/// Write the last frame as a PNG file.
tb_result tr_write_png(tr_renderer* r, const char* path);
/// The camera used for the last frame (the automatic one resolved).
tr_camera tr_last_camera(const tr_renderer* r);
/// What went wrong in the last failed call.
const char* tr_last_error(const tr_renderer* r);

/* ---- window (GLFW; optional) -------------------------------------------------------- */

/// Extensions the world must enable so frames can be shown in a window.
typedef struct tr_window_extensions {
    const char* instance[16];
    uint32_t instance_count;
    const char* device[1];
    uint32_t device_count;
} tr_window_extensions;

/// Start GLFW and list the extensions a window needs. Fails (with a sentence in *why)
/// when Tumble was built without GLFW or there is no display.
tb_result tr_window_prepare(tr_window_extensions* out, const char** why);

/// Called once per shown frame to advance the simulation; return 0 to stop.
typedef int tr_frame_fn(void* user);

/// Open a width x height window (the renderer's size) and show the renderer's frames until
/// the window closes or `frame` returns 0. The world must have been created with
/// tr_window_prepare's extensions (tb_world_create_vulkan). On failure *why says why.
tb_result tr_window_run(tr_renderer* r, tb_world* world, uint32_t width, uint32_t height,
                        const char* title, tr_frame_fn* frame, void* user, const char** why);

#endif
