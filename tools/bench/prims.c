/* bench-prims: GPU time of the parallel primitives (sort, scan, compaction) at several sizes.
 *
 *   bench-prims [--sizes N,N,...] [--reps R] [--key-bits B] [--passes 1]
 *
 * Each primitive's pass list is recorded once per size with the count in GPU memory, as
 * the step uses it; timestamps bracket each repetition, and the inputs are restored (by a
 * copy outside the brackets) before each one, so every sort sees the same random keys.
 * Prints one line per size: median GPU microseconds and elements per second of each
 * primitive; with --passes 1 also the median of every pass of the sort and the scan.
 * Uses the library's GPU layer (src/gpu/) alone: no world, only the device, memory, the
 * pipelines and the primitives.
 */
#include "gpu/device.h"
#include "gpu/memory.h"
#include "gpu/pipeline.h"
#include "gpu/prims.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SIZES 16
#define MAX_REPS 64

typedef struct bench {
    tb_diag diag;
    tb_gpu gpu;
    tb_memory memory;
    tb_pipelines pipelines;
    tb_prims prims;
    tb_buffer work, pristine, scratch, host;
    uint32_t capacity;
    VkQueryPool queries;
    VkCommandBuffer cb;
    double ns_per_tick;
} bench;

static void die(const char* what, const bench* b)
{
    fprintf(stderr, "bench-prims: %s: %s\n", what, b ? b->diag.message : "");
    exit(1);
}

static uint64_t rng_next(uint64_t* s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}

/* Layout of `work` and `pristine`: count word, keys, values (also flags / scan input). */
static VkDeviceSize keys_offset(void) { return 256; }
static VkDeviceSize values_offset(const bench* b) { return 256 + 4 * (VkDeviceSize)b->capacity; }

static void setup(bench* b, uint32_t capacity, uint32_t reps)
{
    memset(b, 0, sizeof *b);
    tb_gpu_options options;
    memset(&options, 0, sizeof options);   /* the device: TUMBLE_DEVICE, else the best GPU */
    if (tb_gpu_create(&b->gpu, &options, &b->diag) || tb_memory_init(&b->memory, &b->gpu) ||
        tb_pipelines_init(&b->pipelines, &b->gpu, NULL))
        die("device", b);
    if (tb_prims_init(&b->prims, &b->pipelines) != TB_OK) die("prims", b);
    b->capacity = capacity;
    VkDeviceSize bytes = values_offset(b) + 4 * (VkDeviceSize)capacity;
    VkBufferUsageFlags copy = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkDeviceSize scratch = tb_prims_sort_scratch(&b->prims, capacity);
    VkDeviceSize scan = tb_prims_scan_scratch(&b->prims, capacity);
    if (scan > scratch) scratch = scan;
    if (tb_buffer_create(&b->memory, bytes, copy | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 0, &b->work) ||
        tb_buffer_create(&b->memory, bytes, copy, 0, &b->pristine) ||
        tb_buffer_create(&b->memory, scratch, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                         VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, 0, &b->scratch) ||
        tb_buffer_create(&b->memory, bytes, copy, 1, &b->host))
        die("buffers", b);
    VkQueryPoolCreateInfo qi = { .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                 .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 64 * reps };
    if (vkCreateQueryPool(b->gpu.device, &qi, NULL, &b->queries) != VK_SUCCESS) die("queries", b);
    if (tb_gpu_command_buffer(&b->gpu, &b->cb)) die("command buffer", b);
    b->ns_per_tick = b->gpu.props.limits.timestampPeriod;
}

static void teardown(bench* b)
{
    vkDestroyQueryPool(b->gpu.device, b->queries, NULL);
    tb_buffer_destroy(&b->memory, &b->host);
    tb_buffer_destroy(&b->memory, &b->scratch);
    tb_buffer_destroy(&b->memory, &b->pristine);
    tb_buffer_destroy(&b->memory, &b->work);
    tb_prims_destroy(&b->prims);
    tb_pipelines_destroy(&b->pipelines);
    tb_memory_destroy(&b->memory);
    tb_gpu_destroy(&b->gpu);
}

static void barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkAccessFlags sa,
                    VkPipelineStageFlags dst, VkAccessFlags da)
{
    VkMemoryBarrier m = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = sa,
                          .dstAccessMask = da };
    vkCmdPipelineBarrier(cb, src, dst, 0, 1, &m, 0, NULL, 0, NULL);
}

