"""The binding's reach over include/tumble.h, on lavapipe: every shape (triangle meshes,
capsules, cylinders and cones included), single bodies' poses, velocities and impulses,
gravity, destroy, contacts as a numpy structured array, stats, the log and the device.
Scenes are a handful of bodies and tens of steps."""
import numpy as np
import pytest

import tumble

DT = 1 / 60


def test_contact_dtype_matches_the_c_struct():
    ffi = tumble.ffi
    assert tumble.CONTACT.itemsize == ffi.sizeof("tb_contact")
    for name, field in ffi.typeof("tb_contact").fields:
        assert tumble.CONTACT.fields[name][1] == ffi.offsetof("tb_contact", name) == field.offset
    assert tumble.CONTACT["point"].shape == (3,) and tumble.CONTACT["point"].base == np.float32
    assert tumble.BODY_ID.itemsize == ffi.sizeof("tb_body_id")
    assert tumble.BODY_ID.names == ("index1", "world", "generation")
    assert tumble.BODY_ID.fields["generation"][1] == ffi.offsetof("tb_body_id", "generation")


def test_box_resting_on_a_plane_has_contacts_that_carry_its_weight(make_world):
    world = make_world()
    ground = world.add_body(world.plane((0, 1, 0), 0.0), static=True)
    box = world.add_body(world.box((0.5, 0.25, 0.5)), position=(0, 0.25, 0))
    assert world.shape_type(world.box((1, 1, 1))) == "box"
    world.step(DT, n=60)
    contacts = world.contacts()
    assert contacts.dtype == tumble.CONTACT and len(contacts) == 4
    assert world.stats()["contact_count"] == 4
    assert all(tumble.Body(*c["a"]) == ground and tumble.Body(*c["b"]) == box for c in contacts)
    np.testing.assert_allclose(contacts["normal"], np.tile([0, 1, 0], (4, 1)), atol=1e-4)
    assert np.all(np.abs(contacts["separation"]) < 0.02)
    np.testing.assert_allclose(np.sort(np.abs(contacts["point"][:, [0, 2]]), axis=0),
                               np.full((4, 2), 0.5), atol=0.01)
    mass, inertia = world.mass(box)
    assert mass == pytest.approx(1000 * 1.0 * 0.5 * 1.0)
    assert inertia[1] == pytest.approx(mass * (1 + 1) / 12, rel=1e-4)
    assert contacts["normal_impulse"].sum() == pytest.approx(mass * 9.81 * DT, rel=0.02)
    assert len(set(contacts["feature"].tolist())) == 4
    assert world.mass(ground)[0] == 0 and world.body_type(ground) == "static"
    assert world.body_type(box) == "dynamic"


def test_sphere_falls_with_gravity_and_gravity_can_change(make_world):
    world = make_world(gravity=(0, -5, 0))
    np.testing.assert_allclose(world.gravity, [0, -5, 0])
    ball = world.add_body(world.sphere(0.5), position=(0, 10, 0))
    world.step(DT, n=30)
    (v, w), (p, q) = world.velocity(ball), world.pose(ball)
    assert v[1] == pytest.approx(-5 * 0.5, rel=1e-3) and np.allclose(w, 0)
    assert p[1] == pytest.approx(10 - 0.5 * 5 * 0.25, abs=0.02)
    np.testing.assert_allclose(q, [0, 0, 0, 1], atol=1e-6)
    world.gravity = (1, 0, 0)
    world.step(DT, n=30)
    v, _ = world.velocity(ball)
    np.testing.assert_allclose(v, [0.5, -2.5, 0], rtol=1e-3, atol=1e-5)


