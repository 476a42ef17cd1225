/* Example plugin: logs contact events, one line each, from the host callback.
 *
 *   step 12 begin 3:1 7:1 points 2 normal_impulse 0.25 friction_impulse 0 0 0.01
 *        point 0 0.5 0 normal 0 1 0
 *
 * (on one line; ids as index:generation; per step, beginnings then ends, each in the
 * order of the bodies' slots). Lines go to the file named by the environment
 * variable TB_CONTACT_LOG when the plugin loads (appended), else to standard output. Each
 * load gets its own tb_plugin and file, so several worlds may load it.
 */
#include <stdio.h>
#include <stdlib.h>

#include "tumble_plugin.h"

typedef struct logger {
    tb_plugin plugin;
    FILE* out;
} logger;

static void write_event(FILE* out, uint64_t step, const char* what, const tb_contact_event* e)
{
    fprintf(out, "step %llu %s %u:%u %u:%u points %u normal_impulse %.9g "
            "friction_impulse %.9g %.9g %.9g point %.9g %.9g %.9g normal %.9g %.9g %.9g\n",
            (unsigned long long)step, what, e->a.index1, e->a.generation, e->b.index1,
            e->b.generation, e->point_count, (double)e->normal_impulse,
            (double)e->friction_impulse.x, (double)e->friction_impulse.y,
            (double)e->friction_impulse.z, (double)e->point.x, (double)e->point.y,
            (double)e->point.z, (double)e->normal.x, (double)e->normal.y, (double)e->normal.z);
}

static void on_contacts(tb_world* world, void* user, const tb_contact_events* events)
{
    (void)world;
    logger* log = user;
    for (uint32_t i = 0; i < events->begin_count; i++)
        write_event(log->out, events->step, "begin", &events->begin[i]);
    for (uint32_t i = 0; i < events->end_count; i++)
        write_event(log->out, events->step, "end", &events->end[i]);
    fflush(log->out);
}

static void on_unload(void* user)
{
    logger* log = user;
    if (log->out != stdout) fclose(log->out);
    free(log);
}

TB_PLUGIN_EXPORT const tb_plugin* tb_plugin_entry(uint32_t host_abi_version)
{
    (void)host_abi_version;
    logger* log = calloc(1, sizeof *log);
    if (!log) return NULL;
    const char* path = getenv("TB_CONTACT_LOG");
    log->out = path && *path ? fopen(path, "a") : stdout;
    if (!log->out) {
        free(log);
        return NULL;
    }
    log->plugin = (tb_plugin){
        .size = sizeof(tb_plugin), .abi_version = TB_PLUGIN_ABI_VERSION,
        .name = "contact_logger", .user = log, .on_contacts = on_contacts,
        .on_unload = on_unload,
    };
    return &log->plugin;
}
