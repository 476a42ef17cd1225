/* A plugin: counts the contacts that begin and end, and says so when it is unloaded.
 *
 *   cc -shared -fPIC plugin_counter.c $(pkg-config --cflags tumble) -o plugin_counter.so
 *
 * A plugin is a shared object exporting tb_plugin_entry, which returns a tb_plugin: its
 * name, its GPU stages (none here; see tools/plugins/blast.c for one) and its host
 * callbacks. The library finds the step's contact events on the GPU, only while a loaded
 * plugin asks for them, and hands them over after each step that has any. */
#include <stdio.h>
#include <stdlib.h>

#include "tumble_plugin.h"

typedef struct counter {
    tb_plugin plugin;
    uint64_t begun, ended, steps;
} counter;

static void on_contacts(tb_world* world, void* user, const tb_contact_events* events)
{
    (void)world;
    counter* c = user;
    c->begun += events->begin_count;
    c->ended += events->end_count;
    c->steps++;
}

static void on_unload(void* user)
{
    counter* c = user;
    printf("plugin_counter: %llu contacts began and %llu ended over %llu steps with events\n",
           (unsigned long long)c->begun, (unsigned long long)c->ended,
           (unsigned long long)c->steps);
    free(c);
}

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;   /* this plugin needs nothing newer than version 1 */
    counter* c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->plugin = (tb_plugin){
        .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION,
        .name = "counter", .user = c, .on_contacts = on_contacts, .on_unload = on_unload,
    };
    return &c->plugin;
}
