/* Tumble plugins: the ABI between libtumble and a plugin (a shared object).
 *
 * A plugin exports one function, tb_plugin_entry, which returns a tb_plugin: what the
 * plugin adds to every step of the world that loads it (tb_world_load_plugin, tumble.h).
 *
 * - GPU stages: compute shaders run at named points of the step, inside the step's one
 *   command buffer. A stage is SPIR-V or a GLSL file compiled when the plugin loads; its
 *   shader includes "tumble_plugin.glsl" (abi/), which declares what a stage may read and
 *   write (the body arrays, the pairs, the plugin's parameter block) and must call
 *   tb_plugin_begin() first. The parameter block (up to TB_PLUGIN_MAX_PARAM_BYTES) is set
 *   by the host with tb_world_set_plugin_param and reaches the GPU at the next step.
 * - Host callbacks: for every step, the pairs of bodies whose contact began and ended in it,
 *   with their impulses (found on the GPU; called before tb_world_step returns).
 *
 * Versioning: tb_plugin and tb_plugin_stage start with their size, and tb_plugin with the
 * ABI version the plugin was built for. A library loads plugins built for its version or
 * older ones (fields they do not have read as zero); a plugin built for a newer version is
 * refused. Fields are only ever appended.
 *
 * A plugin that calls the C API from its callbacks needs the tb_* symbols of the process:
 * load it into a program linked with libtumble.so (or with -rdynamic against libtumble.a).
 */
#ifndef TUMBLE_PLUGIN_H
#define TUMBLE_PLUGIN_H

#include "tumble.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TB_PLUGIN_ABI_VERSION 1u
/// The name of the one symbol a plugin exports (a tb_plugin_entry_fn).
#define TB_PLUGIN_ENTRY_NAME "tb_plugin_entry"
#define TB_PLUGIN_MAX_PARAM_BYTES 256u
/// Stages of one plugin. A world runs at most 16 plugin stages in all.
#define TB_PLUGIN_MAX_STAGES 8u
/// Longest plugin or stage name, in bytes without the terminating zero.
#define TB_PLUGIN_MAX_NAME 31u

#if defined(__GNUC__)
#define TB_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define TB_PLUGIN_EXPORT
#endif

/// Where in the step a stage runs. The step: bounds -> broadphase -> narrowphase ->
/// colouring -> forces -> solver -> integration (DESIGN.md §1).
typedef enum tb_plugin_point {
    /// Before anything of the step: changes to poses are seen by this step's collision
    /// detection, changes to velocities by its solver.
    TB_PLUGIN_PRE_STEP = 0,
    /// After the broadphase found this step's pairs (tb_plugin_pair_count), before the
    /// narrowphase.
    TB_PLUGIN_POST_BROADPHASE = 1,
    /// After the solver and integration: the bodies hold this step's new velocities and
    /// poses.
    TB_PLUGIN_POST_SOLVE = 2,
    /// The end of the step, after every other stage (post-solve plugin stages included).
    TB_PLUGIN_POST_STEP = 3,
    TB_PLUGIN_POINT_FORCE_32 = 0x7fffffff
} tb_plugin_point;

/// How many threads a stage runs (workgroups of 64, the shader's local_size_x).
typedef enum tb_plugin_dispatch {
    /// One thread per body slot (tb_plugin_body_count(); dead slots included).
    TB_PLUGIN_PER_BODY = 0,
    /// One thread per pair of this step (tb_plugin_pair_count()); not at TB_PLUGIN_PRE_STEP,
    /// where the step has no pairs yet.
    TB_PLUGIN_PER_PAIR = 1,
    /// tb_plugin_stage.groups workgroups.
    TB_PLUGIN_FIXED = 2,
    TB_PLUGIN_DISPATCH_FORCE_32 = 0x7fffffff
} tb_plugin_dispatch;

