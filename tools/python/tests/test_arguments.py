"""Wrong arguments are refused before any C call, with an error that names the argument;
nothing is coerced (a (3, 2) array is not three positions, a string is not a number).
One world serves the module: every refusal leaves it unchanged."""
import numpy as np
import pytest

import tumble


@pytest.fixture(scope="module")
def world():
    w = tumble.World()
    yield w
    assert w.stats()["validation_messages"] == 0
    w.close()


@pytest.fixture(scope="module")
def ball(world):
    return world.sphere(0.5)


@pytest.mark.parametrize("positions, error, words", [
    (np.zeros((3, 2)), ValueError, r"positions must be an \(n, 3\) array.*shape \(3, 2\)"),
    (np.zeros((2, 2, 3)), ValueError, r"positions must be an \(n, 3\).*shape \(2, 2, 3\)"),
    (np.zeros(6), ValueError, r"positions must be an \(n, 3\).*shape \(6,\)"),
    (np.zeros((2, 3), dtype=complex), TypeError, "positions must hold real numbers.*complex"),
    (np.array([["1", "2", "3"]]), TypeError, "positions must hold real numbers"),
    ("1 2 3", TypeError, "positions must be real numbers"),
    ([[0, 0, 0], [1, 2]], ValueError, "positions must be a rectangular array"),
    ([[0, None, 0]], TypeError, "positions must hold real numbers.*object"),
    (np.ones((1, 3), dtype=bool), TypeError, "positions must hold real numbers.*bool"),
])
def test_add_bodies_refuses_positions_that_are_not_n_by_3_reals(world, ball, positions, error,
                                                                words):
    before = world.stats()["body_count"]
    with pytest.raises(error, match=words):
        world.add_bodies(ball, positions)
    assert world.stats()["body_count"] == before


def test_add_bodies_refuses_mismatched_and_wrong_per_body_arrays(world, ball):
    two = np.zeros((2, 3))
    with pytest.raises(ValueError, match="velocities has 3 rows but there are 2 bodies"):
        world.add_bodies(ball, two, velocities=np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"rotations must be an \(n, 4\) array"):
        world.add_bodies(ball, two, rotations=np.zeros((2, 3)))
    with pytest.raises(TypeError, match="angular_velocities must hold real numbers"):
        world.add_bodies(ball, two, angular_velocities=np.zeros((2, 3), dtype=complex))
    with pytest.raises(TypeError, match="mass must be a real number"):
        world.add_bodies(ball, two, mass="3")
    with pytest.raises(TypeError, match="static must be True or False"):
        world.add_bodies(ball, two, static="yes")
    with pytest.raises(TypeError, match="shape must be a tumble.Shape"):
        world.add_bodies("sphere", two)
    with pytest.raises(ValueError, match="inertia must be 3 numbers"):
        world.add_bodies(ball, two, inertia=(1, 2))
    with pytest.raises(tumble.TumbleError, match="mass"):           # the library's check
        world.add_bodies(ball, two, mass=-1)
    assert world.add_bodies(ball, np.zeros((0, 3))).ids.shape == (0,)
    assert world.stats()["body_count"] == 0


QUAD = [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]]
UP = [[0, 2, 1], [0, 3, 2]]


