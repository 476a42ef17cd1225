/* Snapshots: the state a world's next step depends on, saved into a caller's bytes and put
 * back, so that the world (or another with the same shapes) continues bit for bit as the
 * original did from there.
 *
 * What the next step reads, beyond the shapes and the settings:
 * - the bodies: their host records and slot table, and every GPU body array (from the
 *   host mirror, brought up to date first);
 * - last step's pairs (their half of the pair array), its manifolds with their impulses
 *   (warm starting, the block solver's stiffness) and the per-body runs that locate a pair
 *   (body_pairs), which the narrowphase and isap search;
 * - the counters: the steps completed (whose parity picks the halves), the events' marks,
 *   the guard's count;
 * - the host's choices that shape the recorded step: the block solver's lanes a body
 *   (which order sums add up in) and the colouring rounds.
 * - what the broadphase keeps between steps (its `kept` bytes: sap's axis, isap's sorted
 *   endpoints; isap starts afresh where the body capacity differs).
 * Every other GPU buffer is scratch a step fills before reading (growth makes those anew
 * too).
 *
 * The bytes are this library version's and this machine's: a header (magic, version,
 * sizes, a checksum of the rest), then the sections in the order of `layout` below.
 */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define SNAPSHOT_MAGIC "TUMBSNAP"
/* 2: the checksum covers the header too (a flipped step count in it was restored, and the
 * next step's count of completed steps wrapped around). */
#define SNAPSHOT_VERSION 2u

typedef struct snapshot_header {
    char magic[8];
    uint32_t version;
    uint32_t header_bytes;        ///< sizeof(snapshot_header)
    uint64_t total_bytes;
    uint64_t checksum;            ///< FNV-1a of the header (this field 0) and all after it
    uint64_t shapes;              ///< the shapes' fingerprint (shape_fingerprint)
    uint64_t gpu_steps, steps;
    uint32_t record_bytes, manifold_bytes, counters_bytes;   ///< this build's struct sizes
    uint32_t broadphase;          ///< tb_broadphase
    uint32_t block_solver, block_iterations, substeps, solver_iterations;
    uint32_t colour_rounds, block_lanes;
    uint32_t body_set_version;
    uint32_t slots_used, slots_live, free_count;
    uint32_t store_slots;         ///< the body store's slots (high-water)
    uint32_t pairs;               ///< last step's pairs kept (its half of the pair array)
    uint32_t isolated_bodies, guard_seen;
    uint32_t broadphase_bytes;    ///< what the broadphase keeps between steps (its `kept`)
    tb_vec3 gravity;
} snapshot_header;

/* The sections after the header, each an array of `count` elements of `size` bytes. */
enum { SEC_FREE, SEC_RECORDS, SEC_ARRAYS, SEC_BODY_PAIRS = SEC_ARRAYS + TB_ARRAY_COUNT,
       SEC_PAIRS, SEC_MANIFOLDS, SEC_COUNTERS, SEC_BROADPHASE, SEC_COUNT };

typedef struct section { size_t offset, bytes; } section;

/* memcpy for sections that may be empty (their pointers NULL then, which memcpy forbids). */
static void copy_bytes(void* to, const void* from, size_t n)
{
    if (n) memcpy(to, from, n);
}

static void layout(const snapshot_header* h, section out[SEC_COUNT])
{
    size_t bytes[SEC_COUNT];
    bytes[SEC_FREE] = (size_t)h->free_count * sizeof(uint32_t);
    bytes[SEC_RECORDS] = (size_t)h->slots_used * sizeof(tb_body_record);
    for (int a = 0; a < TB_ARRAY_COUNT; a++)
        bytes[SEC_ARRAYS + a] = (size_t)h->store_slots * sizeof(tb_gpu_vec4);
    bytes[SEC_BODY_PAIRS] = (size_t)h->store_slots * 16;
    bytes[SEC_PAIRS] = (size_t)h->pairs * 16;
    bytes[SEC_MANIFOLDS] = (size_t)h->pairs * sizeof(tb_gpu_manifold);
    bytes[SEC_COUNTERS] = sizeof(tb_gpu_counters);
    bytes[SEC_BROADPHASE] = h->broadphase_bytes;
    size_t at = sizeof(snapshot_header);
    for (int s = 0; s < SEC_COUNT; s++) {
        out[s] = (section){ at, bytes[s] };
        at += (bytes[s] + 15) & ~(size_t)15;
    }
}

