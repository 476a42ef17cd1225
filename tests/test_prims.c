/* The parallel primitives (src/gpu/prims.c, glsl/prims) against plain C references on
 * random inputs of many sizes, none of them special to the kernels.
 *
 * The element count always lives in GPU memory, written there by a copy, and every pass
 * list is recorded once and submitted twice with two different counts: what the primitives
 * do is decided by the count the GPU reads, never by one the host baked in. Elements at and
 * beyond the count must come back untouched.
 */
#include "harness.h"

#include <stdlib.h>
#include <string.h>

#include "world/world.h"
#include "gpu/prims.h"

/* ---- a rig: a world's device, the primitives, and mirrored buffers --------------------- */

/* Device and host buffers share one layout: a header of words (the count, results), then
 * two arrays. Every submission copies the header and the part of the arrays in use host ->
 * device, runs the passes and copies them back. Scratch is device-only. */
#define HEADER_BYTES 256
#define WORD_COUNT 0     /* the element count the passes read */
#define WORD_RESULT 1    /* scan total, compacted count */
#define POISON 0xdeadbeefu

typedef struct rig {
    tb_world* w;
    tb_prims prims;
    tb_buffer dev, host, scratch;
    VkDeviceSize array_bytes;
    uint32_t used;          ///< words of each array copied (and checked) by the recorded runs
    VkCommandBuffer cb;
} rig;

static VkDeviceSize bytes_of_array(uint32_t capacity)
{
    return ((VkDeviceSize)capacity * 4 + 255) / 256 * 256;
}

static void rig_create(rig* r, uint32_t capacity)
{
    memset(r, 0, sizeof *r);
    r->w = th_world_create(NULL);
    th_assert_ok(tb_prims_init(&r->prims, &r->w->pipelines));
    r->array_bytes = bytes_of_array(capacity + 64); /* room for rig_record's margin */
    VkDeviceSize size = HEADER_BYTES + 2 * r->array_bytes;
    VkBufferUsageFlags copy = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    th_assert_ok(tb_buffer_create(&r->w->memory, size,
                                  copy | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 0, &r->dev));
    th_assert_ok(tb_buffer_create(&r->w->memory, size, copy, 1, &r->host));
    th_assert_ok(tb_gpu_command_buffer(&r->w->gpu, &r->cb));
}

/* Scratch is used through its address and as the source of indirect dispatches. */
static void rig_scratch(rig* r, VkDeviceSize bytes)
{
    th_assert_ok(tb_buffer_create(&r->w->memory, bytes,
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                      VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, 0, &r->scratch));
}

static void rig_destroy(rig* r)
{
    vkFreeCommandBuffers(r->w->gpu.device, r->w->gpu.command_pool, 1, &r->cb);
    tb_buffer_destroy(&r->w->memory, &r->scratch);
    tb_buffer_destroy(&r->w->memory, &r->host);
    tb_buffer_destroy(&r->w->memory, &r->dev);
    tb_prims_destroy(&r->prims);
    th_world_destroy(r->w);
}

static uint32_t* host_words(rig* r)
{
    return (uint32_t*)r->host.mapped;
}

static uint32_t* host_array(rig* r, int k)
{
    return (uint32_t*)((char*)r->host.mapped + HEADER_BYTES + k * r->array_bytes);
}

static tb_gpu_ptr dev_word(rig* r, int i)
{
    return tb_gpu_ptr_of(&r->dev, 4 * (VkDeviceSize)i);
}

static tb_gpu_ptr dev_array(rig* r, int k)
{
    return tb_gpu_ptr_of(&r->dev, HEADER_BYTES + k * r->array_bytes);
}

static tb_gpu_ptr scratch_ptr(rig* r)
{
    return tb_gpu_ptr_of(&r->scratch, 0);
}

static void barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkAccessFlags src_access,
                    VkPipelineStageFlags dst, VkAccessFlags dst_access)
{
    VkMemoryBarrier b = { .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                          .srcAccessMask = src_access, .dstAccessMask = dst_access };
    vkCmdPipelineBarrier(cb, src, dst, 0, 1, &b, 0, NULL, 0, NULL);
}

