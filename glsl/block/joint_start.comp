#version 450
#extension GL_GOOGLE_include_directive : require
// Per joint slot, beside block/start (after the colouring, so a step abandoned there leaves
// the joints as they were): a joint starts its step as a contact does: its multipliers from
// the share params.block.w of last step's, its stiffnesses from the larger of the starting
// stiffness (params.block.x units: its bodies' effective mass, or moment, over dt^2) and
// the share params.block_more.w of last step's. A slot whose state is of another joint
// (the slot was reused: the generations differ) starts from nothing.
#include "joint.glsl"

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= params.joint_info.x || step_aborted()) return;
    tb_gpu_joint jt = joints[j];
    if (joint_kind(jt) == TB_GPU_JOINT_NONE) return;
    tb_gpu_joint_state s = joint_states[j];
    if (s.info.x != jt.info.w) {
        s.linear = vec4(0.0);
        s.angular = vec4(0.0);
        s.axial = vec4(0.0);
        s.force = vec4(0.0);
        s.torque = vec4(0.0);
        s.info = uvec4(jt.info.w, 0u, 0u, 0u);
    } else if (s.info.y != 0u) {
        return;
    }
    vec2 unit = joint_units(jt) * params.block.x;
    float warm = params.block.w, carry = params.block_more.w;
    uint kind = joint_kind(jt);
    s.linear = vec4(s.linear.xyz * warm, max(unit.x, s.linear.w * carry));
    s.angular = vec4(s.angular.xyz * warm, max(unit.y, s.angular.w * carry));
    float axial_unit = kind == TB_GPU_JOINT_HINGE ? unit.y : unit.x;
    s.axial = vec4(s.axial.x * warm, max(axial_unit, s.axial.y * carry),
                   s.axial.z * warm, max(axial_unit, s.axial.w * carry));
    s.info.z = s.axial.x != 0.0 ? 1u : 0u;   // the limit pushed last step: engaged
    joint_states[j] = s;
}
