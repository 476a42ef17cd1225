#!/usr/bin/env python3
"""Writes the fuzz target's seed corpus (tests/fuzz/corpus): call sequences in the byte
encoding of tests/fuzz/fuzz_api.c, each a small scene that works, so that the fuzzer
starts from inputs that reach deep into the step and mutates from there.
    python3 tests/fuzz/seeds.py        (rewrites tests/fuzz/corpus)"""
import os
import pathlib

LETTERS = "abcdefghijklmnopqrstuvwxyz0123456789_-A /"


def f(x):
    """An ordinary float of fz_float: a multiple of 1/16 in [-8, 8)."""
    return [0, int(round(x * 16)) + 128]


def vec(x, y, z):
    return f(x) + f(y) + f(z)


def name(text):
    return [len(text)] + [LETTERS.index(c) for c in text]


SHAPE_DEF = [0, 0, 0]   # the default density, friction and restitution


def plane():       # shape 0 of a seed: the ground, y = 0
    return [0, 2] + SHAPE_DEF + f(0) + f(0) + vec(0, 1, 0)


def box(h):
    return [0, 1] + SHAPE_DEF + f(0) + f(0) + vec(h, h, h)


def sphere(r):
    return [0, 0] + SHAPE_DEF + f(r) + f(0)


def capsule(r, h):
    return [0, 3] + SHAPE_DEF + f(r) + f(h)


def ground():      # a static body on shape 0
    return [6, 0, 0, 1] + vec(0, 0, 0) + [1]


def bodies(shape, positions):
    out = [6, len(positions) - 1]
    for p in positions:
        out += [shape, 0] + vec(*p)
    return out if len(positions) > 1 else out + [1]


def steps(n):
    return [11, 0, n % 3]


def read_all(kind):
    return [12, 4, 1, 2, 3, 4, 0, kind]


def hull(points):
    out = [1, len(points) % 256, len(points) // 256]
    for p in points:
        out += vec(*p)
    return out + SHAPE_DEF + [1]


def mesh(vertices, triangles):
    out = [2, len(vertices), len(triangles)]
    for v in vertices:
        out += vec(*v)
    for t in triangles:
        for i in t:
            out += [0, i]
    return out + SHAPE_DEF


def load_poison_plugin():
    desc = [0, 0] + name("poison") + [1] + [0, 16] + [1] + [0, 1] + [0]
    stage = name("poison") + [1] + [1, 0] + [0, 0] + [0]
    return [31] + desc + stage + [1] + [1]


def plugin_param(values):
    return [15, 0, len(values), 0] + values + [0, 0, 1]


CUBE = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]

SEEDS = {
    "boxes_on_ground": plane() + box(0.5) + ground()
    + bodies(1, [(0, 0.5 + i, 0) for i in range(4)]) + steps(2) + read_all(0) + read_all(2),
    "spheres_and_capsules": plane() + sphere(0.5) + capsule(0.25, 0.5) + ground()
    + bodies(1, [(i, 1, 0) for i in range(3)]) + bodies(2, [(0, 2, 1), (1, 2, 1)]) + steps(2)
    + read_all(1),
    "hull_pile": plane() + hull(CUBE + [(0, 0.75, 0)]) + ground()
    + bodies(1, [(0, 1, 0), (0.2, 2.2, 0), (-0.1, 3.4, 0.1)]) + steps(1) + steps(2),
    "mesh_ground": mesh([(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], [(0, 2, 1), (0, 3, 2)])
    + [6, 0, 0, 1] + vec(0, 0, 0) + [1] + box(0.5) + bodies(1, [(0, 1, 0), (1, 2, 0)]) + steps(2),
    "snapshot_restore": plane() + box(0.5) + ground() + bodies(1, [(0, 0.5, 0), (0, 1.5, 0)])
    + steps(1) + [14, 0, 0] + steps(1) + [14, 1, 0, 0, 0, 40, 7, 0],
    "poison_plugin": plane() + box(0.5) + ground() + bodies(1, [(0, 0.5, 0), (0, 1.5, 0)])
    + load_poison_plugin() + plugin_param([0, 0, 128, 63, 2, 0, 0, 0]) + steps(2) + read_all(0),
}


def main():
    corpus = pathlib.Path(__file__).resolve().parent / "corpus"
    corpus.mkdir(exist_ok=True)
    for old in corpus.iterdir():
        old.unlink()
    for seed, data in SEEDS.items():
        (corpus / seed).write_bytes(bytes(b % 256 for b in data))


if __name__ == "__main__":
    main()
