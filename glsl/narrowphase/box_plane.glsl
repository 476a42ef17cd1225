// Box against plane: the box corners within the margin of the plane, at most four (the
// deepest). A box lying flat gives its four bottom corners; on an edge two; on a corner
// one. Feature key: the corner index (bit i set = the corner's coordinate i is +h_i).
#ifndef TB_NP_BOX_PLANE_GLSL
#define TB_NP_BOX_PLANE_GLSL

// Corner i of a box with half extents h, box frame.
vec3 np_box_corner(vec3 h, uint i)
{
    return vec3((i & 1u) != 0u ? h.x : -h.x, (i & 2u) != 0u ? h.y : -h.y,
                (i & 4u) != 0u ? h.z : -h.z);
}

// The box is first, the plane second: the normal points from the box into the plane's
// solid side.
uint np_box_plane(np_target t, np_body box, np_body plane, float margin, out vec3 normal)
{
    vec4 half_space = np_world_plane(plane);
    normal = -half_space.xyz;
    vec3 n_local = transpose(box.rot) * half_space.xyz;
    float centre = dot(half_space.xyz, box.pos) - half_space.w;
    vec3 h = box.params.xyz;
    uint near = 0u;
    for (uint i = 0u; i < 8u; i++)
        if (centre + dot(n_local, np_box_corner(h, i)) < margin) near++;
    uint count = 0u;
    for (uint i = 0u; i < 8u; i++) {
        float height = centre + dot(n_local, np_box_corner(h, i));
        if (height >= margin) continue;
        if (near > 4u) {
            // Keep the four deepest: corners deeper than this one, ties by index.
            uint rank = 0u;
            for (uint j = 0u; j < 8u; j++) {
                float other = centre + dot(n_local, np_box_corner(h, j));
                if (other < height || (other == height && j < i)) rank++;
            }
            if (rank >= 4u) continue;
        }
        vec3 corner = box.pos + box.rot * np_box_corner(h, i);
        np_emit(t, count, corner - half_space.xyz * (0.5 * height), height, i);
        count++;
    }
    return count;
}

#endif