/* Upload, the passes, download: recorded once, submitted as often as the test likes. The
 * first `used` words of each array travel (they must fit the rig's capacity). */
static void rig_record(rig* r, const tb_pass_list* list, uint32_t used)
{
    used += 61; /* a margin past what the case uses, where nothing may be written either */
    assert_true(4 * (VkDeviceSize)used <= r->array_bytes);
    r->used = used;
    VkCommandBuffer cb = r->cb;
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO };
    assert_int_equal(vkBeginCommandBuffer(cb, &begin), VK_SUCCESS);
    /* Whatever an earlier submission did to these buffers is over. */
    barrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
            VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferCopy parts[3] = {
        { 0, 0, HEADER_BYTES },
        { HEADER_BYTES, HEADER_BYTES, 4 * (VkDeviceSize)used },
        { HEADER_BYTES + r->array_bytes, HEADER_BYTES + r->array_bytes, 4 * (VkDeviceSize)used },
    };
    vkCmdCopyBuffer(cb, r->host.buffer, r->dev.buffer, 3, parts);
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    tb_passes_record(cb, r->w->pipelines.layout, list->passes, list->count,
                     r->w->params_buffer.buffer);
    barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    vkCmdCopyBuffer(cb, r->dev.buffer, r->host.buffer, 3, parts);
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    assert_int_equal(vkEndCommandBuffer(cb), VK_SUCCESS);
}

/* Put the inputs (NULL: poison) and the count in the host buffer, run, results there. */
static void rig_run(rig* r, uint32_t count, const uint32_t* a, const uint32_t* b, uint32_t n)
{
    uint32_t* words = host_words(r);
    for (uint32_t i = 0; i < HEADER_BYTES / 4; i++) words[i] = POISON;
    words[WORD_COUNT] = count;
    const uint32_t* in[2] = { a, b };
    for (int k = 0; k < 2; k++) {
        uint32_t* dst = host_array(r, k);
        for (uint32_t i = 0; i < r->used; i++)
            dst[i] = in[k] && i < n ? in[k][i] : POISON ^ i;
    }
    th_assert_ok(tb_gpu_submit_wait(&r->w->gpu, &r->cb, 1));
}

/* Elements [from, to) of array k in the host buffer equal want[from, to) (NULL: the
 * poison rig_run wrote there). */
static void expect_array(rig* r, int k, uint32_t from, uint32_t to, const uint32_t* want,
                         const char* what, uint32_t size, uint32_t count)
{
    const uint32_t* got = host_array(r, k);
    for (uint32_t i = from; i < to; i++) {
        uint32_t w = want ? want[i] : POISON ^ i;
        if (got[i] != w)
            fail_msg("%s (size %u, count %u): element %u is %u (0x%08x), want %u (0x%08x)", what,
                     size, count, i, got[i], got[i], w, w);
    }
}

static th_rng rng_for(uint32_t n, uint32_t salt)
{
    return th_rng_seed(0x9e3779b97f4a7c15ull ^ ((uint64_t)n << 16) ^ salt);
}

/* The sizes every primitive is tried at: around subgroup, workgroup and tile multiples. */
static const uint32_t SIZES[] = { 0, 1, 2, 3, 7, 8, 9, 31, 32, 33, 63, 64, 65, 255, 256, 257,
                                  1000, 2047, 2048, 2049, 4095, 4096, 4097, 65537, 100003 };
#define SIZE_COUNT (sizeof SIZES / sizeof SIZES[0])
/* Multi-million: blocks of several tiles in the sort, many tiles in the scan's spine; a few
 * seconds on lavapipe. */
#define LARGE 3000017u

/* The second count a recorded list is run with: different, and within max_count = n + 3. */
static uint32_t second_count(uint32_t n)
{
    return n >= 6 ? n / 2 + 1 : n + 3;
}

/* ---- sort --------------------------------------------------------------------------------- */

