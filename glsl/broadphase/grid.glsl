// The uniform grid: an unbounded lattice of cubic cells, hashed into a table by modulo.
//
// A cell is as wide as the largest dynamic body's AABB plus the contact margin (and 1 %
// so rounding cannot matter), so the centres of two boxes that overlap (within the margin)
// lie in the same or in neighbouring cells. Each body is entered once, in the cell of its
// AABB's centre; a body searches its own and the 26 neighbouring cells. Static bodies
// wider than a cell are "large": they stay out of the grid and every dynamic body tests
// them directly, so one ground box or plane cannot ruin the cell size.
#ifndef TB_GRID_GLSL
#define TB_GRID_GLSL

float grid_cell_size()
{
    float largest = uintBitsToFloat(counters.grid.x);
    return max(largest + params.contact.x, 1.0e-6) * 1.01;
}

// Entries whose key is the table size sort after every real cell: dead and large bodies.
uint grid_sentinel()
{
    return params.capacity.y + 1u;
}

ivec3 grid_cell_of(uint body, float cell)
{
    vec3 centre = 0.5 * (body_aabb_min[body].xyz + body_aabb_max[body].xyz);
    return ivec3(floor(centre / cell));
}

uint grid_hash(ivec3 c)
{
    uvec3 u = uvec3(c);
    return ((u.x * 73856093u) ^ (u.y * 19349663u) ^ (u.z * 83492791u)) & params.capacity.y;
}

bool grid_is_large(uint body, float cell)
{
    vec3 side = body_aabb_max[body].xyz - body_aabb_min[body].xyz;
    return !body_is(body, TB_BODY_FLAG_DYNAMIC) &&
           (body_is(body, TB_BODY_FLAG_MESH) || max(side.x, max(side.y, side.z)) > cell);
}

#endif