static size_t total_bytes(const snapshot_header* h)
{
    section s[SEC_COUNT];
    layout(h, s);
    return s[SEC_COUNT - 1].offset + s[SEC_COUNT - 1].bytes;
}

static uint64_t fnv1a(uint64_t h, const void* data, size_t size)
{
    const unsigned char* p = data;
    for (size_t i = 0; i < size; i++) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

/* The checksum of a snapshot of `size` bytes whose header is h: its header with the checksum
 * field 0, then the bytes after the header. */
static uint64_t checksum_of(const snapshot_header* h, const void* data, size_t size)
{
    snapshot_header zeroed = *h;
    zeroed.checksum = 0;
    uint64_t sum = fnv1a(0xcbf29ce484222325ull, &zeroed, sizeof zeroed);
    return fnv1a(sum, (const unsigned char*)data + sizeof *h, size - sizeof *h);
}

/* The shapes as the step sees them: each slot's life and generation, and its GPU entry
 * (without the device addresses of mesh, heightfield and compound images, which differ
 * from process to process). Two worlds whose shapes were made alike give the same. */
static uint64_t shape_fingerprint(const tb_world* w)
{
    uint64_t h = fnv1a(0xcbf29ce484222325ull, &w->shape_slots.used, sizeof(uint32_t));
    for (uint32_t slot = 0; slot < w->shape_slots.used; slot++) {
        const tb_shape_record* s = &w->shapes[slot];
        uint32_t head[3] = { s->alive, s->generation, (uint32_t)s->type };
        h = fnv1a(h, head, sizeof head);
        if (!s->alive) continue;
        tb_gpu_shape g = w->gpu_shapes[slot];
        if (s->mesh || s->heightfield || s->compound) g.hull.x = g.hull.y = 0;
        h = fnv1a(h, &g, sizeof g);
    }
    return h;
}

/* Last step's pairs: its count, or further where a body's run of last step ends further
 * (the midphase split may grow the list after the count was taken). */
static uint32_t last_pairs(const tb_world* w, const tb_gpu_counters* c, const uint32_t* runs)
{
    uint32_t half = (uint32_t)((w->gpu_steps + 1) & 1u), n = w->gpu_steps ? c->state.z : 0;
    for (uint32_t slot = 0; w->gpu_steps && slot < w->store.slots; slot++) {
        const uint32_t* run = runs + 4 * slot + 2 * half;
        if (run[1] && run[0] + run[1] > n) n = run[0] + run[1];
    }
    return n < w->sim.pair_capacity ? n : w->sim.pair_capacity;
}

/* The broadphase's bytes kept between steps (none: bytes 0). */
static VkBuffer broadphase_kept(const tb_world* w, VkDeviceSize* bytes)
{
    VkBuffer buffer = VK_NULL_HANDLE;
    *bytes = 0;
    if (w->broadphase->kept) w->broadphase->kept(&w->bp, &buffer, bytes);
    return buffer;
}

static snapshot_header header_of(const tb_world* w)
{
    snapshot_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, SNAPSHOT_MAGIC, 8);
    h.version = SNAPSHOT_VERSION;
    h.header_bytes = sizeof h;
    h.shapes = shape_fingerprint(w);
    h.gpu_steps = w->gpu_steps;
    h.steps = w->steps;
    h.record_bytes = sizeof(tb_body_record);
    h.manifold_bytes = sizeof(tb_gpu_manifold);
    h.counters_bytes = sizeof(tb_gpu_counters);
    h.broadphase = (uint32_t)w->broadphase_kind;
    h.block_solver = (uint32_t)w->block_solver;
    h.block_iterations = w->block_settings.iterations;
    h.substeps = w->substeps;
    h.solver_iterations = w->solver_iterations;
    h.colour_rounds = w->colour_rounds;
    h.block_lanes = w->block_lanes;
    h.body_set_version = w->body_set_version;
    h.slots_used = w->body_slots.used;
    h.slots_live = w->body_slots.live;
    h.free_count = w->body_slots.free_count;
    h.store_slots = w->store.slots;
    h.isolated_bodies = w->isolated_bodies;
    h.guard_seen = w->guard_seen;
    VkDeviceSize kept;
    broadphase_kept(w, &kept);
    h.broadphase_bytes = (uint32_t)kept;
    h.gravity = w->gravity;
    return h;
}

