/* Parallel primitives: pipelines, scratch layouts and the passes each primitive appends.
 *
 * Every primitive that depends on a GPU count starts with a one-workgroup pass that turns
 * the count into the dispatch of its tile passes, stored at the start of its scratch
 * (indirect_args; sort_args for the sort, which also plans blocks of tiles and its spine);
 * the passes after it are dispatched from there. The scan's spine, one workgroup whatever
 * the count, has a fixed dispatch. Every kernel reads the count itself.
 *
 * Measured on an H200 (tools/bench/prims.c): 32-bit keys with values sort at about 11.6
 * G pairs/s at 16M, 158 us at 1M, 90 us at 64K (13 dependent dispatches are the floor);
 * scans of 16M uints take 97 us.
 */
#include "gpu/prims.h"

#include <stddef.h>
#include <string.h>

#include "layout.h"

/* Scratch starts with the dispatch command of the tile passes; areas after it are aligned
 * so that any of them could also serve as an indirect or copy offset. */
#define ARGS_BYTES 256u
#define AREA_ALIGN 256u

/* Fill: enough workgroups to keep a large GPU busy, a grid-stride loop for the rest. */
#define FILL_MAX_GROUPS 1024u

/* Counts above this would need more than 32 bits for some element indices. */
#define MAX_COUNT 0x80000000u

tb_gpu_ptr tb_gpu_ptr_of(const tb_buffer* buffer, VkDeviceSize offset)
{
    tb_gpu_ptr p = { buffer->buffer, offset, buffer->address ? buffer->address + offset : 0 };
    return p;
}

tb_gpu_ptr tb_gpu_ptr_add(tb_gpu_ptr p, VkDeviceSize bytes)
{
    p.offset += bytes;
    p.address += bytes;
    return p;
}

static VkDeviceSize align_up(VkDeviceSize x, VkDeviceSize a)
{
    return (x + a - 1) / a * a;
}

static uint32_t tiles_of(uint32_t count, uint32_t tile)
{
    return (uint32_t)(((uint64_t)count + tile - 1) / tile);
}

tb_gpu_uvec4 tb_gpu_addresses(VkDeviceAddress a, VkDeviceAddress b)
{
    tb_gpu_uvec4 v = { (uint32_t)a, (uint32_t)(a >> 32), (uint32_t)b, (uint32_t)(b >> 32) };
    return v;
}

/* ---- pipelines ------------------------------------------------------------------------- */

typedef struct pipeline_spec {
    const char* shader;
    size_t field;       /* offset of the VkPipeline in tb_prims */
    int sort_sized;     /* built with sort_group_size instead of group_size */
} pipeline_spec;

#define SPEC(name, field, sort) { "prims/" name, offsetof(tb_prims, field), sort }
static const pipeline_spec PIPELINES[] = {
    SPEC("fill", fill, 0),
    SPEC("indirect_args", indirect_args, 0),
    SPEC("scan_reduce", scan_reduce, 0),
    SPEC("scan_spine", scan_spine, 0),
    SPEC("scan_down", scan_down, 0),
    SPEC("compact_scatter", compact_scatter, 0),
    SPEC("sort_args", sort_args, 0),
    SPEC("sort_histogram", sort_histogram, 1),
    SPEC("sort_spine", sort_spine, 0),
    SPEC("sort_scatter", sort_scatter, 1),
    SPEC("copy", copy, 1),
};
#define PIPELINE_COUNT (sizeof PIPELINES / sizeof PIPELINES[0])

static VkPipeline* pipeline_slot(tb_prims* prims, const pipeline_spec* spec)
{
    return (VkPipeline*)((char*)prims + spec->field);
}

/* Shared memory of sort_scatter, the largest user: per-subgroup digit counters, the digit
 * starts and destinations, the staged tile and the subgroup totals. */
static uint32_t scatter_shared_bytes(uint32_t group_size, uint32_t subgroup_size)
{
    uint32_t subgroups = group_size / subgroup_size;
    return 4u * (subgroups * TB_PRIMS_RADIX + 2u * TB_PRIMS_RADIX + TB_PRIMS_SORT_TILE +
                 subgroups);
}

/* Workgroup sizes: 256 (or the device's most, if smaller) for everything but the sort,
 * whose per-subgroup counters take 1 KiB per subgroup: it keeps at most 16 subgroups. */
