"""Joints from Python, on lavapipe: a ball-joint pendulum, what joints hold, motors and
limits, many joints in one call, joints that die with their bodies, and bad input refused.
Scenes are a few bodies and at most 120 steps."""
import re

import numpy as np
import pytest

import tumble

DT = 1 / 60
G = 9.81


def test_joint_ids_and_kinds_match_the_header():
    ffi, lib = tumble.ffi, tumble.lib
    assert tumble.JOINT_ID.itemsize == ffi.sizeof("tb_joint_id")
    assert tumble.JOINT_ID.names == ("index1", "world", "generation")
    for name, field in ffi.typeof("tb_joint_id").fields:
        assert tumble.JOINT_ID.fields[name][1] == field.offset
    assert tumble.JOINT_KINDS == {"ball": lib.TB_JOINT_BALL, "hinge": lib.TB_JOINT_HINGE,
                                  "fixed": lib.TB_JOINT_FIXED,
                                  "distance": lib.TB_JOINT_DISTANCE,
                                  "slider": lib.TB_JOINT_SLIDER,
                                  "cone_twist": lib.TB_JOINT_CONE_TWIST,
                                  "six_dof": lib.TB_JOINT_SIX_DOF}
    with open(tumble.header_path) as f:                  # "#define TB_MAX_JOINTS 2097152u"
        most = re.search(r"^#define TB_MAX_JOINTS (\d+)[uU]?\s*$", f.read(), re.M)
    assert most and lib.TB_MAX_JOINTS == int(most.group(1))


def test_a_ball_joint_pendulum_swings_on_its_rope(make_world):
    world = make_world()
    pivot = np.array([0.0, 3.0, 0.0])
    hook = world.add_body(world.sphere(0.05), pivot, static=True)
    bob = world.add_body(world.sphere(0.1), pivot + (1, 0, 0))      # the rope level, 1 m
    rope = world.create_joint("ball", hook, bob, at=pivot)
    assert isinstance(rope, tumble.Joint) and world.is_valid(rope)
    assert world.joint_bodies(rope) == (hook, bob)
    assert list(world.joint_ids()) == [rope]
    anchor_a, anchor_b = world.joint_anchors(rope)
    np.testing.assert_allclose(anchor_a, [pivot], atol=1e-6)
    np.testing.assert_allclose(anchor_b, [pivot], atol=1e-6)
    path = []
    for _ in range(120):                                            # 2 s
        world.step(DT)
        path.append(world.pose(bob)[0])
    path = np.array(path)
    off = np.abs(np.linalg.norm(path - pivot, axis=1) - 1)
    assert off.max() < 1e-3, "the bob left the rope's length by %.2f mm" % (off.max() * 1000)
    assert path[:, 0].min() < -0.5                                  # swung through, sideways
    assert path[:, 1].min() == pytest.approx(2.0, abs=0.01)         # under the pivot
    assert np.abs(path[:, 2]).max() < 1e-4                          # in its plane
    anchor_a, anchor_b = world.joint_anchors(rope)
    assert np.linalg.norm(anchor_a - anchor_b) < 1e-3


def test_joint_forces_of_weights_hanging_still(make_world):
    world = make_world()
    post = world.add_body(world.box((0.1, 1, 0.1)), (0, 1, 0), static=True)
    ball = world.sphere(0.1)
    weights = world.add_bodies(ball, (0.5, 1.5, 0), mass=2.0) + \
        world.add_bodies(ball, (-0.5, 1.5, 0), mass=3.0)
    held = world.create_joints("ball", post, weights, at=[(0.5, 2, 0), (-0.5, 2, 0)])
    loose = world.add_body(ball, (0, 1.5, 1), mass=2.0)
    weak = world.create_joint("ball", post, loose, at=(0, 2, 1), break_force=5.0)  # < 19.6 N
    assert isinstance(held, tumble.Joints) and len(held) == 2
    forces, torques, broken = world.joint_forces(held)
    assert forces.shape == torques.shape == (2, 3) and forces.dtype == np.float32
    assert not forces.any() and not broken.any()                    # before the first step
    world.step(DT, n=60)
    forces, torques, broken = world.joint_forces(held)
    np.testing.assert_allclose(forces[:, 1], [2 * G, 3 * G], rtol=0.01)   # up, on the weights
    np.testing.assert_allclose(forces[:, [0, 2]], 0, atol=0.01 * 2 * G)
    np.testing.assert_allclose(torques, 0, atol=0.01)
    assert broken.dtype == bool and broken.tolist() == [False, False]
    for body in weights:                                            # still
        assert np.linalg.norm(world.velocity(body)[0]) < 1e-3
    force, _, broken = world.joint_forces(weak)
    assert force.shape == (1, 3) and broken.tolist() == [True]
    assert world.pose(loose)[0][1] < 1.5 - 0.5 * G * 0.9 ** 2         # it let go: falling
    world.destroy(weak)                                             # broken, still live
    assert world.is_valid(held).tolist() == [True, True] and not world.is_valid(weak)


