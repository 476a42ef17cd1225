/* The GPU layout seen from C must be exactly the layout the shaders assume (std140/std430
 * with vec4-sized members), and its constants must agree with the public header. No GPU. */
#include "harness.h"
#include "layout.h"

#include <string.h>

/* Every member is one 16-byte vector, so C and GLSL agree only if C adds no padding. */
static void test_vec4_types(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_gpu_vec4), 16);
    assert_int_equal(sizeof(tb_gpu_uvec4), 16);
    assert_int_equal(offsetof(tb_gpu_vec4, x), 0);
    assert_int_equal(offsetof(tb_gpu_vec4, y), 4);
    assert_int_equal(offsetof(tb_gpu_vec4, z), 8);
    assert_int_equal(offsetof(tb_gpu_vec4, w), 12);
    assert_int_equal(offsetof(tb_gpu_uvec4, x), 0);
    assert_int_equal(offsetof(tb_gpu_uvec4, w), 12);
}

static void test_params_layout(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_gpu_params), 240);
    assert_int_equal(offsetof(tb_gpu_params, block_joints), 224);
    assert_int_equal(offsetof(tb_gpu_params, joint_arrays), 192);
    assert_int_equal(offsetof(tb_gpu_params, joint_info), 208);
    assert_int_equal(offsetof(tb_gpu_params, contact_arrays), 128);
    assert_int_equal(offsetof(tb_gpu_params, block), 160);
    assert_int_equal(offsetof(tb_gpu_params, block_more), 176);
    assert_int_equal(offsetof(tb_gpu_params, capacity), 64);
    assert_int_equal(offsetof(tb_gpu_params, contact), 80);
    assert_int_equal(offsetof(tb_gpu_params, soft), 96);
    assert_int_equal(offsetof(tb_gpu_params, soft_static), 112);
    assert_int_equal(offsetof(tb_gpu_params, gravity), 0);
    assert_int_equal(offsetof(tb_gpu_params, counts), 16);
    assert_int_equal(offsetof(tb_gpu_params, limits), 32);
    assert_int_equal(offsetof(tb_gpu_params, body_dispatch), 48);
    /* vkCmdDispatchIndirect reads three uint32 at this offset of the params buffer. */
    assert_int_equal(TB_PARAMS_BODY_DISPATCH_OFFSET, offsetof(tb_gpu_params, body_dispatch));
    assert_int_equal(TB_PARAMS_BODY_DISPATCH_OFFSET % 4, 0);
    /* A uniform block is a whole number of vec4. */
    assert_int_equal(sizeof(tb_gpu_params) % 16, 0);
}

static void test_shape_layout(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_gpu_shape), 96);
    assert_int_equal(sizeof(tb_gpu_bvh_node), 16);
    assert_true(sizeof(tb_gpu_bvh_query_push) <= 128);
    assert_int_equal(sizeof(tb_gpu_solver_body), 96);
    assert_int_equal(offsetof(tb_gpu_shape, aabb_center), 0);
    assert_int_equal(offsetof(tb_gpu_shape, aabb_half), 16);
    assert_int_equal(offsetof(tb_gpu_shape, params), 32);
    assert_int_equal(offsetof(tb_gpu_shape, info), 48);
    assert_int_equal(offsetof(tb_gpu_shape, material), 64);
    assert_int_equal(offsetof(tb_gpu_shape, hull), 80);
    /* std430 array stride of the struct is its size rounded to 16. */
    assert_int_equal(sizeof(tb_gpu_shape) % 16, 0);
}

static void test_joint_layout(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_gpu_joint), 176);
    assert_int_equal(offsetof(tb_gpu_joint, anchor_a), 16);
    assert_int_equal(offsetof(tb_gpu_joint, frame_b), 64);
    assert_int_equal(offsetof(tb_gpu_joint, motor), 96);
    assert_int_equal(sizeof(tb_gpu_joint_state), 160);
    assert_int_equal(offsetof(tb_gpu_joint_state, axial), 32);
    assert_int_equal(offsetof(tb_gpu_joint_state, held_force), 48);
    assert_int_equal(offsetof(tb_gpu_joint_state, force), 80);
    assert_int_equal(offsetof(tb_gpu_joint_state, info), 112);
    /* The host passes kinds and axis modes to the GPU as they are. */
    assert_int_equal(TB_GPU_JOINT_BALL, TB_JOINT_BALL);
    assert_int_equal(TB_GPU_JOINT_HINGE, TB_JOINT_HINGE);
    assert_int_equal(TB_GPU_JOINT_FIXED, TB_JOINT_FIXED);
    assert_int_equal(TB_GPU_JOINT_DISTANCE, TB_JOINT_DISTANCE);
    assert_int_equal(TB_GPU_JOINT_SLIDER, TB_JOINT_SLIDER);
    assert_int_equal(TB_GPU_JOINT_CONE, TB_JOINT_CONE_TWIST);
    assert_int_equal(TB_GPU_JOINT_SIX_DOF, TB_JOINT_SIX_DOF);
    assert_int_equal(TB_GPU_JOINT_AXIS_LOCKED, TB_JOINT_AXIS_LOCKED);
    assert_int_equal(TB_GPU_JOINT_AXIS_FREE, TB_JOINT_AXIS_FREE);
    assert_int_equal(TB_GPU_JOINT_AXIS_LIMITED, TB_JOINT_AXIS_LIMITED);
}