static tb_result choose_group_sizes(tb_prims* prims, const VkPhysicalDeviceLimits* limits)
{
    uint32_t s = prims->subgroup_size;
    uint32_t g = 256;
    while (g > limits->maxComputeWorkGroupInvocations) g /= 2;
    if (s == 0 || (s & (s - 1)) != 0 || s > g || s > 128)
        return tb_fail(prims->diag, TB_ERROR_DEVICE,
                       "subgroup size %u unsupported by the parallel primitives", s);
    prims->group_size = g;
    prims->sort_group_size = 16 * s < g ? 16 * s : g;
    prims->max_groups_x = limits->maxComputeWorkGroupCount[0];
    prims->sort_max_blocks = TB_PRIMS_SORT_MAX_BLOCKS;
    if (prims->sort_max_blocks > prims->max_groups_x) prims->sort_max_blocks = prims->max_groups_x;
    uint32_t shared = scatter_shared_bytes(prims->sort_group_size, s);
    if (shared > limits->maxComputeSharedMemorySize)
        return tb_fail(prims->diag, TB_ERROR_DEVICE,
                       "the radix sort needs %u bytes of shared memory, the device has %u",
                       shared, limits->maxComputeSharedMemorySize);
    return TB_OK;
}

tb_result tb_prims_init(tb_prims* prims, tb_pipelines* pipelines)
{
    memset(prims, 0, sizeof *prims);
    prims->pipelines = pipelines;
    prims->diag = pipelines->gpu->diag;
    prims->subgroup_size = pipelines->gpu->subgroup_size;
    tb_result r = choose_group_sizes(prims, &pipelines->gpu->props.limits);
    for (size_t i = 0; !r && i < PIPELINE_COUNT; i++) {
        const pipeline_spec* spec = &PIPELINES[i];
        uint32_t size = spec->sort_sized ? prims->sort_group_size : prims->group_size;
        r = tb_pipeline_create(pipelines, spec->shader, size, pipeline_slot(prims, spec));
    }
    if (r) tb_prims_destroy(prims);
    return r;
}

void tb_prims_destroy(tb_prims* prims)
{
    if (!prims->pipelines) return;
    for (size_t i = 0; i < PIPELINE_COUNT; i++) {
        VkPipeline* p = pipeline_slot(prims, &PIPELINES[i]);
        tb_pipeline_destroy(prims->pipelines, *p);
        *p = VK_NULL_HANDLE;
    }
    prims->pipelines = NULL;
}

/* ---- passes ---------------------------------------------------------------------------- */

/* Passes that write no dispatch arguments: all but the argument kernels, and fill and copy,
 * whose callers may point them at arguments. */
static int writes_no_arguments(const tb_prims* prims, VkPipeline pipeline)
{
    return pipeline != prims->indirect_args && pipeline != prims->sort_args &&
           pipeline != prims->fill && pipeline != prims->copy;
}

static tb_result add_fixed(tb_prims* prims, tb_pass_list* list, VkPipeline pipeline,
                           const void* push, uint32_t push_size, uint32_t groups)
{
    tb_pass pass = { .pipeline = pipeline, .rule = TB_DISPATCH_FIXED, .groups = { groups, 1, 1 },
                     .push_size = push_size,
                     .writes_no_arguments = writes_no_arguments(prims, pipeline) };
    memcpy(pass.push, push, push_size);
    return tb_pass_list_add(list, prims->diag, &pass);
}

static tb_result add_indirect(tb_prims* prims, tb_pass_list* list, VkPipeline pipeline,
                              const void* push, uint32_t push_size, tb_gpu_ptr args)
{
    tb_pass pass = { .pipeline = pipeline, .rule = TB_DISPATCH_INDIRECT, .indirect = args.buffer,
                     .indirect_offset = args.offset, .push_size = push_size,
                     .writes_no_arguments = writes_no_arguments(prims, pipeline) };
    memcpy(pass.push, push, push_size);
    return tb_pass_list_add(list, prims->diag, &pass);
}

static tb_result add_args_pass(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr count,
                               uint32_t largest, uint32_t per_group, tb_gpu_ptr args)
{
    tb_gpu_indirect_push push = {
        .ptrs = tb_gpu_addresses(count.address, args.address),
        .args = { per_group, prims->max_groups_x, largest, 0 },
    };
    return add_fixed(prims, list, prims->indirect_args, &push, sizeof push, 1);
}

static tb_result check_ptr(tb_prims* prims, tb_gpu_ptr p, const char* what)
{
    if (p.address == 0 || p.address % 4 != 0)
        return tb_fail(prims->diag, TB_ERROR_INVALID_ARGUMENT,
                       "%s must be a 4-byte aligned device address", what);
    return TB_OK;
}

static tb_result check_scratch(tb_prims* prims, tb_gpu_ptr scratch, uint32_t max_count)
{
    if (max_count > MAX_COUNT)
        return tb_fail(prims->diag, TB_ERROR_INVALID_ARGUMENT,
                       "the parallel primitives take at most %u elements", MAX_COUNT);
    if (!scratch.buffer) return tb_fail(prims->diag, TB_ERROR_INVALID_ARGUMENT, "no scratch buffer");
    return check_ptr(prims, scratch, "scratch");
}

