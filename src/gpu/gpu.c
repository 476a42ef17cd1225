/* What the plumbing's users share beyond the plumbing itself. */
#include "gpu/gpu.h"

tb_result tb_gpu_kit_clear(const tb_gpu_kit* kit, const tb_buffer* buffer)
{
    tb_result r = tb_transfer_begin(kit->transfer, 0);
    if (r) return r;
    vkCmdFillBuffer(kit->transfer->cb, buffer->buffer, 0, VK_WHOLE_SIZE, 0);
    r = tb_transfer_end(kit->transfer);
    return r ? r : tb_gpu_submit_wait(kit->gpu, &kit->transfer->cb, 1);
}