@pytest.mark.parametrize("vertices, triangles, error, words", [
    (np.zeros((3, 2)), UP, ValueError, r"vertices must be an \(n, 3\) array.*shape \(3, 2\)"),
    (QUAD, [[0, 2], [0, 3]], ValueError, r"triangles must be an \(n, 3\).*shape \(2, 2\)"),
    (QUAD, np.zeros((2, 1, 3), int), ValueError, r"triangles must be.*shape \(2, 1, 3\)"),
    (np.zeros((1, 4, 3)), UP, ValueError, r"vertices must be.*shape \(1, 4, 3\)"),
    (QUAD, np.ravel(UP), ValueError, r"triangles must be an \(n, 3\).*shape \(6,\)"),
    (QUAD, [[0, 2, 1], [0, -3, 2]], ValueError, "triangles must be indices from 0 to "
                                                 r"2\^32 - 1, got -3"),
    (QUAD, [[0, 2, 2 ** 32]], ValueError, r"triangles must be indices .* got 4294967296"),
    (QUAD, [[0, 2, 1.5]], TypeError, "triangles must hold integers.*float64"),
    (QUAD, np.array(UP, dtype=np.float32), TypeError, "triangles must hold integers.*float32"),
    (QUAD, np.array(UP) + 0j, TypeError, "triangles must hold integers.*complex"),
    (np.array(QUAD) + 1j, UP, TypeError, "vertices must hold real numbers.*complex"),
    (QUAD, np.ones((2, 3), bool), TypeError, "triangles must hold integers.*bool"),
    (QUAD, "0 2 1", TypeError, "triangles must be integers"),
    (QUAD, [[0, 2, 1], [0, 3]], ValueError, "triangles must be a rectangular array"),
    ([[-1, 0, -1], [1, np.nan, -1], [1, 0, 1], [-1, 0, 1]], UP, tumble.TumbleError,
     "triangle mesh: vertex 1 is not finite"),
    (QUAD, [[0, 2, 1], [0, 4, 2]], tumble.TumbleError,
     "triangle mesh: triangle 1's index 1 is vertex 4, but the mesh has 4 vertices"),
    (QUAD, np.zeros((0, 3), int), tumble.TumbleError, "at least one triangle"),
])
def test_mesh_refuses_what_is_not_vertices_and_triangles(world, vertices, triangles, error,
                                                         words):
    before = world.stats()["shape_count"]
    with pytest.raises(error, match=words) as caught:
        world.mesh(vertices, triangles)
    if error is tumble.TumbleError:
        assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    assert world.stats()["shape_count"] == before


def test_a_mesh_is_for_static_bodies_only(world, ball):
    quad = world.mesh(QUAD, UP)
    shapes, bodies = world.stats()["shape_count"], world.stats()["body_count"]
    with pytest.raises(tumble.TumbleError, match="is for static bodies only") \
            as caught:
        world.add_bodies(quad, [[0, 0, 0], [5, 0, 0]])
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    assert (world.stats()["shape_count"], world.stats()["body_count"]) == (shapes, bodies)
    with pytest.raises(tumble.TumbleError, match="is not a mesh"):
        world.mesh_geometry(ball)
    with pytest.raises(TypeError, match="shape must be a tumble.Shape .*mesh"):
        world.mesh_info("quad")
    world.destroy(quad)


@pytest.mark.parametrize("heights, cell, holes, error, words", [
    (np.zeros(9), (1, 1), None, ValueError, r"heights must be a \(count_z, count_x\) array"),
    (np.zeros((3, 3)) + 1j, (1, 1), None, TypeError, "heights must hold real numbers"),
    (np.zeros((3, 3)), (1, 1, 1), None, ValueError, "cell must be 2 numbers"),
    (np.zeros((3, 3)), (1, 1), np.zeros((3, 3), bool), ValueError, r"holes must be a \(2, 2\) array"),
    (np.zeros((3, 3)), (1, 1), np.zeros((2, 2)) + 0.5, TypeError, "holes must hold booleans"),
    (np.zeros((3, 3)), (0, 1), None, tumble.TumbleError, "cell sizes must be finite and > 0"),
    (np.zeros((1, 3)), (1, 1), None, tumble.TumbleError, "2 to 32768 samples"),
    (np.full((3, 3), np.inf), (1, 1), None, tumble.TumbleError, "heights must be finite"),
    (np.zeros((3, 3)), (1, 1), np.ones((2, 2), bool), tumble.TumbleError, "every cell is a hole"),
])
def test_heightfield_refuses_what_is_not_a_grid(world, heights, cell, holes, error, words):
    before = world.stats()["shape_count"]
    with pytest.raises(error, match=words):
        world.heightfield(heights, cell, holes)
    assert world.stats()["shape_count"] == before


ROUND = ["capsule", "cylinder", "cone"]