/* The host writes tb_shape_type straight into info.x. */
static void test_shape_type_values(void** state)
{
    (void)state;
    assert_int_equal(TB_GPU_SHAPE_SPHERE, (unsigned)TB_SHAPE_SPHERE);
    assert_int_equal(TB_GPU_SHAPE_BOX, (unsigned)TB_SHAPE_BOX);
    assert_int_equal(TB_GPU_SHAPE_PLANE, (unsigned)TB_SHAPE_PLANE);
    assert_int_equal(TB_GPU_SHAPE_HULL, (unsigned)TB_SHAPE_HULL);
    assert_int_equal(TB_GPU_SHAPE_MESH, (unsigned)TB_SHAPE_MESH);
    assert_int_equal(TB_GPU_SHAPE_HEIGHTFIELD, (unsigned)TB_SHAPE_HEIGHTFIELD);
    assert_int_equal(TB_GPU_SHAPE_COMPOUND, (unsigned)TB_SHAPE_COMPOUND);
    assert_int_equal(sizeof(tb_gpu_compound_child), 64);
    /* A mesh pair's compound child rides above the triangle: 64 children fit. */
    assert_true(TB_COMPOUND_MAX_CHILDREN <= (1u << (32 - TB_PAIR_TRIANGLE_BITS)));
}

/* Two bindings on one index would alias two buffers in the descriptor set. */
static void test_bindings_distinct(void** state)
{
    (void)state;
    const int b[] = { TB_BIND_PARAMS, TB_BIND_BODY_POS, TB_BIND_BODY_ROT, TB_BIND_BODY_LINVEL,
                      TB_BIND_BODY_ANGVEL, TB_BIND_BODY_INV_INERTIA, TB_BIND_BODY_INFO,
                      TB_BIND_BODY_AABB_MIN, TB_BIND_BODY_AABB_MAX, TB_BIND_SHAPES,
                      TB_BIND_COUNTERS, TB_BIND_BODY_PAIRS, TB_BIND_SOLVER_BODIES, TB_BIND_BODY_CLAIM,
                      TB_BIND_BODY_PAIR_COUNT, TB_BIND_GRID_KEYS, TB_BIND_GRID_BODIES,
                      TB_BIND_GRID_TABLE, TB_BIND_LARGE_FLAGS, TB_BIND_LARGE_LIST, TB_BIND_PAIRS,
                      TB_BIND_COLOUR_LIST, TB_BIND_HULL_VECTORS, TB_BIND_HULL_TOPOLOGY,
                      TB_BIND_COLOUR_WORK, TB_BIND_PLUGIN_PARAMS, TB_BIND_BLOCK_START,
                      TB_BIND_BLOCK_FILL, TB_BIND_BODY_COLOUR, TB_BIND_BLOCK_LIST,
                      TB_BIND_BLOCK_TARGET };
    const int n = (int)(sizeof b / sizeof b[0]);
    for (int i = 0; i < n; i++) {
        assert_in_range(b[i], 0, TB_BIND_COUNT - 1);
        for (int j = i + 1; j < n; j++) assert_int_not_equal(b[i], b[j]);
    }
    /* TB_BIND_COUNT sizes the descriptor set layout: no unused holes expected. */
    assert_int_equal(n, TB_BIND_COUNT);
}

