/* src/api/: the public entry points of include/tumble.h and tumble_vulkan.h, and nothing
 * else. Each checks its arguments (NULLs, definitions, finite numbers, ids) and then calls
 * the world (src/world/); a refused call changes nothing.
 *
 *   world.c     create and destroy, step, gravity, stats, errors, shader directory
 *   body.c      bodies: defs checked and resolved (mass, inertia), poses, velocities, reads
 *   shape.c     shapes: materials and geometry checked, mass properties per unit mass
 *   round_shape.c  capsules, cylinders and cones: checks, mass properties, their sizes
 *   contacts.c  the last step's contacts
 *   plugin.c    loading and unloading plugins, their parameters
 *   vulkan.c    Vulkan interop (tumble_vulkan.h)
 *   defaults.c  every default definition
 *
 * This header is what the API's own files share; nothing outside src/api/ includes it. */
#ifndef TB_API_API_H
#define TB_API_API_H

#include "gpu/device.h"
#include "layout.h"
#include "tumble.h"

/// tb_world_create with extra device options (extensions) for Vulkan embedders: checks the
/// def, then builds the world; remembers the error of a world that could not be made.
tb_result tb_api_world_create(const tb_world_def* def, const tb_gpu_options* extra,
                              tb_world** out);

/// Refuses `call` while plugins' contact callbacks run (within a step), with its sentence.
tb_result tb_api_refuse_in_callbacks(tb_world* w, const char* call);

/// A shape def's checks (initialised, density, friction, restitution) and out not NULL.
tb_result tb_api_check_shape_def(tb_world* w, const tb_shape_def* def, tb_shape_id* out);

/// A GPU shape of the given type, local box centred on the origin with half extents `half`.
tb_gpu_shape tb_api_gpu_shape(uint32_t type, tb_vec3 half, tb_gpu_vec4 params);

#endif