/* The GPU's part: the body runs, last step's pairs and manifolds, the counters. */
static tb_result download_step_state(tb_world* w, snapshot_header* h, unsigned char* out,
                                     size_t capacity, int sized)
{
    tb_sim* sim = &w->sim;
    uint32_t slots = w->store.slots, cap = sim->pair_capacity;
    uint32_t half = (uint32_t)((w->gpu_steps + 1) & 1u);
    VkDeviceSize pair_bytes = (VkDeviceSize)cap * 16;
    VkDeviceSize manifold_bytes = (VkDeviceSize)cap * sizeof(tb_gpu_manifold);
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, (VkDeviceSize)slots * 16 + pair_bytes + manifold_bytes +
                                       sizeof(tb_gpu_counters) + h->broadphase_bytes + 80);
    if (r) return r;
    const void* runs = slots ? tb_transfer_download(t, sim->body[TB_SIM_BODY_PAIRS].buffer, 0,
                                                    (VkDeviceSize)slots * 16) : NULL;
    const void* pairs = tb_transfer_download(t, sim->pair[TB_SIM_PAIRS].buffer,
                                             half * pair_bytes, pair_bytes);
    const tb_buffer* last = tb_sim_manifolds_of_step(sim, w->gpu_steps + 1);
    const void* manifolds = tb_transfer_download(t, last->buffer, 0, manifold_bytes);
    const void* counters = tb_transfer_download(t, sim->counters.buffer, 0,
                                                sizeof(tb_gpu_counters));
    VkDeviceSize kept_bytes;
    VkBuffer kept_buffer = broadphase_kept(w, &kept_bytes);
    const void* kept = kept_bytes ? tb_transfer_download(t, kept_buffer, 0, kept_bytes) : NULL;
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &t->cb, 1);
    if (r) return r;
    h->pairs = last_pairs(w, counters, runs);
    if (!sized || total_bytes(h) > capacity) return TB_OK;
    section s[SEC_COUNT];
    layout(h, s);
    if (slots) memcpy(out + s[SEC_BODY_PAIRS].offset, runs, s[SEC_BODY_PAIRS].bytes);
    copy_bytes(out + s[SEC_PAIRS].offset, pairs, s[SEC_PAIRS].bytes);
    copy_bytes(out + s[SEC_MANIFOLDS].offset, manifolds, s[SEC_MANIFOLDS].bytes);
    memcpy(out + s[SEC_COUNTERS].offset, counters, s[SEC_COUNTERS].bytes);
    if (kept) memcpy(out + s[SEC_BROADPHASE].offset, kept, s[SEC_BROADPHASE].bytes);
    return TB_OK;
}