def test_poses_velocities_and_impulses_of_single_bodies(make_world):
    world = make_world(gravity=(0, 0, 0))
    ball = world.add_body(world.sphere(0.5, density=500))
    mass, _ = world.mass(ball)
    assert mass == pytest.approx(500 * 4 / 3 * np.pi * 0.125, rel=1e-5)
    world.set_pose(ball, (1, 2, 3), (0, 0, np.sin(0.25), np.cos(0.25)))
    p, q = world.pose(ball)
    np.testing.assert_allclose(p, [1, 2, 3])
    np.testing.assert_allclose(q, [0, 0, np.sin(0.25), np.cos(0.25)], atol=1e-6)
    world.set_velocity(ball, linear=(0, 0, 2))
    world.apply_impulse(ball, (mass * 3, 0, 0))                    # at its centre: no spin
    v, w = world.velocity(ball)
    np.testing.assert_allclose(v, [3, 0, 2], rtol=1e-5)
    np.testing.assert_allclose(w, 0, atol=1e-6)
    world.step(0.5)
    np.testing.assert_allclose(world.pose(ball)[0], [2.5, 2, 4], atol=1e-4)
    world.set_velocity(ball)
    world.apply_impulse(ball, (0, 0, 1), point=world.pose(ball)[0] + (1, 0, 0))  # off centre
    _, w = world.velocity(ball)
    assert w[1] < 0 and abs(w[0]) < 1e-6                         # r x J = (0, -1, 0)


def test_add_bodies_takes_rotations_velocities_and_body_properties(make_world):
    world = make_world(gravity=(0, 0, 0))
    quarter = (0, np.sin(np.pi / 4), 0, np.cos(np.pi / 4))
    bodies = world.add_bodies(world.box((1, 0.5, 0.25)), [[0, 0, 0], [10, 0, 0]],
                              rotations=quarter, velocities=[[1, 0, 0], [0, 2, 0]],
                              angular_velocities=(0, 0, 0), mass=3, linear_damping=0.0)
    p, q = world.transforms(bodies)
    np.testing.assert_allclose(q, np.tile(quarter, (2, 1)), atol=1e-6)
    assert world.mass(bodies[1])[0] == pytest.approx(3)
    world.step(1.0)
    p, _ = world.transforms(bodies)
    np.testing.assert_allclose(p, [[1, 0, 0], [10, 2, 0]], atol=1e-4)
    mins, maxs = world.aabbs(bodies)                              # as the step began
    np.testing.assert_allclose(mins[0], [-0.25, -0.5, -1], atol=1e-4)   # turned a quarter
    np.testing.assert_allclose(maxs[0][1:], [0.5, 1], atol=1e-4)
    assert 0.25 - 1e-4 <= maxs[0][0] <= 1.25 + 1e-4              # widened along its path
    floaty = world.add_body(world.sphere(0.1), (0, 5, 0), gravity_scale=0.0)
    world.gravity = (0, -9.81, 0)
    world.step(DT, n=10)
    assert np.allclose(world.velocity(floaty)[0], 0)


def test_hull_shape(make_world):
    world = make_world()
    cube = np.array([[x, y, z] for x in (0, 2) for y in (0, 2) for z in (0, 2)], float)
    points = np.concatenate([cube, [[1, 1, 1], [1, 0, 1]]])        # inside, on a face
    hull = world.hull(points)
    assert world.shape_type(hull) == "hull"
    info = world.hull_info(hull)
    assert (info["vertex_count"], info["face_count"], info["edge_count"]) == (8, 6, 12)
    assert info["volume"] == pytest.approx(8)
    np.testing.assert_allclose(info["center_of_mass"], [1, 1, 1], atol=1e-5)
    np.testing.assert_allclose(info["unit_inertia"], [8 / 12] * 3, rtol=1e-4)
    vertices = world.hull_vertices(hull)
    assert vertices.shape == (8, 3)
    np.testing.assert_allclose(np.sort(np.abs(vertices).ravel()), 1, atol=1e-5)
    world.add_body(world.plane((0, 1, 0)), static=True)
    rock = world.add_body(hull, (0, 1.5, 0))
    world.step(DT, n=60)
    assert world.pose(rock)[0][1] == pytest.approx(1.0, abs=0.03)   # resting on a face
    with pytest.raises(tumble.TumbleError) as caught:
        world.hull([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])    # flat: no volume
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    with pytest.raises(tumble.TumbleError):
        world.hull_info(world.sphere(1))


QUAD = [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]         # y = 0, 4 m square
UP = [[0, 2, 1], [0, 3, 2]]                                       # counter-clockwise from +y


