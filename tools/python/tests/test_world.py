"""The Python binding on lavapipe (make test sets TUMBLE_DEVICE and TUMBLE_VALIDATION):
a pile scene driven from Python, a million transforms read into numpy in one call, errors
as exceptions. Every world must end without a validation message."""
import os
import shutil

import numpy as np
import pytest

import tumble
from conftest import BUILD, ROOT


def container(world, half_width, height):
    """Floor (top at y = 0) and four walls around [-hw, hw] x [0, height] x [-hw, hw]."""
    hw, hh, t = half_width, height / 2, 0.5
    for centre, half in [((0, -t, 0), (hw + 2 * t, t, hw + 2 * t)),
                         ((hw + t, hh, 0), (t, hh, hw + 2 * t)), ((-hw - t, hh, 0), (t, hh, hw + 2 * t)),
                         ((0, hh, hw + t), (hw, hh, t)), ((0, hh, -hw - t), (hw, hh, t))]:
        world.add_bodies(world.box(half), np.array([centre]), static=True)


def test_pile_settles_in_its_container(make_world):
    world = make_world(broadphase="lbvh")
    side, layers = 8, 6                       # 384 bodies, half spheres, half boxes
    grid = np.stack(np.meshgrid(np.arange(side), np.arange(layers), np.arange(side),
                                indexing="ij"), axis=-1).reshape(-1, 3).astype(np.float32)
    rng = np.random.default_rng(1)
    start = (grid - [side / 2 - 0.5, -0.5, side / 2 - 0.5]) * 1.1 + rng.uniform(-0.03, 0.03, grid.shape)
    start[:, 1] += 0.5
    half_width = side * 1.1 / 2
    container(world, half_width, layers * 1.1 + 3)
    balls = world.add_bodies(world.sphere(0.5), start[0::2])
    boxes = world.add_bodies(world.box((0.5, 0.5, 0.5)), start[1::2])
    world.step(1 / 60, n=240)
    for bodies in (balls, boxes):
        p, q = world.transforms(bodies)
        assert np.all(np.isfinite(p)) and np.all(np.isfinite(q))
        assert np.all(np.abs(p[:, [0, 2]]) < half_width + 0.05)
        assert np.all(p[:, 1] > 0.3)           # nothing sank through the floor
        assert np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-4)
    before, _ = world.transforms(boxes)
    world.step(1 / 60, n=10)
    after, _ = world.transforms(boxes)
    moved = np.linalg.norm(after - before, axis=1)
    assert np.mean(moved < 0.01) > 0.9         # settled: most boxes keep still
    stats = world.stats()
    assert stats["body_count"] == 384 + 5 and stats["contact_count"] > 0
    assert stats["broadphase"] == "lbvh"


def test_block_solver_holds_a_column(make_world):
    """The block solver, the default, holds a column of 10 unit boxes (hard contacts: the
    top box sinks well under the soft step's 6.8 mm); the choice is refused once the world
    has stepped, and an unknown solver by name."""
    world = make_world()
    assert world.solver == "block"
    world.add_bodies(world.box((20, 0.5, 20)), np.array([[0, -0.5, 0]]), static=True)
    column = world.add_bodies(world.box((0.5, 0.5, 0.5)),
                              np.array([[0, 0.5 + i, 0] for i in range(10)]))
    with pytest.raises(ValueError, match="solver must be one of 'soft', 'block', got 'stiff'"):
        world.set_solver("stiff")
    world.set_solver("soft")
    assert world.solver == "soft"
    world.set_solver("block", iterations=30)
    assert world.solver == "block"
    world.step(1 / 60, n=300)
    p, _ = world.transforms(column)
    assert abs(p[-1, 1] - 9.5) < 0.003
    with pytest.raises(tumble.TumbleError, match="before the world's first step"):
        world.set_solver("soft")
    assert world.solver == "block"