tb_result tb_world_save(tb_world* w, void* out, size_t capacity, size_t* size)
{
    if (w->joints.slots.live)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "a world with joints cannot be saved "
                       "yet (snapshots hold bodies, shapes and contacts)");
    /* The hulls packed first: their places in the hull table are part of the shapes. */
    tb_result r = tb_world_prepare_shapes(w);
    if (!r) r = tb_world_fetch(w, (1u << TB_ARRAY_COUNT) - 1u);
    if (r) return r;
    snapshot_header h = header_of(w);
    unsigned char* bytes = out;
    r = download_step_state(w, &h, bytes, capacity, out != NULL);
    if (r) return r;
    h.total_bytes = total_bytes(&h);
    *size = (size_t)h.total_bytes;
    if (!out) return TB_OK;
    if (capacity < h.total_bytes)
        return tb_fail(&w->diag, TB_ERROR_CAPACITY, "the snapshot takes %llu bytes, more than "
                       "the %zu given", (unsigned long long)h.total_bytes, capacity);
    section s[SEC_COUNT];
    layout(&h, s);
    for (int k = 0; k < SEC_COUNT; k++) {   /* the padding after each section */
        size_t end = s[k].offset + s[k].bytes;
        size_t next = k + 1 < SEC_COUNT ? s[k + 1].offset : end;
        memset(bytes + end, 0, next - end);
    }
    copy_bytes(bytes + s[SEC_FREE].offset, w->body_slots.free, s[SEC_FREE].bytes);
    copy_bytes(bytes + s[SEC_RECORDS].offset, w->bodies, s[SEC_RECORDS].bytes);
    for (int a = 0; a < TB_ARRAY_COUNT; a++)
        copy_bytes(bytes + s[SEC_ARRAYS + a].offset, w->store.host[a], s[SEC_ARRAYS + a].bytes);
    h.checksum = checksum_of(&h, bytes, h.total_bytes);
    memcpy(bytes, &h, sizeof h);
    return TB_OK;
}

/* Why the bytes cannot be restored into this world, or NULL. */
static const char* refusal(const tb_world* w, const snapshot_header* h, const void* data,
                           size_t size)
{
    if (size < sizeof *h || memcmp(h->magic, SNAPSHOT_MAGIC, 8) != 0)
        return "the bytes are not a Tumble snapshot";
    if (h->version != SNAPSHOT_VERSION || h->header_bytes != sizeof *h ||
        h->record_bytes != sizeof(tb_body_record) ||
        h->manifold_bytes != sizeof(tb_gpu_manifold) ||
        h->counters_bytes != sizeof(tb_gpu_counters))
        return "the snapshot was made by another version or build of Tumble";
    if (h->total_bytes != size || total_bytes(h) != size)
        return "the snapshot's size does not match its contents (cut short or damaged)";
    if (checksum_of(h, data, size) != h->checksum)
        return "the snapshot's checksum does not match its contents (damaged)";
    if (h->shapes != shape_fingerprint(w))
        return "the world's shapes differ from the snapshot's (make the same shapes in the "
               "same order first)";
    VkDeviceSize kept;
    broadphase_kept(w, &kept);
    if (h->broadphase != (uint32_t)w->broadphase_kind ||
        (h->broadphase_bytes != kept && !w->broadphase->reads_last_pairs))
        return "the snapshot was taken with another broadphase";
    if (h->block_solver != (uint32_t)w->block_solver ||
        h->block_iterations != w->block_settings.iterations || h->substeps != w->substeps ||
        h->solver_iterations != w->solver_iterations)
        return "the snapshot was taken with another solver or other solver settings";
    if (h->slots_live > h->slots_used || h->free_count > h->slots_used ||
        h->store_slots < h->slots_used || h->pairs > tb_sim_pair_limit(&w->sim) ||
        h->colour_rounds > TB_MAX_COLOURS || h->steps != h->gpu_steps ||
        (h->block_lanes != 8 && h->block_lanes != 16 && h->block_lanes != 32))
        return "the snapshot's counts are out of range (damaged)";
    return NULL;
}