def grid_mesh(quads, size):
    """A flat square of quads x quads quads, `size` m across at y = 0, facing up."""
    x = np.linspace(-size / 2, size / 2, quads + 1)
    xx, zz = np.meshgrid(x, x, indexing="ij")
    vertices = np.stack([xx, np.zeros_like(xx), zz], axis=-1).reshape(-1, 3)
    at = np.arange((quads + 1) ** 2).reshape(quads + 1, quads + 1)
    a, b, c, d = at[:-1, :-1], at[1:, :-1], at[1:, 1:], at[:-1, 1:]   # +x is i, +z is j
    triangles = np.concatenate([np.stack([a, d, c], -1), np.stack([a, c, b], -1)])
    return vertices, triangles.reshape(-1, 3)


def test_mesh_geometry_and_info_round_trip(make_world):
    world = make_world()
    quad = world.mesh(np.array(QUAD, dtype=np.float64), np.array(UP, dtype=np.int64),
                      friction=0.5)
    assert world.shape_type(quad) == "mesh"
    info = world.mesh_info(quad)
    assert (info["vertex_count"], info["triangle_count"]) == (4, 2)
    assert (info["degenerate_count"], info["active_edge_count"]) == (0, 4)  # not the diagonal
    np.testing.assert_array_equal(info["aabb_min"], [-2, 0, -2])
    np.testing.assert_array_equal(info["aabb_max"], [2, 0, 2])
    vertices, triangles = world.mesh_geometry(quad)
    assert vertices.dtype == np.float32 and triangles.dtype == np.uint32
    np.testing.assert_array_equal(vertices, QUAD)
    np.testing.assert_array_equal(triangles, UP)
    grid = world.mesh(*grid_mesh(20, 10.0))
    info = world.mesh_info(grid)
    assert (info["triangle_count"], info["active_edge_count"]) == (800, 80)   # the border
    flat = world.mesh(QUAD, UP + [[1, 1, 2]])                       # one of zero area
    assert world.mesh_info(flat)["degenerate_count"] == 1
    with pytest.raises(tumble.TumbleError, match="is not a mesh"):
        world.mesh_info(world.sphere(1))


def test_heightfield_holds_a_ball_and_lets_one_through_a_hole(make_world):
    world = make_world()
    heights = np.zeros((9, 9))                  # 8 x 8 cells of 1 m, centred: x, z in [-4, 4]
    holes = np.zeros((8, 8), bool)
    holes[4, 4] = True                          # the cell x, z in [0, 1]
    field = world.heightfield(heights, (1.0, 1.0), holes)
    assert world.shape_type(field) == "heightfield"
    world.add_body(field, static=True)
    resting = world.add_body(world.sphere(0.3), (-2.5, 0.3, 1.5))
    falling = world.add_body(world.sphere(0.3), (0.5, 0.3, 0.5))
    world.step(DT, n=90)
    np.testing.assert_allclose(world.pose(resting)[0], [-2.5, 0.3, 1.5], atol=1e-3)
    assert world.pose(falling)[0][1] < -1.0


def test_sphere_rests_on_a_two_triangle_mesh(make_world):
    world = make_world()
    world.add_body(world.mesh(QUAD, UP), static=True)
    ball = world.add_body(world.sphere(0.5), (0.3, 0.5, -0.2))
    heights = []
    for _ in range(120):
        world.step(DT)
        heights.append(world.pose(ball)[0][1])
    assert np.all(np.abs(np.array(heights) - 0.5) < 1e-3), heights
    np.testing.assert_allclose(world.pose(ball)[0][[0, 2]], [0.3, -0.2], atol=1e-3)


def test_box_dropped_on_a_mesh_grid_comes_to_rest_above_it(make_world):
    world = make_world()
    world.add_body(world.mesh(*grid_mesh(20, 10.0)), static=True)
    box = world.add_body(world.box((0.5, 0.25, 0.5)), (0.3, 1.0, 0.1),
                         rotation=(0, np.sin(0.2), 0, np.cos(0.2)))
    world.step(DT, n=120)
    p, _ = world.pose(box)
    v, w = world.velocity(box)
    assert p[1] == pytest.approx(0.25, abs=0.01)
    assert np.linalg.norm(v) < 0.01 and np.linalg.norm(w) < 0.01
    assert len(world.contacts()) > 0