@pytest.mark.parametrize("make", ROUND)
@pytest.mark.parametrize("radius, half_height, error, words", [
    ("big", 0.5, TypeError, "radius must be a real number, got 'big'"),
    (0.5, "tall", TypeError, "half_height must be a real number, got 'tall'"),
    (0.5 + 0j, 0.5, TypeError, r"radius must be a real number, got \(0.5\+0j\)"),
    (0.5, 1j, TypeError, "half_height must be a real number, got 1j"),
    (True, 0.5, TypeError, "radius must be a real number, got True"),
    (None, 0.5, TypeError, "radius must be a real number, got None"),
    ((0.5,), 0.5, TypeError, r"radius must be a real number, got \(0.5,\)"),
    (np.array([0.5, 0.5]), 0.5, TypeError, "radius must be a real number"),
    (b"1", 0.5, TypeError, "radius must be a real number"),
    (0, 0.5, tumble.TumbleError, "not radius 0 and half height 0.5"),
    (-1, 0.5, tumble.TumbleError, "not radius -1 and half height 0.5"),
    (np.nan, 0.5, tumble.TumbleError, "not radius nan and half height 0.5"),
    (np.inf, 0.5, tumble.TumbleError, "not radius inf and half height 0.5"),
    (2e6, 0.5, tumble.TumbleError, r"not radius 2e\+06 and half height 0.5"),
    (0.5, -1, tumble.TumbleError, "not radius 0.5 and half height -1"),
    (0.5, np.nan, tumble.TumbleError, "not radius 0.5 and half height nan"),
    (0.5, -np.inf, tumble.TumbleError, "not radius 0.5 and half height -inf"),
])
def test_round_shapes_refuse_sizes_that_are_not_positive_reals(world, make, radius,
                                                               half_height, error, words):
    before = world.stats()["shape_count"]
    with pytest.raises(error, match=words) as caught:
        getattr(world, make)(radius, half_height)
    if error is tumble.TumbleError:
        assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
        assert str(caught.value).startswith(
            "%s needs a finite radius in (0, 1e6] and a finite half height in " % make)
        assert caught.value.result == "invalid argument"
    assert world.stats()["shape_count"] == before


@pytest.mark.parametrize("make", ROUND)
def test_round_shapes_half_height_zero_only_for_a_capsule(world, make):
    before = world.stats()["shape_count"]
    if make == "capsule":
        world.destroy(world.capsule(0.5, 0))
    else:
        words = (r"%s needs a finite radius in \(0, 1e6\] and a finite half height in "
                 r"\(0, 1e6\], not radius 0.5 and half height 0$" % make)
        with pytest.raises(tumble.TumbleError, match=words):
            getattr(world, make)(0.5, 0)
    assert world.stats()["shape_count"] == before


@pytest.mark.parametrize("make", ROUND)
def test_round_shapes_take_materials_as_sphere_and_box_do(world, make):
    before = world.stats()["shape_count"]
    with pytest.raises(TypeError, match="friction must be a real number, got 'high'"):
        getattr(world, make)(0.5, 0.5, friction="high")
    with pytest.raises(TypeError, match="density must be a real number"):
        getattr(world, make)(0.5, 0.5, density=1j)
    with pytest.raises(TypeError, match="restitution must be a real number"):
        getattr(world, make)(0.5, 0.5, restitution=False)
    with pytest.raises(tumble.TumbleError, match="density must be finite and >= 0, not -1"):
        getattr(world, make)(0.5, 0.5, density=-1)
    with pytest.raises(tumble.TumbleError, match=r"restitution must be in \[0, 1\], not 2"):
        getattr(world, make)(0.5, 0.5, restitution=2)
    with pytest.raises(TypeError, match="unexpected keyword argument 'mass'"):
        getattr(world, make)(0.5, 0.5, mass=1)
    assert world.stats()["shape_count"] == before
    world.destroy(getattr(world, make)(0.5, 0.5, density=0, friction=0, restitution=1))


def test_step_refuses_bad_counts_and_times(world):
    with pytest.raises(ValueError, match=r"n must be a non-negative integer \(the number of "
                                         r"steps\) below 2\^32, got -1"):
        world.step(n=-1)
    with pytest.raises(ValueError, match="n must be .* got 4294967296"):
        world.step(n=2 ** 32)
    with pytest.raises(TypeError, match="n must be a non-negative integer.*2.5"):
        world.step(n=2.5)
    with pytest.raises(TypeError, match="dt must be a real number.*'fast'"):
        world.step("fast")
    with pytest.raises(TypeError, match="dt must be a real number"):
        world.step(1j)
    with pytest.raises(tumble.TumbleError, match="dt") as caught:
        world.step(-0.1)
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    world.step(n=0)
    assert world.stats()["steps"] == 0


