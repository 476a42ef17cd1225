"""A pile settling: 27 boxes dropped, turned at random, onto the ground; prints heights."""
import numpy as np
import tumble

with tumble.World() as world:
    world.add_body(world.plane((0, 1, 0)), static=True)            # the ground: y = 0
    rng = np.random.default_rng(1)
    grid = np.stack(np.meshgrid(range(3), range(3), range(3), indexing="ij"), -1)
    start = grid.reshape(-1, 3) * 1.3 + (-1.3, 2, -1.3)           # 3 layers of 9
    turns = rng.normal(size=(27, 4))
    boxes = world.add_bodies(world.box((0.5, 0.5, 0.5)), start,
                             rotations=turns / np.linalg.norm(turns, axis=1, keepdims=True))
    for step in range(1, 9):
        world.step(1 / 60, n=30)
        y = world.transforms(boxes)[0][:, 1]
        print(f"t = {step / 2:.1f} s: heights {y.min():.2f} to {y.max():.2f} m, "
              f"mean {y.mean():.2f} m")
    contacts = world.contacts()
    ground = (boxes.index(contacts["a"]) < 0) | (boxes.index(contacts["b"]) < 0)
    on_ground = contacts[ground]                                   # not box on box
    print(f"the ground carries {on_ground['normal_impulse'].sum() * 60:.0f} N "
          f"at {len(on_ground)} points; the boxes weigh {27 * 1000 * 9.81:.0f} N")