typedef struct tb_plugin_stage {
    uint32_t size;                ///< sizeof(tb_plugin_stage)
    const char* name;             ///< the stats show it as "plugin/<plugin>/<name>"
    tb_plugin_point point;
    tb_plugin_dispatch dispatch;
    uint32_t groups;              ///< workgroups of a TB_PLUGIN_FIXED stage, in [1, 65535]
    /// The shader: SPIR-V (spirv_size bytes, Vulkan 1.2, entry point "main"), or, when
    /// spirv is NULL, the path of a GLSL compute shader: absolute, or relative to the
    /// plugin file's directory. "tumble_plugin.glsl" and "layout.h" are always found.
    const uint32_t* spirv;
    size_t spirv_size;
    const char* glsl_path;
} tb_plugin_stage;

/// A pair of bodies whose contact began or ended in a step: a pair is in contact when the
/// narrowphase gave it points (tb_world_read_contacts lists them). A beginning describes
/// the pair in that step, an end the pair in the step before, the last it touched.
typedef struct tb_contact_event {
    tb_body_id a, b;              ///< as tb_world_read_contacts gives them; for an end, a body
                                  ///< destroyed since is the null id
    tb_vec3 point;                ///< the pair's first contact point
    tb_vec3 normal;               ///< from a towards b
    float normal_impulse;         ///< N s, summed over the pair's points
    tb_vec3 friction_impulse;     ///< N s, summed over the pair's points
    uint32_t point_count;
} tb_contact_event;

/// One step's events: beginnings, then ends, each ordered by the bodies' slots.
typedef struct tb_contact_events {
    uint64_t step;                ///< the step: tb_world_stats.steps once it was taken
    const tb_contact_event* begin;
    uint32_t begin_count;
    const tb_contact_event* end;
    uint32_t end_count;
} tb_contact_events;

/// Called for each step in which some contact began or ended, in step order, before the
/// step call returns (tb_world_step_n: once per step that had events). `world` may be
/// queried (see above) but not stepped: tb_world_step, tb_world_step_n,
/// tb_world_load_plugin and tb_world_unload_plugin are refused there. Contacts that
/// already touched when the plugin was loaded do not begin again.
typedef void tb_plugin_contacts_fn(tb_world* world, void* user, const tb_contact_events* events);
/// Check a parameter block before it is taken (tb_world_set_plugin_param): return 0 to
/// accept it, else write a sentence saying what is wrong to `why` (why_size bytes).
typedef int tb_plugin_check_params_fn(void* user, const void* params, char* why, size_t why_size);
/// The plugin is unloaded (or its world destroyed).
typedef void tb_plugin_unload_fn(void* user);

typedef struct tb_plugin {
    uint32_t size;                ///< sizeof(tb_plugin)
    uint32_t abi_version;         ///< TB_PLUGIN_ABI_VERSION
    const char* name;             ///< [a-z0-9_], at most TB_PLUGIN_MAX_NAME bytes
    uint32_t param_bytes;         ///< size of the parameter block, <= TB_PLUGIN_MAX_PARAM_BYTES
    const void* default_params;   ///< param_bytes of initial values; NULL: zeros
    uint32_t stage_count;         ///< <= TB_PLUGIN_MAX_STAGES
    const tb_plugin_stage* stages;
    void* user;                   ///< handed to the callbacks
    tb_plugin_contacts_fn* on_contacts;       ///< NULL: no contact events
    tb_plugin_check_params_fn* check_params;  ///< NULL: any block is taken
    tb_plugin_unload_fn* on_unload;           ///< NULL: nothing to do
} tb_plugin;

/// The entry point: given the library's TB_PLUGIN_ABI_VERSION, the plugin's description
/// (which must stay valid until on_unload), or NULL to refuse.
typedef const tb_plugin* tb_plugin_entry_fn(uint32_t host_abi_version);
/// What a plugin defines (declared here so its definition matches).
TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version);

#ifdef __cplusplus
}
#endif
#endif /* TUMBLE_PLUGIN_H */