tb_result tb_prims_fill(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr dst, tb_gpu_ptr count,
                        uint32_t fixed_count, uint32_t value)
{
    tb_result r = check_ptr(prims, dst, "fill destination");
    if (r) return r;
    uint32_t groups = FILL_MAX_GROUPS;
    if (fixed_count) {
        uint32_t needed = tiles_of(fixed_count, prims->group_size);
        if (needed < groups) groups = needed;
    } else if (!count.address) {
        return TB_OK; /* nothing to fill */
    }
    tb_gpu_fill_push push = {
        .dst = tb_gpu_addresses(dst.address, count.address),
        .args = { fixed_count, value, 0, 0 },
    };
    return add_fixed(prims, list, prims->fill, &push, sizeof push, groups);
}

tb_result tb_prims_indirect_args(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr count,
                                 uint32_t group_size, tb_gpu_ptr args)
{
    tb_result r = check_ptr(prims, count, "count");
    if (!r) r = check_ptr(prims, args, "indirect arguments");
    if (!r && group_size == 0)
        r = tb_fail(prims->diag, TB_ERROR_INVALID_ARGUMENT, "group size 0");
    return r ? r : add_args_pass(prims, list, count, UINT32_MAX, group_size, args);
}

/* ---- scan and compaction ---------------------------------------------------------------- */

/* Scratch of scan and compaction: the dispatch command, then the sum of each tile. */
VkDeviceSize tb_prims_scan_scratch(const tb_prims* prims, uint32_t max_count)
{
    (void)prims;
    uint32_t tiles = tiles_of(max_count, TB_PRIMS_SCAN_TILE);
    return ARGS_BYTES + align_up(4 * (VkDeviceSize)(tiles ? tiles : 1), AREA_ALIGN);
}

VkDeviceSize tb_prims_compact_scratch(const tb_prims* prims, uint32_t max_count)
{
    return tb_prims_scan_scratch(prims, max_count);
}

/* reduce -> spine -> down (or compact_scatter), after the dispatch command of the tiles. */
static tb_result record_scan(tb_prims* prims, tb_pass_list* list, uint32_t mode, VkPipeline last,
                             tb_gpu_ptr in, tb_gpu_ptr out, tb_gpu_ptr count, uint32_t max_count,
                             tb_gpu_ptr total, tb_gpu_ptr scratch)
{
    tb_result r = check_scratch(prims, scratch, max_count);
    if (!r) r = check_ptr(prims, in, "input");
    if (!r) r = check_ptr(prims, out, "output");
    if (!r) r = check_ptr(prims, count, "count");
    if (r) return r;
    tb_gpu_ptr args = scratch, sums = tb_gpu_ptr_add(scratch, ARGS_BYTES);
    tb_gpu_scan_push push = {
        .data = tb_gpu_addresses(in.address, out.address),
        .aux = tb_gpu_addresses(sums.address, total.address),
        .count = { (uint32_t)count.address, (uint32_t)(count.address >> 32), max_count, mode },
    };
    r = add_args_pass(prims, list, count, max_count, TB_PRIMS_SCAN_TILE, args);
    if (!r) r = add_indirect(prims, list, prims->scan_reduce, &push, sizeof push, args);
    if (!r) r = add_fixed(prims, list, prims->scan_spine, &push, sizeof push, 1);
    if (!r) r = add_indirect(prims, list, last, &push, sizeof push, args);
    return r;
}

tb_result tb_prims_scan(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr in, tb_gpu_ptr out,
                        tb_gpu_ptr count, uint32_t max_count, tb_gpu_ptr total,
                        tb_gpu_ptr scratch)
{
    return record_scan(prims, list, TB_PRIMS_SCAN_MODE_SUM, prims->scan_down, in, out, count,
                       max_count, total, scratch);
}

tb_result tb_prims_compact(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr flags, tb_gpu_ptr out,
                           tb_gpu_ptr count, uint32_t max_count, tb_gpu_ptr out_count,
                           tb_gpu_ptr scratch)
{
    tb_result r = check_ptr(prims, out_count, "compacted count");
    return r ? r : record_scan(prims, list, TB_PRIMS_SCAN_MODE_FLAGS, prims->compact_scatter,
                               flags, out, count, max_count, out_count, scratch);
}

/* ---- radix sort -------------------------------------------------------------------------- */

/* Scratch of the sort: the plan (dispatch of the blocks, of the spine, then tiles per block
 * and blocks), the digit counts of every block (digit-major), the digit totals, and the
 * temporary keys and values the passes alternate with. */
typedef struct sort_scratch {
    tb_gpu_ptr args, spine_args, spine, totals, keys, values;
    VkDeviceSize size;
} sort_scratch;

