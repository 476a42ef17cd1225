#version 450
#extension GL_GOOGLE_include_directive : require
// Batched projected Gauss-Seidel over the contacts of one colour: push.args.x = colour c,
// push.args.y = substep, push.args.z = what the sweep does (TB_SOLVE_*). Thread i <
// counters.colour[c].x works on the constraint of pair colour_list[colour[c].y + i];
// constraints of one colour touch disjoint dynamic bodies, so they run in parallel without
// atomics and the result does not depend on their order. Dispatched with
// counters.colour_dispatch[c], workgroups of TB_SOLVER_WORKGROUP_SIZE.
//
// Materials, combined by the narrowphase into the manifold: friction sqrt(fa * fb) (a
// slippery surface makes the contact slippery, two rough ones stay rough), restitution
// max(ea, eb) (a bouncy ball bounces on any floor).
//
// The step is a soft step (Box2D v3): each substep applies gravity, warm-starts every
// constraint, solves with penetration pushed out by a stiff damped spring, moves the bodies
// (solver/substep), then relaxes: solves again without the push so its velocity does not
// survive into the motion. Restitution follows the last substep. Penetration is thus
// corrected through positions tracked within the step, never by a bias left in the final
// velocities, so stacks rest without jitter and deep contacts do not pop apart.
#include "contact.glsl"

void main()
{
    if (step_aborted()) return;
    uint colour = push.args.x;
    uint i = pair_thread_index();
    if (colour >= TB_MAX_COLOURS || i >= counters.colour[colour].x) return;
    contact_sweep(colour_list[counters.colour[colour].y + i], push.args.z, push.args.y);
}