def test_a_hinge_motor_and_limit_set_between_steps(make_world):
    world = make_world()
    axle, shoulder = world.add_bodies(world.sphere(0.05), [(0, 1, 0), (3, 2, 0)], static=True)
    wheel = world.add_body(world.cylinder(0.3, 0.05), (0, 1, 0))    # flat on a vertical axle
    motor = world.create_joint("hinge", axle, wheel, at=(0, 1, 0), axis=(0, 1, 0),
                               motor=(3.0, 50.0))
    arm = world.add_body(world.box((0.5, 0.05, 0.05)), (3.5, 2, 0))  # along x
    elbow = world.create_joint("hinge", shoulder, arm, at=(3, 2, 0), axis=(0, 0, 1),
                               limit=(-0.5, 0.5))

    def droop():                                                    # rad below the x axis
        x, y, z, w = world.pose(arm)[1]
        return -2 * np.arctan2(z, w)

    world.step(DT, n=30)
    assert world.velocity(wheel)[1][1] == pytest.approx(3.0, rel=0.01)
    assert droop() == pytest.approx(0.5, abs=0.01)
    world.set_motor(motor, -1.5, 50.0)
    world.set_limit(elbow, -1.0, 0.5)
    world.step(DT, n=60)
    assert world.velocity(wheel)[1][1] == pytest.approx(-1.5, rel=0.01)
    assert droop() == pytest.approx(1.0, abs=0.01)
    world.set_motor(motor, enable=False)
    world.set_limit(elbow, enable=False)
    world.step(DT, n=30)
    assert droop() > 1.2                                            # free to hang down
    assert world.velocity(wheel)[1][1] < -1.0                       # turning on, unpushed


def test_create_joints_with_anchors_and_frames_in_the_bodies(make_world):
    world = make_world()
    hook = world.add_bodies(world.sphere(0.05), (0, 3, 0), static=True)
    links = world.add_bodies(world.sphere(0.1), [(0, 2.5, 0), (0, 2, 0), (0, 1.5, 0)])
    chain = world.create_joints("ball", hook + links[:-1], links, anchors_a=(0, -0.25, 0),
                                anchors_b=[(0, 0.25, 0)] * 3, frames_a=(0, 0, 0, 1))
    assert len(chain) == 3 and len(set(chain)) == 3
    anchors_a, anchors_b = world.joint_anchors(chain)
    np.testing.assert_allclose(anchors_a, [(0, 2.75, 0), (0, 2.25, 0), (0, 1.75, 0)],
                               atol=1e-6)
    np.testing.assert_allclose(anchors_b, anchors_a, atol=1e-6)
    bodies_a, bodies_b = world.joint_bodies(chain)
    assert (bodies_a.ids == (hook + links[:-1]).ids).all() and (bodies_b.ids == links.ids).all()
    assert world.joint_ids().index(chain).tolist() == [0, 1, 2]
    assert chain.index(chain[2]) == 2 and list(chain[1:]) == [chain[1], chain[2]]
    world.step(DT, n=30)                                            # it hangs as it was
    np.testing.assert_allclose(world.transforms(links)[0], [(0, 2.5, 0), (0, 2, 0), (0, 1.5, 0)],
                               atol=1e-3)
    forces = world.joint_forces(chain)[0]
    mass = world.mass(links[0])[0]
    np.testing.assert_allclose(forces[:, 1], np.array([3, 2, 1]) * mass * G, rtol=0.01)
    with pytest.raises(tumble.TumbleError, match="joints"):         # not saved yet
        world.snapshot()