static void test_contact_layout(void** state)
{
    (void)state;
    /* Indirect dispatch arguments sit where the recorded vkCmdDispatchIndirect reads them. */
    assert_int_equal(offsetof(tb_gpu_counters, pair_dispatch), TB_COUNTERS_PAIR_DISPATCH_OFFSET);
    assert_int_equal(offsetof(tb_gpu_counters, colour_dispatch), TB_COUNTERS_COLOUR_DISPATCH_OFFSET);
    assert_int_equal(sizeof(tb_gpu_counters) % 16, 0);
    assert_int_equal(sizeof(tb_gpu_manifold), 16 * (4 + 2 * TB_MAX_MANIFOLD_POINTS) +
                                               8 * TB_MAX_MANIFOLD_POINTS +
                                               16 * (3 + 2 * TB_MAX_MANIFOLD_POINTS));
    assert_int_equal(offsetof(tb_gpu_manifold, point), 32);
    assert_int_equal(offsetof(tb_gpu_manifold, impulse), 32 + 16 * TB_MAX_MANIFOLD_POINTS);
    assert_int_equal(sizeof(tb_gpu_constraint), 32 + 48 * TB_MAX_MANIFOLD_POINTS);
    assert_int_equal(sizeof(tb_gpu_push), 16);
    /* Claims hold the round above the index bits; the pair capacity fits the index bits. */
    assert_true(TB_MAX_COLOURS <= (1 << (32 - TB_COLOUR_INDEX_BITS)));
}

/* The broadphases' structs: vec4 members only, so std430 and C agree; push constants fit
 * the pipeline layout's range. */
static void test_broadphase_layout(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_gpu_broadphase_push), 80);
    assert_true(sizeof(tb_gpu_broadphase_push) <= 128);
    assert_int_equal(sizeof(tb_gpu_lbvh_push), 80);
    assert_int_equal(sizeof(tb_gpu_lbvh_node), 32);
    assert_int_equal(offsetof(tb_gpu_lbvh_node, hi), 16);
    assert_int_equal(sizeof(tb_gpu_lbvh_bounds), 32);
    assert_int_equal(sizeof(tb_gpu_isap_header), 32);
    assert_int_equal(sizeof(tb_gpu_isap_control), 4 * 16 + 2 * 32);
    assert_int_equal(offsetof(tb_gpu_isap_control, header), 64);
    assert_int_equal(sizeof(tb_gpu_sap_partial), 32);
    assert_int_equal(sizeof(tb_gpu_sap_header), 16);
    assert_int_not_equal(TB_BROADPHASE_COUNT, TB_BROADPHASE_WRITE);
    /* Keys beyond every Morton code and every ordered float key. */
    assert_true(TB_LBVH_KEY_DEAD < (1u << TB_LBVH_SORT_BITS));
    assert_true(TB_LBVH_KEY_LARGE >= (1u << TB_LBVH_KEY_BITS));
    assert_true(TB_SAP_KEY_LARGE > 0xff800000u && TB_ISAP_KEY_LARGE > 0xff800000u);
}

static void test_spec_ids(void** state)
{
    (void)state;
    assert_int_not_equal(TB_SPEC_WORKGROUP_SIZE, TB_SPEC_SUBGROUP_SIZE);
}

static void test_misc_constants(void** state)
{
    (void)state;
    /* Flags are distinct single bits. */
    assert_int_equal(TB_BODY_FLAG_ALIVE & TB_BODY_FLAG_DYNAMIC, 0);
    assert_int_equal(TB_BODY_FLAG_ALIVE & (TB_BODY_FLAG_ALIVE - 1), 0);
    assert_int_equal(TB_BODY_FLAG_DYNAMIC & (TB_BODY_FLAG_DYNAMIC - 1), 0);
    /* Workgroup size: a power of two that a subgroup of 4, 8, 32 or 64 divides. */
    assert_true(TB_WORKGROUP_SIZE >= 64 && (TB_WORKGROUP_SIZE & (TB_WORKGROUP_SIZE - 1)) == 0);
    /* The unbounded extent must survive squaring in float (no inf in distance math). */
    float e = (float)TB_UNBOUNDED_EXTENT;
    assert_true(e * e < 3.0e38f);
    assert_true(e >= 1.0e17f);
}

/* The public ABI: ids and result codes are pinned sizes. */
static void test_public_abi_sizes(void** state)
{
    (void)state;
    assert_int_equal(sizeof(tb_result), 4);
    assert_int_equal(sizeof(tb_body_id), 8);
    assert_int_equal(sizeof(tb_shape_id), 8);
    assert_int_equal(sizeof(tb_vec3), 12);
    assert_int_equal(sizeof(tb_quat), 16);
    assert_int_equal(offsetof(tb_quat, w), 12);
    assert_int_equal(sizeof(tb_shape_type), 4);
    assert_int_equal(sizeof(tb_body_type), 4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vec4_types),
        cmocka_unit_test(test_params_layout),
        cmocka_unit_test(test_shape_layout),
        cmocka_unit_test(test_joint_layout),
        cmocka_unit_test(test_shape_type_values),
        cmocka_unit_test(test_bindings_distinct),
        cmocka_unit_test(test_contact_layout),
        cmocka_unit_test(test_broadphase_layout),
        cmocka_unit_test(test_spec_ids),
        cmocka_unit_test(test_misc_constants),
        cmocka_unit_test(test_public_abi_sizes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
