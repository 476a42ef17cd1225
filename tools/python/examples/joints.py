"""Joints: a chain of 10 links swinging from a hook, a wheel turned by a hinge's motor and
an arm that droops to its hinge's limit, then the motor and the limit changed, and what
the arm's hinge holds."""
import numpy as np
import tumble

with tumble.World() as world:
    hook, axle, shoulder = world.add_bodies(world.sphere(0.05),
                                            [(0, 5, 0), (3, 1, 0), (5, 2, 0)], static=True)
    # The chain: capsules 0.4 m long, hung 30 degrees from the vertical, joined end to end.
    down = np.array([np.sin(np.pi / 6), -np.cos(np.pi / 6), 0])
    ends = (0, 5, 0) + np.outer(np.arange(11) * 0.4, down)        # the links' ends
    links = world.add_bodies(world.capsule(0.05, 0.15), (ends[:-1] + ends[1:]) / 2,
                             rotations=(0, 0, np.sin(np.pi / 12), np.cos(np.pi / 12)))
    chain = world.create_joints("ball", hook, links[:1], at=ends[:1]) + \
        world.create_joints("ball", links[:-1], links[1:], at=ends[1:-1])
    # A wheel lying flat on a vertical axle, and an arm along x on a hinge about z.
    wheel = world.add_body(world.cylinder(0.3, 0.05), (3, 1, 0))
    motor = world.create_joint("hinge", axle, wheel, at=(3, 1, 0), axis=(0, 1, 0),
                               motor=(3.0, 50.0))              # 3 rad/s, at most 50 N m
    arm = world.add_body(world.box((0.5, 0.05, 0.05)), (5.5, 2, 0))
    elbow = world.create_joint("hinge", shoulder, arm, at=(5, 2, 0), axis=(0, 0, 1),
                               limit=(-0.5, 0.5))              # rad
    for step in range(1, 5):
        world.step(1 / 60, n=30)
        a, b = world.joint_anchors(chain)
        end = world.pose(links[-1])[0]
        print(f"t = {step / 2:.1f} s: the chain's end at x = {end[0]:5.2f}, "
              f"y = {end[1]:.2f} m; its joints apart by at most "
              f"{np.linalg.norm(a - b, axis=1).max() * 1000:.3f} mm")

    def droop():                                                # degrees below the x axis
        x, y, z, w = world.pose(arm)[1]
        return -2 * np.degrees(np.arctan2(z, w))

    print(f"the wheel turns at {world.velocity(wheel)[1][1]:.2f} rad/s; the arm droops "
          f"{droop():.1f} degrees")
    world.set_motor(motor, -1.5, 50.0)                          # back, at half the speed
    world.set_limit(elbow, -1.0, 0.5)                           # the arm may droop further
    world.step(1 / 60, n=60)
    print(f"then at {world.velocity(wheel)[1][1]:.2f} rad/s; the arm droops "
          f"{droop():.1f} degrees")
    world.step(1 / 60, n=60)                                    # the arm comes to rest
    (force,), (torque,), (broken,) = world.joint_forces(elbow)  # what held the arm
    mass, lever = world.mass(arm)[0], world.pose(arm)[0][0] - 5
    print(f"the elbow holds the arm up with {force[1]:.1f} N and {torque[2]:.1f} N m; the arm "
          f"weighs {mass * 9.81:.1f} N, {lever:.2f} m out (broken: {broken})")
