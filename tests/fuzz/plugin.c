/* The fuzz target's plugin: its entry point hands the loader whatever description the
 * target put in tb_fuzz_plugin_given (tests/fuzz/fuzz_api.c), NULL included. */
#include "tumble_plugin.h"

TB_PLUGIN_EXPORT const tb_plugin* tb_fuzz_plugin_given;

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    return tb_fuzz_plugin_given;
}
