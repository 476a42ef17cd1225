/* Standard scenes shared by the tests, tools/bench and `make run`.
 *
 * A scene builds bodies into a world, knows its usual time step, and afterwards checks the
 * world for the figures that the bench reports (nan, escaped, ...). Not part of the
 * library's ABI: tools and tests compile this file in.
 */
#ifndef TUMBLE_SCENES_H
#define TUMBLE_SCENES_H

#include <stdint.h>
#include <stdio.h>
#include "tumble.h"

#define SCENE_MAX_CHECKS 12

/// Named figures a scene reports after a run, e.g. {"nan", 0}, {"escaped", 0}.
typedef struct scene_checks {
    uint32_t count;
    struct { const char* key; double value; } items[SCENE_MAX_CHECKS];
} scene_checks;

typedef struct scene_params {
    uint32_t n;     ///< number of dynamic bodies asked for
    uint32_t seed;  ///< seed of the scene's fixed jitter
} scene_params;

typedef struct scene_instance scene_instance; ///< a scene built into a world

typedef struct scene {
    const char* name;         ///< e.g. "freefall"
    const char* description;  ///< one line
    float dt;                 ///< usual step, s
    uint32_t default_n;
    uint32_t default_steps;
    /// Build the scene into `world`. On success *out holds what check() needs.
    tb_result (*build)(tb_world* world, const scene_params* params, scene_instance** out);
    /// Fill `out` with the scene's figures after `steps` steps of `dt`.
    tb_result (*check)(tb_world* world, const scene_instance* inst, uint32_t steps, float dt,
                       scene_checks* out);
    void (*destroy)(scene_instance* inst);
} scene;

/// The scene of that name, or NULL.
const scene* scene_find(const char* name);
/// All scenes; *count receives how many.
const scene* scene_list(uint32_t* count);
/// The scene `make run` uses.
const scene* scene_default(void);

/// Ids of the bodies a scene built, dynamic ones first (for readers such as `make run`).
const tb_body_id* scene_body_ids(const scene_instance* inst, uint32_t* count);

/* Command-line helpers shared by the tools. */
/// Parse a decimal uint32 (no sign); returns 0 when the text is not one.
int scene_parse_u32(const char* text, uint32_t* out);
/// Print every scene as "  name  description (default n N, steps S)".
void scene_print_list(FILE* f);

#endif