def test_destroying_a_body_destroys_its_joints(make_world):
    world = make_world()
    hook = world.add_bodies(world.sphere(0.05), (0, 3, 0), static=True)
    links = world.add_bodies(world.sphere(0.1), [(0, 2.5, 0), (0, 2, 0), (0, 1.5, 0)])
    chain = world.create_joints("ball", hook + links[:-1], links, at=[(0, 2.75, 0),
                                                                      (0, 2.25, 0),
                                                                      (0, 1.75, 0)])
    world.step(DT, n=10)
    world.destroy(links[1])                                         # in the chain's middle
    assert world.is_valid(chain).tolist() == [True, False, False]
    assert list(world.joint_ids()) == [chain[0]]
    with pytest.raises(tumble.TumbleError) as caught:
        world.joint_bodies(chain[1])
    assert caught.value.code == tumble.lib.TB_ERROR_STALE_ID
    with pytest.raises(tumble.TumbleError, match=r"what\[1\].*nothing was destroyed"):
        world.destroy(chain)
    with pytest.raises(ValueError, match="names a joint twice"):
        world.destroy(chain[[0, 0]])
    assert world.is_valid(chain[0])
    world.step(DT, n=10)                                            # the rest swing on
    world.destroy(links[[0, 2]])
    assert not world.is_valid(chain).any() and len(world.joint_ids()) == 0
    world.step(DT)


def test_bad_joint_input_raises_and_makes_nothing(make_world):
    world = make_world()
    lib = tumble.lib
    post = world.add_body(world.box((0.1, 1, 0.1)), (0, 1, 0), static=True)
    a, b = pair = world.add_bodies(world.sphere(0.1), [(1, 2, 0), (2, 2, 0)])
    # What the library refuses: its sentence, and no joint made.
    with pytest.raises(tumble.TumbleError, match="two different bodies") as caught:
        world.create_joint("ball", a, a, at=(1, 2, 0))
    assert caught.value.code == lib.TB_ERROR_INVALID_ARGUMENT
    with pytest.raises(tumble.TumbleError, match="must be finite"):
        world.create_joint("ball", a, b, anchor_a=(np.nan, 0, 0))
    with pytest.raises(tumble.TumbleError, match="must be finite"):
        world.create_joint("ball", a, b, at=(1.5, np.nan, 0))
    with pytest.raises(tumble.TumbleError, match="lower > upper"):
        world.create_joint("hinge", post, a, at=(1, 2, 0), axis=(0, 0, 1), limit=(0.5, -0.5))
    with pytest.raises(tumble.TumbleError, match="joint def 1: .*must be finite"):
        world.create_joints("ball", post, pair, anchors_a=[(0, 1, 0), (np.inf, 1, 0)])
    with pytest.raises(tumble.TumbleError, match=r"joint 1 \(at\[1\], axis\[1\]\): point and "
                                                 "axis must be finite.*no joint was made"):
        world.create_joints("ball", post, pair, at=[(1, 2, 0), (np.nan, 2, 0)])
    with pytest.raises(tumble.TumbleError, match="axis not zero"):
        world.create_joint("hinge", post, a, at=(1, 2, 0), axis=(0, 0, 0))
    with pytest.raises(tumble.TumbleError,
                       match="only distance joints, hinges and sliders take a spring"):
        world.create_joint("ball", post, a, at=(1, 2, 0), spring=(2.0, 0.5))
    assert len(world.joint_ids()) == 0
    # What the binding refuses before any call.
    with pytest.raises(ValueError, match="kind must be one of 'ball', 'hinge', 'fixed', "
                                         "'distance', 'slider', 'cone_twist', 'six_dof', got 'weld'"):
        world.create_joint("weld", a, b, at=(1.5, 2, 0))
    with pytest.raises(TypeError, match="body_b must be a tumble.Body"):
        world.create_joint("ball", a, "b", at=(1.5, 2, 0))
    with pytest.raises(TypeError, match="bodies_a must be a tumble.Body or Bodies"):
        world.create_joints("ball", [a], pair, at=(1.5, 2, 0))
    with pytest.raises(ValueError, match="give at .* or anchor_a, not both"):
        world.create_joint("ball", a, b, at=(1.5, 2, 0), anchor_a=(0, 0, 0))
    with pytest.raises(ValueError, match="axis goes with at"):
        world.create_joint("hinge", a, b, axis=(0, 0, 1))
    with pytest.raises(ValueError, match="bodies_a has 2 bodies but bodies_b has 1"):
        world.create_joints("ball", pair, pair[:1], at=(1.5, 2, 0))
    with pytest.raises(ValueError, match="at has 3 rows but there are 2 joints"):
        world.create_joints("ball", post, pair, at=np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"frames_b must be an \(n, 4\) array"):
        world.create_joints("ball", post, pair, frames_b=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="limit must be 2 numbers"):
        world.create_joint("hinge", post, a, at=(1, 2, 0), limit=(0, 1, 2))
    with pytest.raises(TypeError, match="collide_connected must be True or False"):
        world.create_joint("ball", post, a, at=(1, 2, 0), collide_connected="yes")
    with pytest.raises(TypeError, match="length must be a real number"):
        world.create_joint("distance", post, a, length="1 m")
    assert len(world.joint_ids()) == 0
    # set_motor, set_limit: accepted where they fit, refused where not.
    hinge = world.create_joint("hinge", post, a, at=(1, 2, 0), axis=(0, 0, 1))
    world.set_limit(hinge, -0.5, 0.5)
    world.set_motor(hinge, 1.0, 10.0)
    world.set_motor(hinge, enable=False)
    world.set_limit(hinge, enable=False)
    with pytest.raises(tumble.TumbleError, match="lower > upper"):
        world.set_limit(hinge, 0.5, -0.5)
    with pytest.raises(tumble.TumbleError, match="max_motor_force must be >= 0"):
        world.set_motor(hinge, 1.0, -1.0)
    with pytest.raises(tumble.TumbleError, match="within \\[-pi, pi\\]"):
        world.set_limit(hinge, -4.0, 0.0)
    with pytest.raises(TypeError, match="give speed and max_force"):
        world.set_motor(hinge, 1.0)
    with pytest.raises(TypeError, match="give lower and upper"):
        world.set_limit(hinge, upper=1.0)
    with pytest.raises(TypeError, match="enable must be True or False"):
        world.set_limit(hinge, 0, 1, enable=1)
    with pytest.raises(TypeError, match="joint must be a tumble.Joint"):
        world.set_motor(a, 1.0, 1.0)
    with pytest.raises(TypeError, match="joints must be tumble.Joints or a tumble.Joint"):
        world.joint_forces([hinge])
    ball = world.create_joint("ball", a, b, at=(1.5, 2, 0))
    with pytest.raises(tumble.TumbleError, match="only hinges and sliders take a motor"):
        world.set_motor(ball, 1.0, 1.0)
    with pytest.raises(tumble.TumbleError, match="only hinges, sliders, distance and cone-twist"):
        world.set_limit(ball, 0.0, 1.0)
    # A stale id, after destroy.
    world.destroy(ball)
    assert not world.is_valid(ball)
    for call in (lambda: world.destroy(ball), lambda: world.set_motor(ball, 0.0, 0.0),
                 lambda: world.set_limit(ball, enable=False), lambda: world.joint_forces(ball),
                 lambda: world.joint_anchors(ball), lambda: world.joint_bodies(ball),
                 lambda: world.destroy(tumble.Joints(np.array([(ball.index1, ball.world,
                                                                ball.generation)],
                                                              dtype=tumble.JOINT_ID)))):
        with pytest.raises(tumble.TumbleError, match="stale") as caught:
            call()
        assert caught.value.code == lib.TB_ERROR_STALE_ID
    assert list(world.joint_ids()) == [hinge]
    world.step(DT)