typedef enum key_kind { KEYS_RANDOM, KEYS_FEW, KEYS_SORTED, KEYS_REVERSED } key_kind;

static void make_keys(uint32_t* keys, uint32_t n, key_kind kind, th_rng* rng)
{
    for (uint32_t i = 0; i < n; i++) {
        switch (kind) {
        case KEYS_RANDOM: keys[i] = th_rng_u32(rng); break;
        /* Few distinct keys that differ in high and low digits: long runs of equal keys. */
        case KEYS_FEW: keys[i] = (th_rng_u32(rng) % 5) * 0x01010101u; break;
        case KEYS_SORTED: keys[i] = i * 7u + (th_rng_u32(rng) & 3u) * (i & 1u); break;
        case KEYS_REVERSED: keys[i] = (n - i) * 5u; break;
        }
    }
    if (kind == KEYS_SORTED)
        for (uint32_t i = 1; i < n; i++)
            if (keys[i] < keys[i - 1]) keys[i] = keys[i - 1];
}

typedef struct sort_ref { uint32_t key, index; } sort_ref;

static uint32_t sort_mask;

static int compare_sort_ref(const void* a, const void* b)
{
    const sort_ref* x = a;
    const sort_ref* y = b;
    uint32_t kx = x->key & sort_mask, ky = y->key & sort_mask;
    if (kx != ky) return kx < ky ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index; /* stable: index breaks ties */
}

/* The stable sort of the first `count` pairs by the low key_bits; the rest unchanged. */
static void reference_sort(const uint32_t* keys, const uint32_t* values, uint32_t count,
                           uint32_t n, uint32_t key_bits, uint32_t* out_keys, uint32_t* out_values)
{
    sort_ref* ref = malloc(((size_t)count + 1) * sizeof *ref);
    assert_non_null(ref);
    for (uint32_t i = 0; i < count; i++) ref[i] = (sort_ref){ keys[i], i };
    sort_mask = key_bits == 32 ? 0xffffffffu : (1u << key_bits) - 1u;
    qsort(ref, count, sizeof *ref, compare_sort_ref);
    for (uint32_t i = 0; i < count; i++) {
        out_keys[i] = ref[i].key;
        out_values[i] = values[ref[i].index];
    }
    for (uint32_t i = count; i < n; i++) {
        out_keys[i] = keys[i];
        out_values[i] = values[i];
    }
    free(ref);
}

/* Sort n pairs with one recorded list (max_count n + 3), at count n and at another count. */
static void check_sort(rig* r, uint32_t n, uint32_t key_bits, key_kind kind)
{
    uint32_t max_count = n + 3, cap = max_count;
    uint32_t* keys = malloc(4 * (size_t)cap + 4);
    uint32_t* values = malloc(4 * (size_t)cap + 4);
    uint32_t* want_keys = malloc(4 * (size_t)cap + 4);
    uint32_t* want_values = malloc(4 * (size_t)cap + 4);
    assert_true(keys && values && want_keys && want_values);
    th_rng rng = rng_for(n, key_bits * 16 + kind);
    make_keys(keys, cap, kind, &rng);
    for (uint32_t i = 0; i < cap; i++) values[i] = i; /* the original index: shows stability */

    tb_pass_list list = { 0 };
    th_assert_ok(tb_prims_sort(&r->prims, &list, dev_array(r, 0), dev_array(r, 1),
                               dev_word(r, WORD_COUNT), max_count, key_bits, scratch_ptr(r)));
    rig_record(r, &list, cap);
    const uint32_t counts[2] = { n, second_count(n) };
    for (int run = 0; run < 2; run++) {
        uint32_t count = counts[run];
        rig_run(r, count, keys, values, cap);
        reference_sort(keys, values, count, cap, key_bits, want_keys, want_values);
        expect_array(r, 0, 0, cap, want_keys, "sorted keys", n, count);
        expect_array(r, 1, 0, cap, want_values, "sorted values", n, count);
        expect_array(r, 0, cap, r->used, NULL, "keys beyond max_count", n, count);
        expect_array(r, 1, cap, r->used, NULL, "values beyond max_count", n, count);
    }
    tb_pass_list_free(&list);
    free(keys);
    free(values);
    free(want_keys);
    free(want_values);
}