def test_a_million_transforms_in_one_call(make_world):
    n = 1_000_000
    world = make_world(gravity=(0, 0, 0), initial_body_capacity=n + 16)
    side = 100
    index = np.arange(n)
    grid = np.stack([index % side, index // side % side, index // (side * side)], axis=1)
    start = grid.astype(np.float32) * 2.0
    bodies = world.add_bodies(world.sphere(0.25), start, velocities=np.tile([1.0, 0, 0], (n, 1)))
    world.step(0.5)
    positions, rotations = world.transforms(bodies)
    assert positions.shape == (n, 3) and rotations.shape == (n, 4)
    assert positions.dtype == np.float32
    np.testing.assert_allclose(positions, start + [0.5, 0, 0], atol=1e-4)
    np.testing.assert_allclose(rotations, np.tile([0, 0, 0, 1], (n, 1)), atol=1e-6)


def test_errors_are_exceptions(make_world):
    world = make_world()
    with pytest.raises(tumble.TumbleError, match="radius") as caught:
        world.sphere(-1.0)
    assert caught.value.code == tumble.lib.TB_ERROR_INVALID_ARGUMENT
    ball = world.sphere(0.5)
    with pytest.raises(tumble.TumbleError, match="finite"):
        world.add_bodies(ball, np.array([[0, np.nan, 0]]))
    assert world.stats()["body_count"] == 0    # all or none: nothing was added
    with pytest.raises(ValueError, match="broadphase must be one of .*'lbvh'.*got 'octree'"):
        tumble.World(broadphase="octree")


def plugin_path(name):
    return os.path.join(BUILD, "plugins", name)


def test_blast_plugin_from_python(make_world):
    """The blast plugin (tools/plugins) pushes a ring of balls outwards at the rate its
    parameters, given as a numpy array, say: 12 m/s^2 at the centre, 0 at radius 4."""
    world = make_world(gravity=(0, 0, 0))
    angles = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    ring = np.stack([2 * np.cos(angles), np.zeros(8), 2 * np.sin(angles)], axis=1)
    balls = world.add_bodies(world.sphere(0.25), ring)
    blast = world.load_plugin(plugin_path("tb_blast.so"))
    blast.set_params(np.array([[0, 0, 0, 12], [4, 0, 0, 0]], dtype=np.float32))
    world.step(1 / 60)
    for k in range(8):
        v, _ = world.velocity(balls[k])
        assert np.allclose(v, ring[k] / 2 * 6 / 60, atol=1e-5)
    with pytest.raises(tumble.TumbleError, match="radius"):
        blast.set_params(np.array([-1], dtype=np.float32), offset=16)
    blast.unload()
    with pytest.raises(tumble.TumbleError):
        blast.unload()


def test_shader_hot_reload(make_world, tmp_path):
    """A copy of glsl/ runs the step; scaling gravity in its substep shader doubles the fall
    of a ball from the next step on, without a new world."""
    source = os.path.join(ROOT, "glsl")
    shaders = tmp_path / "glsl"
    shutil.copytree(source, shaders)
    world = make_world()
    world.set_shader_dir(shaders)
    ball = world.add_bodies(world.sphere(0.5), np.array([[0.0, 100.0, 0.0]]))
    world.step(1 / 60)
    fall = world.velocity(ball[0])[0][1]
    assert np.isclose(fall, -9.81 / 60, rtol=1e-3)
    substep = shaders / "integrate" / "substep.comp"
    text = substep.read_text()
    term = "params.gravity.xyz * (s.angular.w * h)"
    assert term in text
    substep.write_text(text.replace(term, "params.gravity.xyz * (2.0 * s.angular.w * h)"))
    world.step(1 / 60)
    assert np.isclose(world.velocity(ball[0])[0][1], fall + 2 * fall, rtol=1e-3)
    with pytest.raises(tumble.TumbleError, match="not a readable directory"):
        world.set_shader_dir(tmp_path / "missing")
    world.set_shader_dir(None)


def test_contact_reuse_settings(make_world):
    """The contact reuse bounds read back as set, 0 turns reuse off, and bad bounds are
    refused with the world unchanged."""
    world = make_world()
    distance, angle = world.contact_reuse
    assert distance == pytest.approx(0.001) and angle == pytest.approx(np.pi / 90)
    world.contact_reuse = (0.002, 0.01)
    assert world.contact_reuse == pytest.approx((0.002, 0.01))
    for bad in [(-1, 0.01), (0.001, float("nan")), (0.001, 1.0)]:
        with pytest.raises(tumble.TumbleError):
            world.contact_reuse = bad
    with pytest.raises(ValueError):
        world.contact_reuse = (1, 2, 3)
    assert world.contact_reuse == pytest.approx((0.002, 0.01))
    world.contact_reuse = (0, 0)
    assert world.contact_reuse == (0.0, 0.0)