def test_cone_twist_six_dof_and_springs(make_world):
    world = make_world()
    post = world.add_body(world.sphere(0.02), (0, 2, 0), static=True)
    rod = world.box((0.5, 0.05, 0.05))
    # A level rod on a cone of 0.5 rad about its length falls to the cone and hangs there.
    coned = world.add_body(rod, (0.5, 2, 0))
    world.create_joint("cone_twist", post, coned, at=(0, 2, 0), axis=(1, 0, 0), cone_angle=0.5,
                       limit=(-0.2, 0.2))
    # A 6-dof joint locked but for the turn about z, limited to +-0.3 rad: a limited hinge.
    other = world.add_body(world.sphere(0.02), (0, 4, 0), static=True)
    hinged = world.add_body(rod, (0.5, 4, 0))
    world.create_joint("six_dof", other, hinged, at=(0, 4, 0), axis=(1, 0, 0),
                       axes=["locked"] * 5 + [(-0.3, 0.3)])
    # A 2 kg box on a vertical slider with a damped 2 Hz spring to 0.1 m below its anchor.
    top = world.add_body(world.sphere(0.02), (3, 3, 0), static=True)
    box = world.add_body(world.box((0.2, 0.2, 0.2)), (3, 3, 0), mass=2.0)
    slider = world.create_joint("slider", top, box, at=(3, 3, 0), axis=(0, -1, 0),
                                spring=(2.0, 1.0, 0.1))
    for _ in range(60):
        world.step(DT)
    x_of = lambda body: world.pose(body)[1]       # noqa: E731
    along = tumble_rotate(x_of(coned), (1, 0, 0))
    assert np.arccos(min(1.0, along[0])) == pytest.approx(0.5, abs=np.radians(1))
    q = x_of(hinged)
    assert 2 * np.arctan2(q[2], q[3]) == pytest.approx(-0.3, abs=np.radians(1))
    sag = 0.1 + G / (2 * np.pi * 2) ** 2          # the target, and Hooke's stretch
    assert 3 - world.pose(box)[0][1] == pytest.approx(sag, rel=0.02)
    # A 2 kg box hung from its top on a soft ball joint (2 Hz, critically damped) sags as a
    # spring of that frequency would.
    hook = world.add_body(world.sphere(0.02), (6, 3, 0), static=True)
    hung = world.add_body(world.box((0.1, 0.1, 0.1)), (6, 2.9, 0), mass=2.0)
    world.create_joint("ball", hook, hung, at=(6, 3, 0), soft=(2.0, 1.0))
    for _ in range(60):
        world.step(DT)
    assert 2.9 - world.pose(hung)[0][1] == pytest.approx(G / (2 * np.pi * 2) ** 2, rel=0.02)
    world.set_spring(slider, 2.0, 1.0, target=0.0)
    world.set_spring(slider, enable=False)
    with pytest.raises(tumble.TumbleError, match="spring_hertz > 0"):
        world.set_spring(slider, 0.0, 1.0)
    with pytest.raises(TypeError, match="give hertz and damping_ratio"):
        world.set_spring(slider, 2.0)
    with pytest.raises(ValueError, match="axes must be six entries"):
        world.create_joint("six_dof", post, box, at=(0, 2, 0), axes=["free"] * 5)
    with pytest.raises(ValueError, match=r"axes\[2\] must be"):
        world.create_joint("six_dof", post, box, at=(0, 2, 0), axes=["free", "free", "loose",
                                                                     "free", "free", "free"])
    with pytest.raises(tumble.TumbleError, match="axis 1's limits"):
        world.create_joint("six_dof", post, box, at=(0, 2, 0),
                           axes=["free", (1, -1), "free", "free", "free", "free"])
    with pytest.raises(tumble.TumbleError, match="constraint_hertz and constraint_damping"):
        world.create_joint("ball", post, box, at=(0, 2, 0), soft=(-1.0, 1.0))
    with pytest.raises(tumble.TumbleError, match="cone_angle must be within"):
        world.create_joint("cone_twist", post, box, at=(0, 2, 0), cone_angle=-1)