def test_destroy_bodies_and_shapes(make_world):
    world = make_world()
    ball = world.sphere(0.5)
    bodies = world.add_bodies(ball, np.arange(12, dtype=float).reshape(4, 3) * 2)
    assert len(world.body_ids()) == 4 and len(world.isolated_bodies()) == 0
    world.destroy(bodies[1])
    assert world.is_valid(bodies).tolist() == [True, False, True, True]
    with pytest.raises(tumble.TumbleError, match=r"what\[1\].*nothing was destroyed") as caught:
        world.destroy(bodies)
    assert caught.value.code == tumble.lib.TB_ERROR_STALE_ID
    assert world.stats()["body_count"] == 3
    with pytest.raises(ValueError, match="twice"):
        world.destroy(bodies[[0, 0]])
    with pytest.raises(tumble.TumbleError) as caught:
        world.destroy(ball)                                        # bodies still use it
    assert caught.value.code == tumble.lib.TB_ERROR_IN_USE
    rest = bodies[[0, 2, 3]]
    assert world.body_ids().index(rest).tolist() == [0, 1, 2]
    world.destroy(rest)
    assert len(world.body_ids()) == 0
    world.destroy(ball)
    assert not world.is_valid(ball)
    with pytest.raises(tumble.TumbleError) as caught:
        world.velocity(bodies[0])
    assert caught.value.code == tumble.lib.TB_ERROR_STALE_ID and caught.value.result
    world.step(DT)
    assert world.stats()["body_count"] == 0


def test_bodies_index_maps_contacts_to_bodies(make_world):
    world = make_world()
    world.add_body(world.plane((0, 1, 0)), static=True)
    pile = world.add_bodies(world.box((0.5, 0.5, 0.5)), [[0, 0.5, 0], [0, 1.5, 0], [5, 0.5, 0]])
    world.step(DT, n=20)
    contacts = world.contacts()
    a, b = pile.index(contacts["a"]), pile.index(contacts["b"])
    pairs = {tuple(sorted((int(i), int(j)))) for i, j in zip(a, b)}
    assert pairs == {(-1, 0), (-1, 2), (0, 1)}                    # -1: the ground
    assert pile.index(pile[2]) == 2 and pile.index(world.body_ids()[0]) == -1
    assert len(pile[1:]) == 2 and len(pile + pile[:1]) == 4 and list(pile)[1] == pile[1]


def test_stats_device_log_and_version(make_world):
    lines = []
    world = make_world(broadphase="sap", substeps=4, log=lambda level, text: lines.append(
        (level, text)))
    world.add_bodies(world.sphere(0.5), [[0, 0, 0], [0, 0.9, 0]])
    world.step(DT, n=3)
    stats = world.stats()
    assert stats["broadphase"] == "sap" and stats["steps"] == 3 and stats["submits"] == 1
    assert stats["body_count"] == 2 and stats["shape_count"] == 1 and stats["pair_count"] == 1
    assert stats["gpu_ms"] > 0 and "integrate/integrate" in stats["stages"]
    info = world.device_info()
    assert info["is_cpu"] and "llvmpipe" in info["name"] and info["subgroup_size"] > 0
    with pytest.raises(tumble.TumbleError):
        world.sphere(0)
    assert ("info", "sphere radius must be finite and > 0, not 0") in lines
    assert tumble.version()[0] == tumble.HEADER_VERSION[0]
    assert tumble.__version__ == "%d.%d.%d" % tumble.HEADER_VERSION
    assert set(tumble.BROADPHASES) == {"default", "grid", "sap", "lbvh", "isap"}


def test_shape_ids_list_live_shapes_in_slot_order(make_world):
    world = make_world()
    a, b, c = world.sphere(1.0), world.box((1, 1, 1)), world.sphere(2.0)
    world.destroy(b)
    assert world.shape_ids() == [a, c]
    again = world.box((2, 2, 2))
    assert world.shape_ids() == [a, again, c]
    assert not world.is_valid(b) and world.is_valid(again)