def test_shapes_and_single_bodies_name_their_arguments(world, ball):
    with pytest.raises(TypeError, match="radius must be a real number"):
        world.sphere("big")
    with pytest.raises(ValueError, match=r"half_extents must be 3 numbers, got an array of "
                                         r"shape \(2,\)"):
        world.box((1, 1))
    with pytest.raises(TypeError, match="normal must hold real numbers"):
        world.plane((0, 1j, 0))
    with pytest.raises(TypeError, match="friction must be a real number"):
        world.box((1, 1, 1), friction="high")
    with pytest.raises(ValueError, match=r"points must be an \(n, 3\) array"):
        world.hull(np.zeros((4, 2)))
    with pytest.raises(TypeError, match="body must be a tumble.Body"):
        world.velocity(ball)
    with pytest.raises(TypeError, match="bodies must be tumble.Bodies or a tumble.Body"):
        world.transforms([1, 2, 3])
    body = world.add_body(ball, (0, 50, 0))
    with pytest.raises(ValueError, match="rotation must be 4 numbers"):
        world.set_pose(body, (0, 0, 0), (0, 0, 1))
    with pytest.raises(ValueError, match="impulse must be 3 numbers"):
        world.apply_impulse(body, (1, 2))
    with pytest.raises(TypeError, match="point must hold real numbers"):
        world.apply_impulse(body, (1, 2, 3), point=("a", "b", "c"))
    with pytest.raises(ValueError, match="gravity must be 3 numbers"):
        world.gravity = (0, -9.81)
    with pytest.raises(TypeError, match="what must be a tumble.Body, Bodies, Joint, Joints or "
                                          "Shape"):
        world.destroy(3)
    with pytest.raises(TypeError, match="path must be a path"):
        world.load_plugin(42)
    world.destroy(body)


def test_world_arguments():
    with pytest.raises(ValueError, match="broadphase must be one of 'default', 'grid', 'sap', "
                                         "'lbvh', 'isap', got 'octree'"):
        tumble.World(broadphase="octree")
    with pytest.raises(ValueError, match="broadphase must be one of"):
        tumble.World(broadphase=3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'gravty'.*gravity"):
        tumble.World(gravty=(0, 0, 0))
    with pytest.raises(ValueError, match="substeps must be a non-negative integer below 2"):
        tumble.World(substeps=-1)
    with pytest.raises(TypeError, match="contact_hertz must be a real number"):
        tumble.World(contact_hertz="60")
    with pytest.raises(TypeError, match="log must be a callable"):
        tumble.World(log="stderr")
    with pytest.raises(tumble.TumbleError, match="substeps") as caught:
        tumble.World(substeps=0)                                    # the library's range
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    with pytest.raises(tumble.TumbleError) as caught:
        tumble.World(device="no such device")
    assert caught.value.code == tumble.lib.TB_ERROR_NO_DEVICE


def test_plugin_arguments(world):
    with pytest.raises(tumble.TumbleError, match="missing.so"):
        world.load_plugin("/nonexistent/missing.so")


def test_use_after_close_is_a_clear_error():
    w = tumble.World()
    ball = w.sphere(0.5)
    bodies = w.add_bodies(ball, [[0, 0, 0]])
    w.close()
    assert w.closed
    w.close()                                                      # twice is fine
    for call in (lambda: w.step(), lambda: w.transforms(bodies), lambda: w.sphere(1),
                 lambda: w.add_bodies(ball, [[0, 0, 0]]), lambda: w.stats(),
                 lambda: w.contacts(), lambda: w.gravity, lambda: w.velocity(bodies[0]),
                 lambda: w.destroy(bodies), lambda: w.load_plugin("x.so")):
        with pytest.raises(tumble.ClosedError, match="tumble.World was closed"):
            call()
    with tumble.World() as w2:
        pass
    with pytest.raises(tumble.ClosedError):
        w2.step()