def tumble_rotate(q, v):
    """v turned by the x y z w quaternion q."""
    u, w = np.asarray(q[:3], dtype=float), float(q[3])
    v = np.asarray(v, dtype=float)
    return v + 2 * w * np.cross(u, v) + 2 * np.cross(u, np.cross(u, v))


def test_a_soft_step_world_refuses_joints(make_world):
    world = make_world()
    world.set_solver("soft")
    a, b = world.add_bodies(world.sphere(0.1), [(1, 2, 0), (2, 2, 0)])
    with pytest.raises(tumble.TumbleError, match="block solver"):
        world.create_joint("ball", a, b, at=(1.5, 2, 0))
    assert len(world.joint_ids()) == 0 and len(world.joint_forces(tumble.Joints(
        np.zeros(0, dtype=tumble.JOINT_ID)))[0]) == 0


def test_use_after_close_is_a_clear_error():
    world = tumble.World()
    a, b = world.add_bodies(world.sphere(0.1), [(1, 2, 0), (2, 2, 0)])
    joint = world.create_joint("ball", a, b, at=(1.5, 2, 0))
    world.close()
    for call in (lambda: world.create_joint("ball", a, b, at=(1.5, 2, 0)),
                 lambda: world.joint_forces(joint), lambda: world.joint_ids(),
                 lambda: world.set_motor(joint, 0.0, 0.0), lambda: world.destroy(joint)):
        with pytest.raises(tumble.ClosedError):
            call()