def test_compound_composes_mass_and_stands_on_its_children(make_world):
    world = make_world()
    world.add_body(world.plane((0, 1, 0)), static=True)
    ball = world.sphere(0.25)
    dumbbell = world.compound([(ball, (1.0, 0.5, 0.0)), (ball, (-1.0, 0.5, 0.0), (0, 0, 0, 1))])
    assert world.shape_type(dumbbell) == "compound"
    info = world.compound_info(dumbbell)
    assert info["child_count"] == 2
    np.testing.assert_allclose(info["center_of_mass"], [0, 0.5, 0], atol=1e-6)
    np.testing.assert_allclose(sorted(info["unit_inertia"]),
                               [0.4 * 0.25 ** 2, 0.4 * 0.25 ** 2 + 1, 0.4 * 0.25 ** 2 + 1],
                               rtol=1e-5)
    children = world.compound_children(dumbbell)
    assert [c[0] for c in children] == [ball, ball]
    np.testing.assert_allclose(np.linalg.norm(children[0][1]), 1.0, rtol=1e-6)
    assert world.sphere_radius(ball) == 0.25
    np.testing.assert_array_equal(world.box_half_extents(world.box((1, 2, 3))), [1, 2, 3])
    body = world.add_body(dumbbell, (0, 0.3, 0), rotation=info["principal_axes"])
    world.step(DT, n=60)
    np.testing.assert_allclose(world.pose(body)[0], [0, 0.25, 0], atol=2e-3)
    with pytest.raises(tumble.TumbleError, match=r"only convex shapes \(spheres, boxes, "
                                                 r"hulls, capsules, cylinders, cones\)"):
        world.compound([(world.plane((0, 1, 0)), (0, 0, 0))])
    with pytest.raises(tumble.TumbleError, match="is used by"):
        world.destroy(ball)
    with pytest.raises(TypeError, match="child 0 must be"):
        world.compound([ball])


QUARTER_Z = (0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4))         # y axis turned onto x


def test_capsules_cylinders_and_cones_are_made_and_read_back(make_world):
    world = make_world()
    capsule = world.capsule(0.3, 0.5, density=500, friction=0.6, restitution=0.1)
    cylinder = world.cylinder(np.float32(0.25), 1)                   # numpy and int sizes
    cone = world.cone(0.2, np.float64(0.75))
    ball = world.capsule(0.4, 0)                                     # half height 0: a sphere
    assert [world.shape_type(s) for s in (capsule, cylinder, cone, ball)] == \
        ["capsule", "cylinder", "cone", "capsule"]
    assert world.round_size(capsule) == (np.float32(0.3), np.float32(0.5))
    assert world.round_size(cylinder) == (0.25, 1.0)
    assert world.round_size(cone) == (np.float32(0.2), 0.75)
    assert world.round_size(ball) == (np.float32(0.4), 0.0)
    assert all(isinstance(x, float) for x in world.round_size(cone))
    mass, inertia = world.mass(world.add_body(capsule, (0, 5, 0)))
    volume = np.pi * 0.3 ** 2 * 2 * 0.5 + 4 / 3 * np.pi * 0.3 ** 3
    assert mass == pytest.approx(500 * volume, rel=1e-5)
    assert inertia[0] == pytest.approx(inertia[2]) and inertia[1] < inertia[0]
    mass, inertia = world.mass(world.add_body(cylinder, (5, 5, 0)))    # default density
    assert mass == pytest.approx(1000 * np.pi * 0.25 ** 2 * 2, rel=1e-5)
    assert inertia[1] == pytest.approx(mass * 0.25 ** 2 / 2, rel=1e-4)
    mass, inertia = world.mass(world.add_body(cone, (10, 5, 0)))
    assert mass == pytest.approx(1000 * np.pi * 0.2 ** 2 * 1.5 / 3, rel=1e-5)
    assert inertia[1] == pytest.approx(mass * 0.3 * 0.2 ** 2, rel=1e-4)
    assert world.mass(world.add_body(ball, (15, 5, 0)))[0] == pytest.approx(
        1000 * 4 / 3 * np.pi * 0.4 ** 3, rel=1e-5)
    with pytest.raises(tumble.TumbleError, match="is not a capsule, cylinder or cone") \
            as caught:
        world.round_size(world.sphere(1))
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    with pytest.raises(tumble.TumbleError, match="is not a capsule, cylinder or cone"):
        world.round_size(world.box((1, 1, 1)))
    with pytest.raises(TypeError, match="shape must be a tumble.Shape .*capsule"):
        world.round_size("capsule")
    world.destroy(world.body_ids())
    world.destroy(cone)
    with pytest.raises(tumble.TumbleError) as caught:
        world.round_size(cone)
    assert caught.value.code == tumble.lib.TB_ERROR_STALE_ID