static void sort_sizes(uint32_t key_bits, key_kind kind, int with_large)
{
    uint32_t largest = with_large ? LARGE : SIZES[SIZE_COUNT - 1];
    rig r;
    rig_create(&r, largest + 3);
    rig_scratch(&r, tb_prims_sort_scratch(&r.prims, largest + 3));
    for (size_t i = 0; i < SIZE_COUNT; i++) check_sort(&r, SIZES[i], key_bits, kind);
    if (with_large) check_sort(&r, LARGE, key_bits, kind);
    rig_destroy(&r);
}

static void test_sort_random_keys(void** state)
{
    (void)state;
    sort_sizes(32, KEYS_RANDOM, 1);
}

/* Long runs of equal keys must keep their input order (values are the input index). */
static void test_sort_few_distinct_keys_is_stable(void** state)
{
    (void)state;
    sort_sizes(32, KEYS_FEW, 0);
}

/* Only the low key_bits decide; odd pass counts (1, 3) end with the copy back. */
static void test_sort_low_key_bits(void** state)
{
    (void)state;
    static const uint32_t bits[] = { 1, 5, 8, 13, 20, 24, 31 };
    rig r;
    uint32_t largest = SIZES[SIZE_COUNT - 1] + 3;
    rig_create(&r, largest);
    rig_scratch(&r, tb_prims_sort_scratch(&r.prims, largest));
    for (size_t b = 0; b < sizeof bits / sizeof bits[0]; b++)
        for (size_t i = 0; i < SIZE_COUNT; i += 2) check_sort(&r, SIZES[i], bits[b], KEYS_RANDOM);
    rig_destroy(&r);
}

static void test_sort_sorted_and_reversed(void** state)
{
    (void)state;
    sort_sizes(32, KEYS_SORTED, 0);
    sort_sizes(32, KEYS_REVERSED, 0);
}

/* ---- scan ----------------------------------------------------------------------------------- */

static void check_scan(rig* r, uint32_t n, int in_place, int with_total)
{
    uint32_t max_count = n + 3, cap = max_count;
    uint32_t* in = malloc(4 * (size_t)cap + 4);
    uint32_t* want = malloc(4 * (size_t)cap + 4);
    assert_true(in && want);
    th_rng rng = rng_for(n, 100 + in_place * 2 + with_total);
    /* Mostly small values, some huge: the sums wrap modulo 2^32 on both sides. */
    for (uint32_t i = 0; i < cap; i++)
        in[i] = (i % 97 == 5) ? th_rng_u32(&rng) : th_rng_u32(&rng) % 1000;
    tb_gpu_ptr total = with_total ? dev_word(r, WORD_RESULT) : (tb_gpu_ptr){ 0 };
    tb_pass_list list = { 0 };
    th_assert_ok(tb_prims_scan(&r->prims, &list, dev_array(r, 0), dev_array(r, in_place ? 0 : 1),
                               dev_word(r, WORD_COUNT), max_count, total, scratch_ptr(r)));
    rig_record(r, &list, cap);
    const uint32_t counts[2] = { n, second_count(n) };
    for (int run = 0; run < 2; run++) {
        uint32_t count = counts[run];
        rig_run(r, count, in, NULL, cap);
        uint32_t sum = 0;
        for (uint32_t i = 0; i < count; i++) {
            want[i] = sum;
            sum += in[i];
        }
        if (in_place) {
            for (uint32_t i = count; i < cap; i++) want[i] = in[i];
            expect_array(r, 0, 0, cap, want, "scanned in place", n, count);
        } else {
            expect_array(r, 0, 0, cap, in, "scan input", n, count);
            expect_array(r, 1, 0, count, want, "scanned", n, count);
            expect_array(r, 1, count, cap, NULL, "beyond the count", n, count);
        }
        if (with_total && host_words(r)[WORD_RESULT] != sum)
            fail_msg("scan total (size %u, count %u) %u, want %u", n, count,
                     host_words(r)[WORD_RESULT], sum);
        if (!with_total) assert_int_equal(host_words(r)[WORD_RESULT], POISON);
    }
    tb_pass_list_free(&list);
    free(in);
    free(want);
}