/* Why the snapshot's bodies cannot be taken (ids out of range), or NULL. */
static const char* body_refusal(const tb_world* w, const snapshot_header* h,
                                const unsigned char* in, const section* s)
{
    const tb_body_record* records = (const tb_body_record*)(in + s[SEC_RECORDS].offset);
    uint32_t live = 0;
    for (uint32_t slot = 0; slot < h->slots_used; slot++) {
        tb_body_record b;
        memcpy(&b, &records[slot], sizeof b);
        if (!b.alive) continue;
        live++;
        if (b.shape >= w->shape_slots.used || !w->shapes[b.shape].alive ||
            (b.type != TB_BODY_STATIC && b.type != TB_BODY_DYNAMIC))
            return "a body of the snapshot names no shape of this world (damaged)";
    }
    const uint32_t* free_list = (const uint32_t*)(in + s[SEC_FREE].offset);
    for (uint32_t i = 0; i < h->free_count; i++) {
        uint32_t slot;
        memcpy(&slot, &free_list[i], sizeof slot);
        if (slot >= h->slots_used) return "the snapshot's free slots are out of range (damaged)";
    }
    return live == h->slots_live ? NULL : "the snapshot's body count does not match (damaged)";
}

/* The host's part: slot table, records, the body mirror (all of it to upload). */
static tb_result restore_bodies(tb_world* w, const snapshot_header* h, const unsigned char* in,
                                const section* s)
{
    uint32_t* free_list = NULL;
    if (h->free_count) {
        free_list = malloc(s[SEC_FREE].bytes);
        if (!free_list) return tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "out of host memory");
        memcpy(free_list, in + s[SEC_FREE].offset, s[SEC_FREE].bytes);
    }
    /* A shape's users are its bodies and its compounds: only the bodies change hands. */
    for (uint32_t slot = 0; slot < w->body_slots.used; slot++)
        if (w->bodies[slot].alive) w->shapes[w->bodies[slot].shape].users--;
    tb_slots_free(&w->body_slots);
    w->body_slots = (tb_slots){ h->slots_used, h->slots_live, free_list, h->free_count,
                                h->free_count };
    if (w->bodies) memset(w->bodies, 0, (size_t)w->body_record_capacity * sizeof *w->bodies);
    copy_bytes(w->bodies, in + s[SEC_RECORDS].offset, s[SEC_RECORDS].bytes);
    for (uint32_t slot = 0; slot < h->slots_used; slot++)
        if (w->bodies[slot].alive) w->shapes[w->bodies[slot].shape].users++;
    uint32_t slots = w->store.slots > h->store_slots ? w->store.slots : h->store_slots;
    for (int a = 0; a < TB_ARRAY_COUNT; a++) {
        const tb_gpu_vec4* from = (const tb_gpu_vec4*)(in + s[SEC_ARRAYS + a].offset);
        for (uint32_t slot = 0; slot < slots; slot++) {
            tb_gpu_vec4 zero = { 0, 0, 0, 0 };
            *tb_body_store_write(&w->store, (tb_body_array)a, slot) =
                slot < h->store_slots ? from[slot] : zero;
        }
    }
    /* The slots beyond the snapshot's are dead now (uploaded as such), and the step covers
     * the snapshot's slots, as it did (isap checks last step's slot count). */
    w->store.slots = h->store_slots;
    return TB_OK;
}

/* The GPU's part, after the buffers have room: runs, last step's pairs and manifolds,
 * counters. */
