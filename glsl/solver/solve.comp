#version 450
#extension GL_GOOGLE_include_directive : require
// Batched projected Gauss-Seidel over the contacts of one colour: push.args.x = colour c,
// push.args.y = iteration. Thread i < counters.colour[c].x solves the constraint of pair
// colour_list[colour[c].y + i]; constraints of one colour touch disjoint dynamic bodies, so
// they run in parallel without atomics and the result does not depend on their order.
// Dispatched with counters.colour_dispatch[c], workgroups of TB_SOLVER_WORKGROUP_SIZE.
//
// Materials, combined by the narrowphase into the manifold: friction sqrt(fa * fb) (a
// slippery surface makes the contact slippery, two rough ones stay rough), restitution
// max(ea, eb) (a bouncy ball bounces on any floor).
//
// Per point and iteration: the normal impulse, accumulated and clamped >= 0, drives the
// relative normal velocity to its target (0 at rest, -e * vn for a bounce, -s / dt for a
// speculative point s apart); then the two friction impulses, accumulated and clamped
// together to a circular cone of radius mu * normal impulse (no preferred direction, unlike
// a box per tangent). A sweep with push.args.z = 1 before the first iteration applies the
// previous step's impulses (warm start) to every constraint.
//
// Penetration is recovered by split impulses: a second accumulated normal impulse
// (impulse.w) drives pseudo velocities (solver_bodies push) towards a recovery rate; integrate moves
// the pose with v + push but keeps v. A positional bias in the real velocity would turn
// penetration into kinetic energy, so deep contacts would pop apart and stacks would jitter;
// split impulses move the bodies apart without making them faster.
#include "contact.glsl"

void main()
{
    if (step_aborted()) return;
    uint colour = push.args.x;
    uint i = pair_thread_index();
    if (colour >= TB_MAX_COLOURS || i >= counters.colour[colour].x) return;
    uint p = colour_list[counters.colour[colour].y + i];
    if (push.args.z != 0u) warm_start_contact(p);
    else solve_contact(p);
}
