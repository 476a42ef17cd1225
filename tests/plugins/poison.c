/* A plugin that breaks one body on purpose (tests/test_plugin.c, the guard): while its
 * parameter block's x is 1, its stage after the broadphase (so the body keeps its pairs) writes NaN into the velocity of the body in
 * slot y (index1 - 1). */
#include "tumble_plugin.h"

static const float defaults[4] = { 0, 0, 0, 0 };

static const tb_plugin_stage stages[] = { {
    .size = sizeof(tb_plugin_stage), .name = "poison", .point = TB_PLUGIN_POST_BROADPHASE,
    .dispatch = TB_PLUGIN_PER_BODY, .glsl_path = "poison.comp",
} };

static const tb_plugin plugin = {
    .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION, .name = "poison",
    .param_bytes = sizeof defaults, .default_params = defaults,
    .stage_count = 1, .stages = stages,
};

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    return &plugin;
}
