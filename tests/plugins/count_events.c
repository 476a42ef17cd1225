/* A plugin that only counts contact events, for timing what the library's event path costs
 * apart from what a plugin does with the events (tools/bench/plugins). At unload it prints
 * the count to standard error. */
#include <stdio.h>
#include <stdlib.h>

#include "tumble_plugin.h"

typedef struct counter {
    tb_plugin plugin;
    uint64_t events, calls;
} counter;

static void on_contacts(tb_world* world, void* user, const tb_contact_events* events)
{
    (void)world;
    counter* c = user;
    c->events += events->begin_count + events->end_count;
    c->calls++;
}

static void on_unload(void* user)
{
    counter* c = user;
    fprintf(stderr, "count_events: %llu events in %llu steps\n", (unsigned long long)c->events,
            (unsigned long long)c->calls);
    free(c);
}

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    counter* c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->plugin = (tb_plugin){
        .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION,
        .name = "count_events", .user = c, .on_contacts = on_contacts, .on_unload = on_unload,
    };
    return &c->plugin;
}
