// tumble.h from C++: this translation unit includes the public header, compiled as C++11
// with every warning an error, and uses it: a world, a shape, bodies made one at a time and
// in bulk, steps, a bulk read, stats, errors. It proves the header is C++-clean (extern "C",
// no C-only constructs) and links against the C library; so is the plugin header, whose
// structs a C++ plugin fills. Exits nonzero on failure; the
// validation layer is on under `make test` and any message it gives fails the test.
#include "tumble.h"
#include "tumble_plugin.h"

#include <cmath>
#include <cstdio>
#include <vector>

static int failures = 0;

static void expect(bool ok, const char* what)
{
    if (!ok) {
        std::fprintf(stderr, "test_cplusplus: %s\n", what);
        failures++;
    }
}

int main()
{
    tb_world_def def = tb_default_world_def();
    def.broadphase = TB_BROADPHASE_LBVH;
    tb_world* world = nullptr;
    if (tb_world_create(&def, &world) != TB_OK) {
        std::fprintf(stderr, "test_cplusplus: %s\n", tb_world_last_error(nullptr));
        return 1;
    }
    tb_shape_def shape_def = tb_default_shape_def();
    tb_shape_id ball;
    expect(tb_shape_create_sphere(world, &shape_def, 0.5f, &ball) == TB_OK, "sphere");
    expect(tb_shape_create_sphere(world, &shape_def, -1.0f, &ball) == TB_ERROR_INVALID_ARGUMENT,
           "a negative radius is refused");
    std::vector<tb_body_def> defs(100, tb_default_body_def());
    for (size_t i = 0; i < defs.size(); i++) {
        defs[i].shape = ball;
        defs[i].position = tb_vec3{ 2.0f * static_cast<float>(i), 10.0f, 0.0f };
    }
    std::vector<tb_body_id> ids(defs.size());
    expect(tb_body_create_many(world, defs.data(), static_cast<uint32_t>(defs.size()),
                               ids.data()) == TB_OK, "bodies in bulk");
    expect(tb_world_step_n(world, 1.0f / 60.0f, 30) == TB_OK, "steps");
    std::vector<tb_vec3> positions(ids.size());
    std::vector<tb_quat> rotations(ids.size());
    expect(tb_world_read_transforms(world, ids.data(), static_cast<uint32_t>(ids.size()),
                                    positions.data(), rotations.data()) == TB_OK, "bulk read");
    // Half a second of free fall: 1.23 m down, within the substeps' discretisation.
    for (size_t i = 0; i < positions.size(); i++)
        expect(std::fabs(positions[i].y - (10.0f - 0.5f * 9.81f * 0.25f)) < 0.02f, "free fall");
    tb_world_stats stats;
    expect(tb_world_get_stats(world, &stats) == TB_OK, "stats");
    expect(stats.body_count == 100 && stats.pair_count == 0, "counts");
    expect(stats.validation_messages == 0, "validation messages");
    tb_plugin_id plugin;
    expect(tb_world_load_plugin(world, "no-such-plugin.so", &plugin) == TB_ERROR_INVALID_ARGUMENT,
           "a missing plugin is refused");
    tb_plugin_stage stage = {};
    stage.size = sizeof stage;
    stage.point = TB_PLUGIN_POST_STEP;
    expect(stage.size >= 48 && TB_PLUGIN_ABI_VERSION >= 1u, "plugin structs");
    tb_world_destroy(world);
    return failures ? 1 : 0;
}