static void test_scan(void** state)
{
    (void)state;
    rig r;
    rig_create(&r, LARGE + 3);
    rig_scratch(&r, tb_prims_scan_scratch(&r.prims, LARGE + 3));
    for (size_t i = 0; i < SIZE_COUNT; i++) {
        check_scan(&r, SIZES[i], 0, 1);
        check_scan(&r, SIZES[i], 1, (int)(i & 1));
    }
    check_scan(&r, LARGE, 1, 1);
    check_scan(&r, LARGE, 0, 0);
    rig_destroy(&r);
}

/* A count above max_count is clamped to it: nothing beyond the scratch's reach is touched. */
static void test_scan_count_clamped(void** state)
{
    (void)state;
    const uint32_t n = 5000, max_count = 4200;
    rig r;
    rig_create(&r, n);
    rig_scratch(&r, tb_prims_scan_scratch(&r.prims, max_count));
    uint32_t* in = malloc(4 * n);
    assert_non_null(in);
    for (uint32_t i = 0; i < n; i++) in[i] = i % 3;
    tb_pass_list list = { 0 };
    th_assert_ok(tb_prims_scan(&r.prims, &list, dev_array(&r, 0), dev_array(&r, 1),
                               dev_word(&r, WORD_COUNT), max_count, dev_word(&r, WORD_RESULT),
                               scratch_ptr(&r)));
    rig_record(&r, &list, n);
    rig_run(&r, n, in, NULL, n);
    uint32_t sum = 0;
    for (uint32_t i = 0; i < max_count; i++) {
        if (host_array(&r, 1)[i] != sum) fail_msg("element %u", i);
        sum += in[i];
    }
    assert_int_equal(host_words(&r)[WORD_RESULT], sum);
    expect_array(&r, 1, max_count, n, NULL, "beyond max_count", n, n);
    tb_pass_list_free(&list);
    free(in);
    rig_destroy(&r);
}

/* ---- compaction ------------------------------------------------------------------------------ */

typedef enum flag_kind { FLAGS_NONE, FLAGS_ALL, FLAGS_RANDOM } flag_kind;

static void check_compact(rig* r, uint32_t n, flag_kind kind)
{
    uint32_t max_count = n + 3, cap = max_count;
    uint32_t* flags = malloc(4 * (size_t)cap + 4);
    uint32_t* want = malloc(4 * (size_t)cap + 4);
    assert_true(flags && want);
    th_rng rng = rng_for(n, 200 + kind);
    for (uint32_t i = 0; i < cap; i++) {
        uint32_t x = th_rng_u32(&rng);
        /* Any nonzero word is a set flag, the high bit alone included. */
        flags[i] = kind == FLAGS_NONE ? 0 : kind == FLAGS_ALL ? (x | 0x80000000u)
                                                              : (x % 3 == 0 ? x >> (x % 32) : 0);
    }
    tb_pass_list list = { 0 };
    th_assert_ok(tb_prims_compact(&r->prims, &list, dev_array(r, 0), dev_array(r, 1),
                                  dev_word(r, WORD_COUNT), max_count, dev_word(r, WORD_RESULT),
                                  scratch_ptr(r)));
    rig_record(r, &list, cap);
    const uint32_t counts[2] = { n, second_count(n) };
    for (int run = 0; run < 2; run++) {
        uint32_t count = counts[run], k = 0;
        rig_run(r, count, flags, NULL, cap);
        for (uint32_t i = 0; i < count; i++)
            if (flags[i]) want[k++] = i;
        if (host_words(r)[WORD_RESULT] != k)
            fail_msg("compacted count (size %u, count %u) %u, want %u", n, count,
                     host_words(r)[WORD_RESULT], k);
        expect_array(r, 1, 0, k, want, "compacted indices", n, count);
        expect_array(r, 1, k, cap, NULL, "beyond the compacted", n, count);
        expect_array(r, 0, 0, cap, flags, "flags", n, count);
    }
    tb_pass_list_free(&list);
    free(flags);
    free(want);
}

