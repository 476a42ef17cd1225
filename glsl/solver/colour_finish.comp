#version 450
#extension GL_GOOGLE_include_directive : require
// After the colouring rounds, one workgroup (any size; 64 = one thread per colour):
// - colour[c].y = first index of colour c in the colour list (exclusive scan of the counts,
//   the same the claim passes wrote for the recorded rounds), colour[c].z = batches before c;
// - colour_dispatch[c] = workgroups of TB_SOLVER_WORKGROUP_SIZE covering colour[c].x
//   threads, rows in y beyond TB_DISPATCH_MAX_X;
// - solver.x colours used, solver.y constraints left uncoloured, solver.z batches: a colour
//   is cut into batches of the subgroup width, each solved by one subgroup.
// Constraints left uncoloured when fewer than TB_MAX_COLOURS rounds were recorded abandon the
// step (TB_ABORT_COLOURS): the host records more rounds and runs the step again. With every
// round recorded, solver/solve_tail solves them instead.
// Each thread sums the counts below its colour itself: 64 independent loads beat a scan's
// barriers at this size.
#include "world.glsl"

uint batches_of(uint count)
{
    return (count + SUBGROUP_SIZE - 1u) / SUBGROUP_SIZE;
}

void write_colour(uint c)
{
    uint first = 0u, batches = 0u;
    for (uint k = 0u; k < c; k++) {
        uint n = counters.colour[k].x;
        first += n;
        batches += batches_of(n);
    }
    counters.colour[c].y = first;
    counters.colour[c].z = batches;
    counters.colour_dispatch[c] = dispatch_covering(counters.colour[c].x, TB_SOLVER_WORKGROUP_SIZE);
}

void write_totals()
{
    uint coloured = 0u, used = 0u, batches = 0u;
    for (uint c = 0u; c < TB_MAX_COLOURS; c++) {
        uint n = counters.colour[c].x;
        coloured += n;
        used += n > 0u ? 1u : 0u;
        batches += batches_of(n);
    }
    uint left = counters.solver.y - coloured;
    counters.solver.x = used;
    counters.solver.y = left;
    counters.solver.z = batches;
    if (left > 0u && params.capacity.z < TB_MAX_COLOURS)
        atomicOr(counters.state.x, TB_ABORT_COLOURS);
}

void main()
{
    // Every thread reads the abort flag before thread 0 may set it, or the threads of a later
    // subgroup would see this very pass's flag and stop half-way.
    bool aborted = step_aborted();
    barrier();
    if (aborted) return;
    for (uint c = gl_LocalInvocationID.x; c < TB_MAX_COLOURS; c += gl_WorkGroupSize.x)
        write_colour(c);
    if (gl_LocalInvocationID.x == 0u) write_totals();
}