static sort_scratch sort_layout(const tb_prims* prims, tb_gpu_ptr base, uint32_t max_count)
{
    sort_scratch s;
    uint32_t blocks = tiles_of(max_count, TB_PRIMS_SORT_TILE);
    if (blocks > prims->sort_max_blocks) blocks = prims->sort_max_blocks;
    VkDeviceSize spine_bytes = 4 * (VkDeviceSize)TB_PRIMS_RADIX * blocks;
    VkDeviceSize array_bytes = align_up(4 * (VkDeviceSize)(max_count ? max_count : 1), AREA_ALIGN);
    VkDeviceSize at = ARGS_BYTES;
    s.args = base;
    s.spine_args = tb_gpu_ptr_add(base, 16);
    s.spine = tb_gpu_ptr_add(base, at);
    at += align_up(spine_bytes ? spine_bytes : 4, AREA_ALIGN);
    s.totals = tb_gpu_ptr_add(base, at);
    at += align_up(4 * TB_PRIMS_RADIX, AREA_ALIGN);
    s.keys = tb_gpu_ptr_add(base, at);
    at += array_bytes;
    s.values = tb_gpu_ptr_add(base, at);
    s.size = at + array_bytes;
    return s;
}

VkDeviceSize tb_prims_sort_scratch(const tb_prims* prims, uint32_t max_count)
{
    tb_gpu_ptr none = { VK_NULL_HANDLE, 0, 0 };
    return sort_layout(prims, none, max_count).size;
}

/* One pass over `bits` key bits from `shift`: histogram -> spine -> scatter. */
static tb_result sort_pass(tb_prims* prims, tb_pass_list* list, tb_gpu_sort_push* push,
                           const sort_scratch* s, uint32_t shift, uint32_t bits)
{
    push->count.w = shift | bits << 8;
    tb_result r = add_indirect(prims, list, prims->sort_histogram, push, sizeof *push, s->args);
    if (!r) r = add_indirect(prims, list, prims->sort_spine, push, sizeof *push, s->spine_args);
    if (!r) r = add_indirect(prims, list, prims->sort_scatter, push, sizeof *push, s->args);
    return r;
}

tb_result tb_prims_sort(tb_prims* prims, tb_pass_list* list, tb_gpu_ptr keys, tb_gpu_ptr values,
                        tb_gpu_ptr count, uint32_t max_count, uint32_t key_bits,
                        tb_gpu_ptr scratch)
{
    tb_result r = check_scratch(prims, scratch, max_count);
    if (!r) r = check_ptr(prims, keys, "keys");
    if (!r) r = check_ptr(prims, values, "values");
    if (!r) r = check_ptr(prims, count, "count");
    if (!r && (key_bits < 1 || key_bits > 32))
        r = tb_fail(prims->diag, TB_ERROR_INVALID_ARGUMENT, "sort key bits %u not in 1..32", key_bits);
    if (r) return r;
    sort_scratch s = sort_layout(prims, scratch, max_count);
    /* Passes alternate between the caller's arrays and the temporary ones. */
    VkDeviceAddress key_arrays[2] = { keys.address, s.keys.address };
    VkDeviceAddress value_arrays[2] = { values.address, s.values.address };
    tb_gpu_sort_push push = {
        .spine = tb_gpu_addresses(s.spine.address, s.totals.address),
        .count = { (uint32_t)count.address, (uint32_t)(count.address >> 32), max_count, 0 },
        .plan = { (uint32_t)s.args.address, (uint32_t)(s.args.address >> 32),
                  prims->group_size / prims->subgroup_size, prims->sort_max_blocks },
    };
    r = add_fixed(prims, list, prims->sort_args, &push, sizeof push, 1);
    uint32_t pass = 0;
    for (uint32_t shift = 0; !r && shift < key_bits; shift += TB_PRIMS_RADIX_BITS, pass++) {
        uint32_t bits = key_bits - shift < TB_PRIMS_RADIX_BITS ? key_bits - shift : TB_PRIMS_RADIX_BITS;
        push.keys = tb_gpu_addresses(key_arrays[pass & 1], key_arrays[(pass + 1) & 1]);
        push.values = tb_gpu_addresses(value_arrays[pass & 1], value_arrays[(pass + 1) & 1]);
        r = sort_pass(prims, list, &push, &s, shift, bits);
    }
    if (!r && (pass & 1)) { /* the last pass wrote the temporary arrays */
        push.keys = tb_gpu_addresses(s.keys.address, keys.address);
        push.values = tb_gpu_addresses(s.values.address, values.address);
        r = add_indirect(prims, list, prims->copy, &push, sizeof push, s.args);
    }
    return r;
}
