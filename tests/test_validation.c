/* The tests' guard must be able to fire: with validation on, a real usage error and a real
 * synchronization hazard each reach the world's diag as counted messages. Uses the core's
 * internal GPU layer directly, since the public API never makes such mistakes. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include <string.h>

#include "gpu/device.h"
#include "gpu/memory.h"

typedef struct fixture {
    tb_diag diag;
    tb_gpu gpu;
    tb_memory memory;
    tb_buffer buffer;
    VkCommandBuffer cb;
} fixture;

static void quiet(void* user, tb_log_level level, const char* message)
{
    (void)user; (void)level; (void)message;
}

static int setup(void** state)
{
    static fixture f;
    memset(&f, 0, sizeof f);
    f.diag.log = quiet;
    tb_gpu_options options;
    memset(&options, 0, sizeof options);
    options.validation = 1;
    assert_int_equal(tb_gpu_create(&f.gpu, &options, &f.diag), TB_OK);
    assert_int_equal(tb_memory_init(&f.memory, &f.gpu), TB_OK);
    assert_int_equal(tb_gpu_command_buffer(&f.gpu, &f.cb), TB_OK);
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO };
    assert_int_equal(vkBeginCommandBuffer(f.cb, &begin), VK_SUCCESS);
    *state = &f;
    return 0;
}

static int teardown(void** state)
{
    fixture* f = *state;
    vkEndCommandBuffer(f->cb);
    tb_buffer_destroy(&f->memory, &f->buffer);
    tb_memory_destroy(&f->memory);
    tb_gpu_destroy(&f->gpu);
    return 0;
}

static void test_usage_error_is_counted(void** state)
{
    fixture* f = *state;
    /* A fill needs TRANSFER_DST usage; this buffer lacks it. */
    assert_int_equal(tb_buffer_create(&f->memory, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 0,
                                      &f->buffer), TB_OK);
    uint64_t before = f->diag.validation_messages;
    vkCmdFillBuffer(f->cb, f->buffer.buffer, 0, 256, 0);
    assert_true(f->diag.validation_messages > before);
}

static void test_missing_barrier_is_counted(void** state)
{
    fixture* f = *state;
    assert_int_equal(tb_buffer_create(&f->memory, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0,
                                      &f->buffer), TB_OK);
    vkCmdFillBuffer(f->cb, f->buffer.buffer, 0, 256, 1);
    uint64_t before = f->diag.validation_messages;
    /* Two writes to the same bytes with no barrier between them: a write-after-write hazard
     * that only synchronization validation sees. */
    vkCmdFillBuffer(f->cb, f->buffer.buffer, 0, 256, 2);
    assert_true(f->diag.validation_messages > before);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_usage_error_is_counted, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_barrier_is_counted, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
