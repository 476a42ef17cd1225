/* A plugin whose contact callback tries to step its world and to destroy it, which the
 * plugin ABI forbids (tests/test_plugin.c): the library refuses both and the outer step
 * goes on. */
#include "tumble_plugin.h"

static void on_contacts(tb_world* world, void* user, const tb_contact_events* events)
{
    (void)user;
    (void)events;
    tb_world_step(world, 1.0f / 60.0f);
    tb_world_destroy(world);
}

static const tb_plugin plugin = {
    .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION, .name = "nested_step",
    .on_contacts = on_contacts,
};

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    return &plugin;
}
