#version 450
#extension GL_GOOGLE_include_directive : require
// Per dynamic body, after start: the pose the iterations start from. The inertial pose
// (velocity with gravity, over the step) is where a body in free flight goes, but a body
// at rest on others would start each step sunk by g dt^2 into them and the sweeps would
// spend themselves lifting the pile back. So the guess takes back as much of gravity as the
// forces its contacts ended last step with hold up: a resting body starts where it is.
// Those forces whole, though a contact starts the step with only the share params.block.w
// of them (start.comp): with the share, a resting body started sunk by (1 - share) g dt^2
// and the sweeps lifted it back each step (H200, 30 sweeps: the columns scene drifted
// 1.5 cm in 600 steps instead of 3.4 mm, the deep pile of 4,000 ended 99.6 % at rest
// instead of 100 %). Only that much: the rest of those forces (an impact's, a push
// sideways) is left to the solve, or a stale impact force would launch the body. The
// solve's target stays the inertial pose: where the velocity after gravity takes the body
// in the step (in one piece: block/end moves the body on by what the pieces add), and the
// turn the substep passes predicted (in pieces, the spin changing between them by the
// gyroscopic term as in the soft step's substeps), both kept in block_target.
#include "joint.glsl"
#include "../integrate/motion.glsl"

// The force and torque (about its centre) that body i's joints' predictions hold it with
// (joint_held_on; block/joint_start says which joints predict).
void joints_held(uint i, out vec3 force, out vec3 torque)
{
    force = vec3(0.0);
    torque = vec3(0.0);
    if (params.joint_info.x == 0u) return;
    uint first = block_start[i], n = block_fill[i];
    for (uint e = 0u; e < n; e++) {
        uint entry = block_entries[first + e].x;
        if (!block_is_joint(entry)) continue;
        vec3 f, t;
        joint_held_on(block_joint_of(entry), block_is_b(entry), f, t);
        force += f;
        torque += t;
    }
}

// The body's joints push it over the step as their predictions hold it: its velocities
// change by that force and torque, its prediction (block_target, and where the sweeps
// start) with them.
void add_joints(uint i, float h, inout vec3 v)
{
    vec3 force, torque;
    joints_held(i, force, torque);
    if (force == vec3(0.0) && torque == vec3(0.0)) return;
    tb_gpu_solver_body s = solver_bodies[i];
    vec3 dv = h * force * s.linear.w;
    mat3 r = quat_to_mat3(body_rot[i]);
    vec3 dw = h * (r * (body_inv_inertia[i].xyz * (transpose(r) * torque)));
    v += dv;
    block_target[2u * i].xyz += dv * h;
    solver_bodies[i].angular.xyz = s.angular.xyz + dw;
    vec4 turned = normalize(quat_mul(quat_of_rotation_vector(dw * h), s.delta_rotation));
    block_target[2u * i + 1u] = turned;
    solver_bodies[i].delta_rotation = turned;
}

void main()
{
    uint i = body_thread_index();
    if (i >= params.counts.x || step_aborted() || body_colour[i] == TB_BLOCK_NOT_SOLVED) return;
    tb_gpu_solver_body s = solver_bodies[i];
    float h = block_h();
    block_target[2u * i] = vec4(s.linear.xyz * h, 0.0);
    block_target[2u * i + 1u] = s.delta_rotation;
    vec3 g = params.gravity.xyz * s.angular.w;
    float weight = length(g);
    vec3 v = s.linear.xyz;
    if (weight > 0.0) {
        vec3 up = -g / weight;
        float share = max(params.block.w, 0.01);
        float held = clamp(dot(block_contact_force(i), up) * s.linear.w / share, 0.0, weight);
        v += h * held * up;
    }
    add_joints(i, h, v);
    solver_bodies[i].delta_position.xyz = v * h;
}
