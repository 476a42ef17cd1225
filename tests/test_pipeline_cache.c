/* The pipeline cache file: written at destruction with a header naming this device, read
 * back by the next world, and a foreign or damaged file is ignored rather than trusted. */
#include "harness.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <vulkan/vulkan.h>

static char cache_path[64];

static int setup(void** state)
{
    (void)state;
    snprintf(cache_path, sizeof cache_path, "/tmp/tumble-cache-test-%ld.bin", (long)getpid());
    remove(cache_path);
    return 0;
}

static int teardown(void** state)
{
    (void)state;
    remove(cache_path);
    return 0;
}

/* One world that builds its pipelines, steps, and is destroyed (which saves the cache). */
static tb_device_info run_world(void)
{
    tb_world_def def = tb_default_world_def();
    def.pipeline_cache_path = cache_path;
    tb_world* w = th_world_create(&def);
    tb_body_def body_def = th_dynamic_def(th_sphere(w, 0.5f), th_v3(0, 1, 0));
    tb_body_id body;
    th_assert_ok(tb_body_create(w, &body_def, &body));
    tb_device_info info;
    th_assert_ok(tb_world_device_info(w, &info));
    th_assert_ok(tb_world_step(w, 1.0f / 60));
    th_world_destroy(w);
    return info;
}

static VkPipelineCacheHeaderVersionOne read_header(long* size)
{
    VkPipelineCacheHeaderVersionOne header;
    memset(&header, 0, sizeof header);
    FILE* f = fopen(cache_path, "rb");
    assert_non_null(f);
    assert_int_equal(fread(&header, 1, sizeof header, f), sizeof header);
    fseek(f, 0, SEEK_END);
    *size = ftell(f);
    fclose(f);
    return header;
}

static void test_cache_is_written_for_this_device(void** state)
{
    (void)state;
    tb_device_info info = run_world();
    long size;
    VkPipelineCacheHeaderVersionOne header = read_header(&size);
    assert_true(size >= (long)sizeof header);
    assert_int_equal(header.headerVersion, VK_PIPELINE_CACHE_HEADER_VERSION_ONE);
    assert_int_equal(header.vendorID, info.vendor_id);
    assert_int_equal(header.deviceID, info.device_id);
}

static void test_damaged_cache_is_ignored_and_replaced(void** state)
{
    (void)state;
    FILE* f = fopen(cache_path, "wb");
    assert_non_null(f);
    for (int i = 0; i < 4096; i++) fputc((i * 37) & 0xff, f);
    fclose(f);
    tb_device_info info = run_world();
    long size;
    VkPipelineCacheHeaderVersionOne header = read_header(&size);
    assert_int_equal(header.vendorID, info.vendor_id);
    assert_int_equal(header.deviceID, info.device_id);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_cache_is_written_for_this_device, setup, teardown),
        cmocka_unit_test_setup_teardown(test_damaged_cache_is_ignored_and_replaced, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
