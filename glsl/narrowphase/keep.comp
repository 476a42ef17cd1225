#version 450
#extension GL_GOOGLE_include_directive : require
// Last stage of the contact work of a step: this step's manifolds, with the impulses the
// solver ended with, become "last step's" for the next step's warm start. Kept apart from
// this step's (rather than alternating halves of one array) so each array stays within a
// storage buffer binding's range for twice as many pairs.
//
// An empty manifold (most of a pile's pairs) keeps only what the next step reads of it
// whatever its count (the normal, count, features and cached axis): its points, impulses
// and slips are read only below the count, and copying them was most of this pass.
#include "world.glsl"

void main()
{
    uint p = pair_thread_index();
    if (step_aborted() || p >= counters.state.z) return;
    uvec4 info = manifolds[p].info;
    if (info.x != 0u) {
        prev_manifolds[p] = manifolds[p];
        return;
    }
    prev_manifolds[p].normal = manifolds[p].normal;
    prev_manifolds[p].info = info;
    prev_manifolds[p].feature = manifolds[p].feature;
    prev_manifolds[p].axis = manifolds[p].axis;
}
