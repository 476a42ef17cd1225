/* The joint graph's colouring on the host, which the GPU's colouring takes as its first
 * priority (glsl/block/colour.comp).
 *
 * The GPU colours bodies in rounds by a priority (Jones and Plassmann): each body takes the
 * smallest colour its higher-priority neighbours leave, so the colouring it finds is the
 * greedy colouring in priority order. Hashed priorities give a net of joints (a grid of
 * ball joints, two-colourable) five or six colours, and in a world of joints a colour costs
 * a dispatch in each of the solve's sweeps, bound by its latency, not by its bodies. So the
 * host colours the joint graph, which changes only when joints come and go, greedily in
 * breadth-first order: on a connected graph without odd cycles (a chain, a net, a tree such
 * as a ragdoll, a car's wheels on its chassis) every body at an even depth takes colour 0
 * and every body at an odd one colour 1. That colour is the body's rank (body_info.z): the
 * GPU orders bodies by rank first, then by its own priority, so the joint graph's bodies
 * colour as the host did unless contacts between them ask for more. A body without joints
 * has rank 0, as in a world without joints, whose colouring is unchanged.
 */
#include <stdlib.h>
#include <string.h>

#include "world/world.h"

#define TB_RANK_MOST 255u

typedef struct rank_graph {
    uint32_t* first;   /* per body slot + 1: its run of neighbours in `next` */
    uint32_t* next;    /* neighbour slots, two entries a joint */
    uint32_t* colour;  /* per body slot, UINT32_MAX while uncoloured */
    uint32_t* queue;
} rank_graph;

static int joint_counts(const tb_world* w, const tb_joint_record* j)
{
    return j->alive && w->bodies[j->body_a].type == TB_BODY_DYNAMIC &&
           w->bodies[j->body_b].type == TB_BODY_DYNAMIC && j->body_a != j->body_b;
}

/* The joints between dynamic bodies as an adjacency list (counting sort by body). */
static void build_graph(const tb_world* w, rank_graph* g, uint32_t bodies)
{
    memset(g->first, 0, (bodies + 1) * sizeof *g->first);
    for (uint32_t s = 0; s < w->joints.slots.used; s++) {
        const tb_joint_record* j = &w->joints.records[s];
        if (!joint_counts(w, j)) continue;
        g->first[j->body_a + 1]++;
        g->first[j->body_b + 1]++;
    }
    for (uint32_t i = 0; i < bodies; i++) g->first[i + 1] += g->first[i];
    uint32_t* fill = g->queue;   /* free until the walk */
    memcpy(fill, g->first, bodies * sizeof *fill);
    for (uint32_t s = 0; s < w->joints.slots.used; s++) {
        const tb_joint_record* j = &w->joints.records[s];
        if (!joint_counts(w, j)) continue;
        g->next[fill[j->body_a]++] = j->body_b;
        g->next[fill[j->body_b]++] = j->body_a;
    }
}

/* The smallest colour none of v's coloured neighbours has. */
static uint32_t free_colour(const rank_graph* g, uint32_t v)
{
    uint64_t taken = 0;
    for (uint32_t e = g->first[v]; e < g->first[v + 1]; e++) {
        uint32_t c = g->colour[g->next[e]];
        if (c < 64) taken |= 1ull << c;
    }
    uint32_t c = 0;
    while (c < 64 && (taken >> c & 1u)) c++;
    return c;
}

/* Greedy colours in breadth-first order from each body not yet reached. */
static void colour_graph(rank_graph* g, uint32_t bodies)
{
    for (uint32_t i = 0; i < bodies; i++) g->colour[i] = UINT32_MAX;
    for (uint32_t root = 0; root < bodies; root++) {
        if (g->colour[root] != UINT32_MAX || g->first[root] == g->first[root + 1]) continue;
        uint32_t head = 0, tail = 0;
        g->queue[tail++] = root;
        g->colour[root] = 0;
        while (head < tail) {
            uint32_t v = g->queue[head++];
            for (uint32_t e = g->first[v]; e < g->first[v + 1]; e++) {
                uint32_t o = g->next[e];
                if (g->colour[o] != UINT32_MAX) continue;
                g->colour[o] = free_colour(g, o);
                g->queue[tail++] = o;
            }
        }
    }
}

/* Each body's rank into body_info.z, uploading only those that changed. */
static void write_ranks(tb_world* w, const rank_graph* g, uint32_t bodies)
{
    const tb_gpu_uvec4* info = (const tb_gpu_uvec4*)w->store.host[TB_ARRAY_INFO];
    for (uint32_t i = 0; i < bodies; i++) {
        uint32_t c = g->colour[i];
        uint32_t rank = !w->bodies[i].alive || c == UINT32_MAX ? 0
                      : c < TB_RANK_MOST ? c : TB_RANK_MOST;
        if (info[i].z == rank) continue;
        tb_gpu_uvec4* out = (tb_gpu_uvec4*)tb_body_store_write(&w->store, TB_ARRAY_INFO, i);
        out->z = rank;
    }
}

tb_result tb_world_rank_joint_bodies(tb_world* w)
{
    if (!w->joint_ranks_dirty) return TB_OK;
    uint32_t bodies = w->body_slots.used, ends = 2 * w->joints.slots.used;
    rank_graph g = {
        .first = malloc((bodies + 1) * sizeof(uint32_t)),
        .next = malloc((ends ? ends : 1) * sizeof(uint32_t)),
        .colour = malloc((bodies ? bodies : 1) * sizeof(uint32_t)),
        .queue = malloc((bodies ? bodies : 1) * sizeof(uint32_t)),
    };
    tb_result r = TB_OK;
    if (!g.first || !g.next || !g.colour || !g.queue) {
        r = tb_fail(&w->diag, TB_ERROR_OUT_OF_MEMORY, "no host memory to colour the joint "
                    "graph of %u bodies", bodies);
    } else {
        build_graph(w, &g, bodies);
        colour_graph(&g, bodies);
        write_ranks(w, &g, bodies);
        w->joint_ranks_dirty = 0;
    }
    free(g.first);
    free(g.next);
    free(g.colour);
    free(g.queue);
    return r;
}