@pytest.mark.parametrize("make, size, rotation, height", [
    ("capsule", (0.3, 0.5), (0, 0, 0, 1), 0.8),                  # standing on a cap
    ("capsule", (0.3, 0.5), QUARTER_Z, 0.3),                     # lying on its side
    ("cylinder", (0.3, 0.4), (0, 0, 0, 1), 0.4),                 # standing on its base
    ("cone", (0.3, 0.4), (0, 0, 0, 1), 0.2),                     # base at -half_height / 2
])
def test_round_shapes_rest_on_a_plane(make_world, make, size, rotation, height):
    world = make_world()
    world.add_body(world.plane((0, 1, 0)), static=True)
    body = world.add_body(getattr(world, make)(*size), (0.2, height, -0.1), rotation=rotation)
    positions = []
    for _ in range(90):
        world.step(DT)
        positions.append(world.pose(body)[0])
    positions = np.array(positions)
    assert np.all(np.abs(positions - [0.2, height, -0.1]) < 1e-3), positions
    np.testing.assert_allclose(world.pose(body)[1], rotation, atol=1e-3)
    contacts = world.contacts()
    assert len(contacts) > 0
    np.testing.assert_allclose(contacts["normal"], np.tile([0, 1, 0], (len(contacts), 1)),
                               atol=1e-4)
    mass, _ = world.mass(body)
    assert contacts["normal_impulse"].sum() == pytest.approx(mass * 9.81 * DT, rel=0.02)


def test_compound_with_capsule_children(make_world):
    """A sled of two capsule runners lying along x, 1 m apart, and a box deck: it stands on
    its runners."""
    world = make_world()
    world.add_body(world.plane((0, 1, 0)), static=True)
    runner, deck = world.capsule(0.1, 0.6), world.box((0.5, 0.05, 0.6))
    sled = world.compound([(runner, (0, 0, 0.5), QUARTER_Z), (runner, (0, 0, -0.5), QUARTER_Z),
                           (deck, (0, 0.15, 0))])
    assert world.shape_type(sled) == "compound"
    info = world.compound_info(sled)
    assert info["child_count"] == 3
    runner_volume = np.pi * 0.1 ** 2 * 1.2 + 4 / 3 * np.pi * 0.1 ** 3
    deck_volume = 1.0 * 0.1 * 1.2
    assert info["volume"] == pytest.approx(2 * runner_volume + deck_volume, rel=1e-5)
    centre = info["center_of_mass"]
    np.testing.assert_allclose(centre, [0, 0.15 * deck_volume / info["volume"], 0], atol=1e-6)
    children = world.compound_children(sled)
    assert [c[0] for c in children] == [runner, runner, deck]
    assert world.round_size(children[0][0]) == (np.float32(0.1), np.float32(0.6))
    body = world.add_body(sled, centre + (0, 0.1, 0), rotation=info["principal_axes"])
    world.step(DT, n=60)
    np.testing.assert_allclose(world.pose(body)[0], centre + (0, 0.1, 0), atol=2e-3)
    assert world.mass(body)[0] == pytest.approx(1000 * info["volume"], rel=1e-5)
    with pytest.raises(tumble.TumbleError, match="is used by"):
        world.destroy(runner)
    cup = world.compound([(world.cylinder(0.3, 0.05), (0, 0, 0)),
                          (world.cone(0.2, 0.3), (0, 0.3, 0))])
    assert world.compound_info(cup)["child_count"] == 2


def test_snapshot_and_restore(make_world):
    world = make_world()
    world.add_body(world.plane((0, 1, 0), 0), (0, 0, 0), static=True)
    pile = world.add_bodies(world.box((0.5, 0.5, 0.5)), [(0, 0.5 + 1.2 * i, 0.1 * i) for i in range(4)])
    world.step(n=10)
    saved = world.snapshot()
    world.step(n=30)
    after = world.transforms(pile)[0].copy()
    world.restore(saved)
    world.step(n=30)
    assert (world.transforms(pile)[0] == after).all()
    with pytest.raises(tumble.TumbleError, match="checksum"):
        world.restore(saved[:-1] + bytes([saved[-1] ^ 1]))
    with pytest.raises(TypeError):
        world.restore("not bytes")
