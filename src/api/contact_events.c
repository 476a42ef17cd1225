/* Contact events for plugins: after a step call, the pairs whose contact began or ended
 * since the previous call. A pair is in contact when tb_world_read_contacts lists a point
 * of it. Only worlds with a plugin that wants the events read the contacts back. */
#include <stdlib.h>
#include <string.h>

#include "api/world.h"

static int wants_events(const tb_world* w)
{
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++)
        if (w->plugins.slots[i].alive && w->plugins.slots[i].desc.on_contacts) return 1;
    return 0;
}

static tb_result reserve(tb_world* w, tb_contact_pairs* list, uint32_t count)
{
    if (count <= list->capacity) return TB_OK;
    uint32_t cap = list->capacity ? list->capacity : 64;
    while (cap < count) cap *= 2;
    tb_contact_event* grown = realloc(list->pairs, cap * sizeof *grown);
    if (!grown) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    list->pairs = grown;
    list->capacity = cap;
    return TB_OK;
}

static tb_result read_contacts(tb_world* w, uint32_t* count)
{
    tb_plugins* p = &w->plugins;
    tb_result r = tb_world_read_contacts(w, p->contacts, p->contact_capacity, count);
    if (r || *count <= p->contact_capacity) return r;
    tb_contact* grown = realloc(p->contacts, *count * sizeof *grown);
    if (!grown) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
    p->contacts = grown;
    p->contact_capacity = *count;
    return tb_world_read_contacts(w, p->contacts, p->contact_capacity, count);
}

static int same_pair(const tb_contact_event* e, const tb_contact* c)
{
    return memcmp(&e->a, &c->a, sizeof c->a) == 0 && memcmp(&e->b, &c->b, sizeof c->b) == 0;
}

static uint64_t key_of(const tb_contact_event* e)
{
    return (uint64_t)e->a.index1 << 32 | e->b.index1;
}

static int by_key(const void* x, const void* y)
{
    uint64_t a = key_of(x), b = key_of(y);
    return a < b ? -1 : a > b;
}

/* One event per pair (its points are consecutive), impulses summed; sorted by pair. */
static tb_result gather_pairs(tb_world* w, const tb_contact* c, uint32_t count)
{
    tb_contact_pairs* now = &w->plugins.current;
    now->count = 0;
    for (uint32_t i = 0; i < count; i++) {
        tb_contact_event* e = now->count ? &now->pairs[now->count - 1] : NULL;
        if (!e || !same_pair(e, &c[i])) {
            tb_result r = reserve(w, now, now->count + 1);
            if (r) return r;
            e = &now->pairs[now->count++];
            *e = (tb_contact_event){ .a = c[i].a, .b = c[i].b, .point = c[i].point,
                                     .normal = c[i].normal };
        }
        e->normal_impulse += c[i].normal_impulse;
        e->friction_impulse.x += c[i].friction_impulse.x;
        e->friction_impulse.y += c[i].friction_impulse.y;
        e->friction_impulse.z += c[i].friction_impulse.z;
        e->point_count++;
    }
    if (now->count > 1) qsort(now->pairs, now->count, sizeof *now->pairs, by_key);
    return TB_OK;
}

static tb_result push(tb_world* w, tb_contact_pairs* list, const tb_contact_event* e)
{
    tb_result r = reserve(w, list, list->count + 1);
    if (!r) list->pairs[list->count++] = *e;
    return r;
}

/* Walk both sorted lists: pairs only now began, pairs only before ended. A pair whose
 * slots were reused by other bodies (new generations) is a different pair. */
static tb_result compare(tb_world* w)
{
    tb_plugins* p = &w->plugins;
    p->begin.count = p->end.count = 0;
    uint32_t i = 0, j = 0;
    tb_result r = TB_OK;
    while (!r && (i < p->current.count || j < p->previous.count)) {
        const tb_contact_event* now = i < p->current.count ? &p->current.pairs[i] : NULL;
        const tb_contact_event* before = j < p->previous.count ? &p->previous.pairs[j] : NULL;
        int order = !now ? 1 : !before ? -1 : by_key(now, before);
        if (order == 0 && memcmp(&now->a, &before->a, sizeof now->a) == 0 &&
            memcmp(&now->b, &before->b, sizeof now->b) == 0) {
            i++, j++;
            continue;
        }
        if (order <= 0) r = push(w, &p->begin, &p->current.pairs[i++]);
        if (!r && order >= 0) r = push(w, &p->end, &p->previous.pairs[j++]);
    }
    return r;
}

static void deliver(tb_world* w)
{
    tb_plugins* p = &w->plugins;
    if (!p->begin.count && !p->end.count) return;
    tb_contact_events events = { w->steps, p->begin.pairs, p->begin.count, p->end.pairs,
                                 p->end.count };
    for (uint32_t i = 0; i < TB_MAX_PLUGINS; i++) {
        tb_plugin_record* plugin = &p->slots[i];
        if (plugin->alive && plugin->desc.on_contacts)
            plugin->desc.on_contacts(w, plugin->desc.user, &events);
    }
}

tb_result tb_plugins_after_step(tb_world* w)
{
    tb_plugins* p = &w->plugins;
    if (!wants_events(w)) {
        p->previous.count = 0;
        return TB_OK;
    }
    uint32_t count = 0;
    tb_result r = read_contacts(w, &count);
    if (!r) r = gather_pairs(w, p->contacts, count);
    if (!r) r = compare(w);
    if (r) return r;
    tb_contact_pairs swap = p->previous;
    p->previous = p->current;
    p->current = swap;
    deliver(w);
    return TB_OK;
}
