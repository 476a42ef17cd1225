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
#include "block.glsl"
#include "../integrate/motion.glsl"

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
    solver_bodies[i].delta_position.xyz = v * h;
}