static tb_result upload_step_state(tb_world* w, const snapshot_header* h,
                                   const unsigned char* in, const section* s)
{
    tb_sim* sim = &w->sim;
    uint32_t slots = w->store.slots, half = (uint32_t)((h->gpu_steps + 1) & 1u);
    tb_transfer* t = &w->transfer;
    tb_result r = tb_transfer_begin(t, (VkDeviceSize)slots * 16 + s[SEC_PAIRS].bytes +
                                       s[SEC_MANIFOLDS].bytes + sizeof(tb_gpu_counters) +
                                       s[SEC_BROADPHASE].bytes + 80);
    if (r) return r;
    if (slots) {
        unsigned char* runs = tb_transfer_upload(t, sim->body[TB_SIM_BODY_PAIRS].buffer, 0,
                                                 (VkDeviceSize)slots * 16);
        memset(runs, 0, (size_t)slots * 16);
        memcpy(runs, in + s[SEC_BODY_PAIRS].offset, s[SEC_BODY_PAIRS].bytes);
    }
    if (h->pairs) {
        VkDeviceSize base = (VkDeviceSize)half * sim->pair_capacity * 16;
        memcpy(tb_transfer_upload(t, sim->pair[TB_SIM_PAIRS].buffer, base, s[SEC_PAIRS].bytes),
               in + s[SEC_PAIRS].offset, s[SEC_PAIRS].bytes);
        const tb_buffer* last = tb_sim_manifolds_of_step(sim, h->gpu_steps + 1);
        memcpy(tb_transfer_upload(t, last->buffer, 0, s[SEC_MANIFOLDS].bytes),
               in + s[SEC_MANIFOLDS].offset, s[SEC_MANIFOLDS].bytes);
    }
    memcpy(tb_transfer_upload(t, sim->counters.buffer, 0, sizeof(tb_gpu_counters)),
           in + s[SEC_COUNTERS].offset, sizeof(tb_gpu_counters));
    memcpy(sim->readback.mapped, in + s[SEC_COUNTERS].offset, sizeof(tb_gpu_counters));
    VkDeviceSize kept_bytes;
    VkBuffer kept = broadphase_kept(w, &kept_bytes);
    if (kept_bytes && kept_bytes == h->broadphase_bytes)
        memcpy(tb_transfer_upload(t, kept, 0, kept_bytes), in + s[SEC_BROADPHASE].offset,
               kept_bytes);
    r = tb_transfer_end(t);
    if (!r) r = tb_gpu_submit_wait(&w->gpu, &t->cb, 1);
    return r;
}

tb_result tb_world_load(tb_world* w, const void* data, size_t size)
{
    if (w->joints.slots.live)
        return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "a snapshot cannot be restored into "
                       "a world with joints (snapshots hold no joints yet)");
    tb_result r = tb_world_prepare_shapes(w);   /* as tb_world_save fingerprints them */
    if (r) return r;
    snapshot_header h;
    memset(&h, 0, sizeof h);
    if (size >= sizeof h) memcpy(&h, data, sizeof h);
    const char* why = refusal(w, &h, data, size);
    section s[SEC_COUNT];
    layout(&h, s);
    if (!why) why = body_refusal(w, &h, data, s);
    if (why) return tb_fail(&w->diag, TB_ERROR_INVALID_ARGUMENT, "tb_world_restore: %s", why);
    const unsigned char* in = data;
    /* Room first: until here nothing changed, and growing keeps what the world holds. */
    r = tb_bodies_reserve_records(w, h.slots_used);
    if (!r) r = tb_world_reserve_bodies(w, h.store_slots);
    if (!r) r = tb_sim_reserve_pairs(&w->sim, &w->transfer, h.pairs);
    if (!r) r = tb_world_flush(w);
    if (r) return r;
    r = restore_bodies(w, &h, in, s);
    if (!r) r = upload_step_state(w, &h, in, s);
    if (r) return r;
    w->gpu_steps = h.gpu_steps;
    w->steps = h.steps;
    w->body_set_version = h.body_set_version;
    w->colour_rounds = h.colour_rounds;
    w->block_rounds = 0;   /* this world's own steps find how few it needs */
    w->block_lanes = h.block_lanes;
    w->isolated_bodies = h.isolated_bodies;
    w->guard_seen = h.guard_seen;
    w->gravity = h.gravity;
    w->events.begin.count = w->events.end.count = 0;
    /* isap's state for another body capacity does not fit: it starts afresh. */
    VkDeviceSize kept;
    broadphase_kept(w, &kept);
    if (kept != h.broadphase_bytes) r = w->broadphase->reserve(&w->bp, w->store.capacity);
    w->step_built = 0;
    w->buffer_generation++;
    return r ? r : tb_world_flush(w);
}
