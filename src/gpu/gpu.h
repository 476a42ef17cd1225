/* src/gpu/: the Vulkan plumbing, and nothing of physics.
 *
 *   device.h     instance, device choice, queue, submission, validation messages
 *   memory.h     buffers and their device addresses
 *   transfer.h   staging uploads and downloads around a submission
 *   pipeline.h   compute pipelines from the embedded SPIR-V, the shared descriptor set
 *   glsl.h, watch.h   run-time GLSL compilation and file watching for hot-reload (reload.c)
 *   graph.h      the step graph: stages of passes recorded into one command buffer
 *   prims.h      parallel primitives: radix sort, scan, compaction, fill, indirect args
 *
 * It reads and writes whatever buffers its callers name; it knows no stage. Every stage
 * borrows the plumbing as a tb_gpu_kit: where errors go, the device, memory, transfers,
 * pipelines, the primitives and the step graph. A stage keeps a copy of this struct (the
 * pointers stay valid for the world's life) and sees nothing else of the world but the
 * buffers its own narrow struct names. */
#ifndef TB_GPU_GPU_H
#define TB_GPU_GPU_H

#include "base/diag.h"
#include "gpu/device.h"
#include "gpu/graph.h"
#include "gpu/memory.h"
#include "gpu/pipeline.h"
#include "gpu/prims.h"
#include "gpu/transfer.h"

typedef struct tb_gpu_kit {
    tb_diag* diag;
    tb_gpu* gpu;
    tb_memory* memory;
    tb_pipelines* pipelines;
    tb_transfer* transfer;
    tb_prims* prims;
    tb_graph* graph;
} tb_gpu_kit;

/// Fill a buffer with zeros and wait for it (state that must start empty).
tb_result tb_gpu_kit_clear(const tb_gpu_kit* kit, const tb_buffer* buffer);

#endif
