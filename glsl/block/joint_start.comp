#version 450
#extension GL_GOOGLE_include_directive : require
// Per joint slot, beside block/start (after the colouring, so a step abandoned there leaves
// the joints as they were): a joint starts its step as a contact does: its multipliers from
// the share params.block_joints.y of last step's, its stiffnesses from the larger of the
// starting stiffness (params.block.x units: its bodies' effective mass, or moment, over
// dt^2) and the share params.block_joints.z of last step's; and it keeps the values its hard
// rows start with, which the step's first sweeps hold (joint_record_start). A slot whose
// state is of another joint (the slot was reused: the generations differ) starts from
// nothing.
#include "joint.glsl"

// A joint starts its step with less of last step's multipliers and stiffnesses than a
// contact (tb_block_settings: 0.475 and 0.9, against 0.95 and 0.99): structures whose
// joints hold more conditions than their bodies have freedoms, each sweep leaving a little
// over, gathered multipliers and stiffness from step to step until they shook themselves
// apart. With a contact's share a 10 x 10 net of spheres on ball joints hanging still
// opened its joints by 13 cm within 150 steps (lavapipe), and a bridge of 40 hinged planks
// under a load twisted about its length and turned over by step 200; with half the
// contacts' multipliers and 0.9 of the stiffness a 20 x 20 net holds within 0.06 mm over
// 600 steps, a 100-plank bridge within 0.1 mm (NVIDIA H200, docs/joints.md). With the hold
// sweeps the contact's shares still tore nets and bridges apart.

// The limits that pushed last step, engaged from the step's start (joint_limit_row's bits).
uint engaged_limits(uint kind, tb_gpu_joint_state s)
{
    if (kind == TB_GPU_JOINT_SIX_DOF) {
        uint bits = 0u;
        for (int i = 0; i < 3; i++) {
            if (s.linear[i] != 0.0) bits |= 1u << i;
            if (s.angular[i] != 0.0) bits |= 8u << i;
        }
        return bits;
    }
    return (s.axial.x != 0.0 ? 1u : 0u) | (kind == TB_GPU_JOINT_CONE && s.axial.z != 0.0 ? 2u : 0u);
}

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
        s.held_force = vec4(0.0);
        s.held_torque = vec4(0.0);
        s.force = vec4(0.0);
        s.torque = vec4(0.0);
        s.info = uvec4(jt.info.w, 0u, 0u, 0u);
    } else if (s.info.y != 0u) {
        // Broken: it holds nothing from the step after it broke on.
        joint_states[j].force = vec4(0.0);
        joint_states[j].torque = vec4(0.0);
        return;
    }
    vec2 unit = joint_units(jt.info.xy) * params.block.x;
    float warm = params.block_joints.y, carry = params.block_joints.z;
    uint kind = joint_kind(jt);
    // Last step's force and torque, and whether this step predicts with them: a joint that
    // is all its dynamic bodies have (a pendulum's rod; no other joint, no contact) does,
    // so its bodies swing on their circle instead of out past it each step to be pulled
    // back along the radius, which cost a 1 m pendulum 28 % of its energy a period (0.08 %
    // over ten periods with the prediction). Where a body has more (a chain's links), the
    // predicted forces and torques from its several joints are explicit stiff terms on a
    // light body: with them a hanging chain of three started to swing by itself, and one
    // with a heavy end blew up. A bound on the force as well (twice the lighter body's
    // weight, from before `alone`) made a pendulum let go level lose its swing until its
    // tension at the bottom was within the bound, at 60 degrees: it turned at 2.76, 2.63,
    // 2.55, 2.51, 2.50 m of the 3 m it started at (lavapipe; tools/python/README.md's
    // pendulum), and turns at 2.999, 2.996, 2.994, ... without it.
    vec3 force = s.held_force.xyz + s.linear.xyz, torque = s.held_torque.xyz + s.angular.xyz;
    uint a = jt.info.x, b = jt.info.y;
    bool alone = (!block_dynamic(a) || block_fill[a] == 1u) &&
                 (!block_dynamic(b) || block_fill[b] == 1u);
    bool predict = joint_may_hold(kind) && alone;
    s.held_force = predict ? vec4(force, 1.0) : vec4(0.0);
    s.held_torque = predict ? vec4(torque, 0.0) : vec4(0.0);
    vec3 linear = predict ? vec3(0.0) : (joint_may_hold(kind) ? force : s.linear.xyz) * warm;
    vec3 angular = predict ? vec3(0.0) : (joint_may_hold(kind) ? torque : s.angular.xyz) * warm;
    s.linear = vec4(linear, max(unit.x, s.linear.w * carry));
    s.angular = vec4(angular, max(unit.y, s.angular.w * carry));
    bool turns = kind == TB_GPU_JOINT_HINGE || kind == TB_GPU_JOINT_CONE;
    float axial_unit = turns ? unit.y : unit.x;
    s.axial = vec4(s.axial.x * warm, max(axial_unit, s.axial.y * carry),
                   s.axial.z * warm, max(axial_unit, s.axial.w * carry));
    s.info.z = engaged_limits(kind, s);
    joint_states[j] = s;
    joint_record_start(j, s);
}
