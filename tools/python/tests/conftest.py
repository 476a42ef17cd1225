"""Shared by the suite: the package under test, and worlds that must end without a
validation message.

`make check-python` installs the package into a virtual environment and runs the suite
there; run straight from a checkout (python3 -m pytest tools/python), the source package
is used instead."""
import importlib.util
import os
import sys

import pytest

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
ROOT = os.path.normpath(os.path.join(PYTHON_DIR, "..", ".."))
if importlib.util.find_spec("tumble") is None:
    sys.path.insert(0, PYTHON_DIR)

import tumble  # noqa: E402

BUILD = os.environ.get("TUMBLE_BUILD_DIR") or os.path.join(ROOT, "build")


@pytest.fixture
def make_world():
    worlds = []

    def make(**kwargs):
        w = tumble.World(**kwargs)
        worlds.append(w)
        return w

    yield make
    for w in worlds:
        if not w.closed:
            assert w.stats()["validation_messages"] == 0
            w.close()