static void test_compact(void** state)
{
    (void)state;
    rig r;
    rig_create(&r, LARGE + 3);
    rig_scratch(&r, tb_prims_compact_scratch(&r.prims, LARGE + 3));
    for (size_t i = 0; i < SIZE_COUNT; i++)
        for (int kind = FLAGS_NONE; kind <= FLAGS_RANDOM; kind++)
            check_compact(&r, SIZES[i], (flag_kind)kind);
    check_compact(&r, LARGE, FLAGS_RANDOM);
    rig_destroy(&r);
}

/* ---- small limits ----------------------------------------------------------------------------- */

/* With a device limit of 3 workgroups in x, dispatches go in rows (and groups past the last
 * tile must do nothing); with at most 3 sort blocks, a block holds many tiles, so digit
 * starts must carry from one tile of a block to the next. */
static void test_rows_and_blocks_of_tiles(void** state)
{
    (void)state;
    rig r;
    uint32_t largest = SIZES[SIZE_COUNT - 1] + 3;
    rig_create(&r, largest);
    VkDeviceSize sort = tb_prims_sort_scratch(&r.prims, largest);
    VkDeviceSize scan = tb_prims_scan_scratch(&r.prims, largest);
    rig_scratch(&r, sort > scan ? sort : scan);
    r.prims.max_groups_x = 3;
    r.prims.sort_max_blocks = 3;
    for (size_t i = 0; i < SIZE_COUNT; i += 3) {
        check_sort(&r, SIZES[i], 32, KEYS_FEW);
        check_sort(&r, SIZES[i], 20, KEYS_RANDOM);
        check_scan(&r, SIZES[i], 1, 1);
        check_compact(&r, SIZES[i], FLAGS_RANDOM);
    }
    rig_destroy(&r);
}

/* ---- fill ------------------------------------------------------------------------------------ */

/* With the count on the GPU (and a bound or none) or fixed on the host. */
static void check_fill(rig* r, uint32_t n, int gpu_count, uint32_t bound)
{
    uint32_t cap = n + 3, value = 0x5a5a0000u + n;
    tb_gpu_ptr count = gpu_count ? dev_word(r, WORD_COUNT) : (tb_gpu_ptr){ 0 };
    tb_pass_list list = { 0 };
    th_assert_ok(tb_prims_fill(&r->prims, &list, dev_array(r, 1), count,
                               gpu_count ? bound : n, value));
    rig_record(r, &list, cap);
    uint32_t counts[2] = { n, gpu_count ? second_count(n) : n };
    for (int run = 0; run < 2; run++) {
        uint32_t filled = counts[run];
        if (gpu_count && bound && filled > bound) filled = bound;
        rig_run(r, counts[run], NULL, NULL, 0);
        const uint32_t* got = host_array(r, 1);
        for (uint32_t i = 0; i < filled; i++)
            if (got[i] != value) fail_msg("fill (size %u): element %u is %u", n, i, got[i]);
        expect_array(r, 1, filled, cap, NULL, "beyond the fill", n, counts[run]);
    }
    tb_pass_list_free(&list);
}

static void test_fill(void** state)
{
    (void)state;
    rig r;
    rig_create(&r, 300000);
    for (size_t i = 0; i < SIZE_COUNT; i++) {
        check_fill(&r, SIZES[i], 0, 0);
        check_fill(&r, SIZES[i], 1, 0);
        check_fill(&r, SIZES[i], 1, SIZES[i] + 1);
    }
    /* More elements than the fill's workgroups have invocations: the grid-stride loop. */
    check_fill(&r, 299999, 0, 0);
    check_fill(&r, 299999, 1, 0);
    check_fill(&r, 299999, 1, 250000); /* the bound clamps a larger count */
    rig_destroy(&r);
}