static void begin(bench* b)
{
    VkCommandBufferBeginInfo bi = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO };
    vkBeginCommandBuffer(b->cb, &bi);
}

static void submit(bench* b)
{
    vkEndCommandBuffer(b->cb);
    if (tb_gpu_submit_wait(&b->gpu, &b->cb, 1)) die("submit", b);
}

/* Random keys and values (or flags with the given density, or small scan values) and the
 * count, host -> pristine. */
static void upload(bench* b, uint32_t n, int what)
{
    uint32_t* words = b->host.mapped;
    uint32_t* keys = (uint32_t*)((char*)b->host.mapped + keys_offset());
    uint32_t* values = (uint32_t*)((char*)b->host.mapped + values_offset(b));
    uint64_t s = 0x2545f4914f6cdd1dull ^ n;
    words[0] = n;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t r = (uint32_t)(rng_next(&s) >> 32);
        keys[i] = what == 0 ? r : (r % 100);           /* sort keys, or scan values */
        values[i] = what == 0 ? i : (r % 4 == 0);       /* sort values, or flags (1/4 set) */
    }
    begin(b);
    VkBufferCopy all = { 0, 0, b->host.size };
    vkCmdCopyBuffer(b->cb, b->host.buffer, b->pristine.buffer, 1, &all);
    submit(b);
}

static int compare_double(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return x < y ? -1 : x > y;
}

static double median(double* x, uint32_t n)
{
    qsort(x, n, sizeof x[0], compare_double);
    return x[n / 2];
}

/* Record reps x (restore inputs, timestamp, passes, timestamp) and return the median us.
 * With per_pass, a timestamp follows every pass and per_pass[i] gets pass i's median. */
