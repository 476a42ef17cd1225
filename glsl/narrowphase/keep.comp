#version 450
#extension GL_GOOGLE_include_directive : require
// Last stage of the contact work of a step: this step's manifolds, with the impulses the
// solver ended with, become "last step's" for the next step's warm start. Kept apart from
// this step's (rather than alternating halves of one array) so each array stays within a
// storage buffer binding's range for twice as many pairs.
#include "world.glsl"

void main()
{
    uint p = pair_thread_index();
    if (step_aborted() || p >= counters.state.z) return;
    prev_manifolds[p] = manifolds[p];
}
