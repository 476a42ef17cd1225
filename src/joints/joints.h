/* Joints: the host's table of joint slots and its GPU image, which the block solver reads
 * (glsl/block/joint.glsl).
 *
 * Reads the joint records the world hands it (defs already checked, bodies as slots);
 * writes three GPU arrays: the joints (tb_gpu_joint, uploaded whole up to the slots in use
 * whenever one changed), their state (tb_gpu_joint_state, written only by the GPU: it
 * starts a slot's state anew when the joint's generation differs from the state's, so a
 * reused slot needs no upload), and the table of body pairs that must not collide (an
 * open-addressed hash set of slot pairs, which the broadphases look up). Capacities double;
 * growth copies the state over and says so, since the step records its joint passes for a
 * capacity.
 */
#ifndef TB_JOINTS_JOINTS_H
#define TB_JOINTS_JOINTS_H

#include "base/slots.h"
#include "gpu/memory.h"
#include "gpu/transfer.h"
#include "layout.h"
#include "tumble.h"

/// Host record of a joint slot.
typedef struct tb_joint_record {
    uint16_t generation;
    uint8_t alive;
    uint32_t body_a, body_b;   ///< body slots
    tb_joint_def def;          ///< as created (limits and motor as last set)
} tb_joint_record;

typedef struct tb_joints {
    tb_memory* memory;
    tb_slots slots;
    uint32_t capacity;           ///< slots the host records and GPU arrays hold
    tb_joint_record* records;
    tb_gpu_joint* table;         ///< host image of the GPU's joints
    tb_buffer joints, state;     ///< tb_gpu_joint[capacity], tb_gpu_joint_state[capacity]
    tb_buffer filter;            ///< uvec2[filter_size]: body pairs that do not collide
    uint32_t filter_size;        ///< a power of two, 0 when no joint keeps its bodies apart
    uint32_t filter_capacity;    ///< entries the filter buffer holds
    uint32_t no_collide;         ///< live joints with collide_connected off
    uint32_t* filter_host;       ///< host image of the filter, two slots + 1 an entry
    int table_dirty, filter_dirty;
} tb_joints;

tb_result tb_joints_init(tb_joints* j, tb_memory* memory, tb_transfer* t);
void tb_joints_destroy(tb_joints* j);

/// Room for `count` more joints (records and GPU arrays); *grew is set when the arrays were
/// replaced (the step must record its joint passes again).
tb_result tb_joints_reserve(tb_joints* j, tb_transfer* t, uint32_t count, int* grew);
/// Take a slot for a checked def whose bodies are the slots a and b (room reserved).
uint32_t tb_joints_add(tb_joints* j, const tb_joint_def* def, uint32_t a, uint32_t b);
void tb_joints_remove(tb_joints* j, uint32_t slot);
/// The record of a joint slot changed (limits, motor): upload it with the next step.
void tb_joints_changed(tb_joints* j, uint32_t slot);

/// Before a submission's transfer: build the filter table of the pairs that do not collide,
/// if it changed (may replace its buffer: its address goes in the params).
tb_result tb_joints_prepare(tb_joints* j);
/// tb_gpu_params.joint_info: slots in use, the filter's entries and address.
tb_gpu_uvec4 tb_joints_params(const tb_joints* j);
/// Staging bytes of what awaits upload, and its uploads (clears the marks).
VkDeviceSize tb_joints_upload_bytes(const tb_joints* j);
void tb_joints_record_uploads(tb_joints* j, tb_transfer* t);

/// The GPU states of `count` slots, fresh from the device, into out.
tb_result tb_joints_read_state(tb_joints* j, tb_transfer* t, const uint32_t* slots,
                               uint32_t count, tb_gpu_joint_state* out);

#endif