static double time_list(bench* b, const tb_pass_list* list, uint32_t reps, double* per_pass)
{
    uint32_t stamps = per_pass ? list->count + 1 : 2;
    begin(b);
    vkCmdResetQueryPool(b->cb, b->queries, 0, stamps * reps);
    VkBufferCopy all = { 0, 0, b->work.size };
    for (uint32_t r = 0; r < reps; r++) {
        barrier(b->cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdCopyBuffer(b->cb, b->pristine.buffer, b->work.buffer, 1, &all);
        barrier(b->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
        vkCmdWriteTimestamp(b->cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, b->queries, stamps * r);
        if (!per_pass) {
            tb_passes_record(b->cb, b->pipelines.layout, list->passes, list->count,
                             VK_NULL_HANDLE /* no per-body passes */);
            vkCmdWriteTimestamp(b->cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, b->queries, stamps * r + 1);
            continue;
        }
        for (uint32_t i = 0; i < list->count; i++) {
            if (i)
                barrier(b->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                            VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
            tb_passes_record(b->cb, b->pipelines.layout, &list->passes[i], 1,
                             VK_NULL_HANDLE /* no per-body passes */);
            vkCmdWriteTimestamp(b->cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, b->queries,
                                stamps * r + i + 1);
        }
    }
    submit(b);
    uint64_t* ticks = malloc(sizeof *ticks * stamps * reps);
    if (!ticks) die("memory", b);
    vkGetQueryPoolResults(b->gpu.device, b->queries, 0, stamps * reps,
                          sizeof *ticks * stamps * reps, ticks, sizeof ticks[0],
                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    double us[MAX_REPS];
    for (uint32_t i = 0; per_pass && i < list->count; i++) {
        for (uint32_t r = 0; r < reps; r++)
            us[r] = (double)(ticks[stamps * r + i + 1] - ticks[stamps * r + i]) * b->ns_per_tick * 1e-3;
        per_pass[i] = median(us, reps);
    }
    for (uint32_t r = 0; r < reps; r++)
        us[r] = (double)(ticks[stamps * r + stamps - 1] - ticks[stamps * r]) * b->ns_per_tick * 1e-3;
    free(ticks);
    return median(us, reps);
}

static void print_passes(const char* what, const tb_pass_list* list, const double* us)
{
    printf("    %s passes (us):", what);
    for (uint32_t i = 0; i < list->count; i++) printf(" %.1f", us[i]);
    printf("\n");
}

/* The sorted keys must be in order and every value must still belong to its key. */
static int check_sorted(bench* b, uint32_t n, uint32_t key_bits)
{
    begin(b);
    barrier(b->cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy all = { 0, 0, b->work.size };
    vkCmdCopyBuffer(b->cb, b->work.buffer, b->host.buffer, 1, &all);
    barrier(b->cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    submit(b);
    const uint32_t* keys = (const uint32_t*)((char*)b->host.mapped + keys_offset());
    const uint32_t* values = (const uint32_t*)((char*)b->host.mapped + values_offset(b));
    uint32_t mask = key_bits == 32 ? ~0u : (1u << key_bits) - 1;
    for (uint32_t i = 1; i < n; i++) {
        uint32_t a = keys[i - 1] & mask, c = keys[i] & mask;
        if (a > c || (a == c && values[i - 1] >= values[i])) return 0;
    }
    return 1;
}

static uint32_t parse_sizes(const char* s, uint32_t* out)
{
    uint32_t n = 0;
    while (*s && n < MAX_SIZES) {
        char* end;
        out[n++] = (uint32_t)strtoul(s, &end, 10);
        s = *end == ',' ? end + 1 : end;
        if (end == s && *s) break;
    }
    return n;
}

int main(int argc, char** argv)
{
    uint32_t sizes[MAX_SIZES] = { 1000, 65536, 1u << 20, 4u << 20, 16u << 20 };
    uint32_t size_count = 5, reps = 9, key_bits = 32;
    int per_pass = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--sizes")) size_count = parse_sizes(argv[i + 1], sizes);
        else if (!strcmp(argv[i], "--passes")) per_pass = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--reps")) reps = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--key-bits")) key_bits = (uint32_t)atoi(argv[i + 1]);
        else { fprintf(stderr, "usage: bench-prims [--sizes N,...] [--reps R] [--key-bits B] [--passes 1]\n"); return 2; }
    }
    if (reps < 1) reps = 1;
    if (reps > MAX_REPS) reps = MAX_REPS;
    uint32_t capacity = 1;
    for (uint32_t i = 0; i < size_count; i++) if (sizes[i] > capacity) capacity = sizes[i];
    bench b;
    setup(&b, capacity, reps);
    printf("device: %s, subgroup %u, group sizes %u (sort %u)\n", b.gpu.props.deviceName,
           b.prims.subgroup_size, b.prims.group_size, b.prims.sort_group_size);
    tb_gpu_ptr count = tb_gpu_ptr_of(&b.work, 0), total = tb_gpu_ptr_of(&b.work, 4);
    tb_gpu_ptr keys = tb_gpu_ptr_of(&b.work, keys_offset());
    tb_gpu_ptr values = tb_gpu_ptr_of(&b.work, values_offset(&b));
    tb_gpu_ptr scratch = tb_gpu_ptr_of(&b.scratch, 0);
    for (uint32_t i = 0; i < size_count; i++) {
        uint32_t n = sizes[i];
        tb_pass_list sort = { 0 }, scan = { 0 }, compact = { 0 };
        if (tb_prims_sort(&b.prims, &sort, keys, values, count, n, key_bits, scratch) ||
            tb_prims_scan(&b.prims, &scan, keys, keys, count, n, total, scratch) ||
            tb_prims_compact(&b.prims, &compact, values, keys, count, n, total, scratch))
            die("record", &b);
        upload(&b, n, 0);
        double sort_us = time_list(&b, &sort, reps, NULL);
        int ok = check_sorted(&b, n, key_bits);
        upload(&b, n, 1);
        double scan_us = time_list(&b, &scan, reps, NULL);
        double compact_us = time_list(&b, &compact, reps, NULL);
        printf("n %9u  sort(%u bits, %u dispatches) %9.1f us %7.0f Mkeys/s %s | scan %8.1f us %7.0f Mel/s"
               " | compact %8.1f us %7.0f Mel/s\n",
               n, key_bits, sort.count, sort_us, n / sort_us, ok ? "ok" : "WRONG", scan_us,
               n / scan_us, compact_us, n / compact_us);
        if (per_pass) {
            double us[64];
            upload(&b, n, 0);
            time_list(&b, &sort, reps, us);
            print_passes("sort", &sort, us);
            upload(&b, n, 1);
            time_list(&b, &scan, reps, us);
            print_passes("scan", &scan, us);
        }
        tb_pass_list_free(&sort);
        tb_pass_list_free(&scan);
        tb_pass_list_free(&compact);
    }
    teardown(&b);
    return 0;
}