/* ---- indirect arguments ----------------------------------------------------------------------- */

static void test_indirect_args(void** state)
{
    (void)state;
    rig r;
    rig_create(&r, 16);
    const uint32_t limit = r.w->gpu.props.limits.maxComputeWorkGroupCount[0];
    const uint32_t group_sizes[] = { 1, 64, 256, 2048 };
    const uint32_t counts[] = { 0, 1, 63, 64, 65, 100003, 65535u * 256u, 65535u * 256u + 1,
                                16777216, 200000000, 0x80000000u };
    for (size_t g = 0; g < sizeof group_sizes / sizeof group_sizes[0]; g++) {
        uint32_t gs = group_sizes[g];
        tb_pass_list list = { 0 };
        th_assert_ok(tb_prims_indirect_args(&r.prims, &list, dev_word(&r, WORD_COUNT), gs,
                                            dev_word(&r, 4)));
        rig_record(&r, &list, 4);
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
            uint32_t n = counts[c];
            rig_run(&r, n, NULL, NULL, 0);
            const uint32_t* cmd = &host_words(&r)[4];
            uint64_t groups = ((uint64_t)n + gs - 1) / gs;
            uint64_t covered = (uint64_t)cmd[0] * cmd[1] * cmd[2];
            if (cmd[2] != 1 || cmd[0] > limit || cmd[1] > limit || covered < groups ||
                (groups > 0 && cmd[1] > 1 && covered >= groups + cmd[1]) ||
                (groups == 0 && covered != 0))
                fail_msg("count %u, group size %u: dispatch %u x %u x %u (limit %u)", n, gs,
                         cmd[0], cmd[1], cmd[2], limit);
            if (groups <= limit && (cmd[0] != groups || cmd[1] != 1))
                fail_msg("count %u, group size %u: %u x %u, want one row", n, gs, cmd[0], cmd[1]);
        }
        tb_pass_list_free(&list);
    }
    rig_destroy(&r);
}

/* ---- arguments ---------------------------------------------------------------------------------- */

static void test_bad_arguments(void** state)
{
    (void)state;
    rig r;
    memset(&r, 0, sizeof r);
    r.w = th_world_create_ex(NULL, 1);
    th_assert_ok(tb_prims_init(&r.prims, &r.w->pipelines));
    th_assert_ok(tb_buffer_create(&r.w->memory, 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                  VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, 0, &r.dev));
    tb_gpu_ptr p = tb_gpu_ptr_of(&r.dev, 0), none = { 0 };
    tb_pass_list list = { 0 };
    th_assert_result(tb_prims_sort(&r.prims, &list, p, p, p, 10, 0, p), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_prims_sort(&r.prims, &list, p, p, p, 10, 33, p), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_prims_scan(&r.prims, &list, p, p, p, 10, none, none),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_prims_compact(&r.prims, &list, p, p, p, 10, none, p),
                     TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_prims_indirect_args(&r.prims, &list, p, 0, p), TB_ERROR_INVALID_ARGUMENT);
    th_assert_result(tb_prims_scan(&r.prims, &list, p, p, p, 0x80000001u, none, p),
                     TB_ERROR_INVALID_ARGUMENT);
    assert_int_equal(list.count, 0); /* a refused primitive appends nothing */
    tb_buffer_destroy(&r.w->memory, &r.dev);
    tb_prims_destroy(&r.prims);
    th_world_destroy(r.w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sort_random_keys),
        cmocka_unit_test(test_sort_few_distinct_keys_is_stable),
        cmocka_unit_test(test_sort_low_key_bits),
        cmocka_unit_test(test_sort_sorted_and_reversed),
        cmocka_unit_test(test_scan),
        cmocka_unit_test(test_scan_count_clamped),
        cmocka_unit_test(test_compact),
        cmocka_unit_test(test_rows_and_blocks_of_tiles),
        cmocka_unit_test(test_fill),
        cmocka_unit_test(test_indirect_args),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
