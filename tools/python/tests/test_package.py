"""The package as users get it: how it finds the library (TUMBLE_LIBRARY, pkg-config, the
source tree), the errors when it cannot, and the README's examples, run as scripts."""
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import tumble
from tumble import _library
from conftest import PYTHON_DIR

EXAMPLE = os.path.join(PYTHON_DIR, "examples", "pile.py")
JOINTS_EXAMPLE = os.path.join(PYTHON_DIR, "examples", "joints.py")
README = os.path.join(PYTHON_DIR, "README.md")


def run_python(code_or_script, env_changes, timeout=120):
    """Run Python on the tumble package under test, with the environment changed."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.dirname(os.path.dirname(os.path.abspath(tumble.__file__)))
    for name, value in env_changes.items():
        if value is None:
            env.pop(name, None)
        else:
            env[name] = value
    args = [sys.executable, code_or_script] if code_or_script.endswith(".py") else \
        [sys.executable, "-c", code_or_script]
    return subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True, timeout=timeout)


def test_a_wrong_tumble_library_is_an_error_naming_the_path(tmp_path):
    done = run_python("import tumble", {"TUMBLE_LIBRARY": "/nonexistent/libtumble.so"})
    assert done.returncode != 0
    assert "LibraryNotFound: TUMBLE_LIBRARY is '/nonexistent/libtumble.so', but no file " \
           "is there" in done.stderr
    not_a_library = tmp_path / "libtumble.so"
    not_a_library.write_text("not a shared object")
    done = run_python("import tumble", {"TUMBLE_LIBRARY": str(not_a_library)})
    assert done.returncode != 0
    assert "cannot open %s (found through TUMBLE_LIBRARY)" % not_a_library in done.stderr
    done = run_python("import tumble", {"TUMBLE_HEADER": str(tmp_path / "none.h")})
    assert "TUMBLE_HEADER is '%s', but no file is there" % (tmp_path / "none.h") in done.stderr


def test_a_header_of_another_major_version_is_refused(tmp_path):
    with open(tumble.header_path) as f:
        text = f.read()
    newer = re.sub(r"#define TB_VERSION_MAJOR \d+", "#define TB_VERSION_MAJOR 99", text)
    (tmp_path / "tumble.h").write_text(newer)
    done = run_python("import tumble", {"TUMBLE_HEADER": str(tmp_path / "tumble.h")})
    assert done.returncode != 0
    assert "too old or of another major version for the header" in done.stderr


def fake_install(prefix):
    """An installed Tumble under `prefix` as make install lays it out, with its tumble.pc."""
    (prefix / "lib" / "pkgconfig").mkdir(parents=True)
    (prefix / "include").mkdir()
    shutil.copyfile(os.path.realpath(tumble.library_path), prefix / "lib" / "libtumble.so")
    shutil.copyfile(tumble.header_path, prefix / "include" / "tumble.h")
    (prefix / "lib" / "pkgconfig" / "tumble.pc").write_text(
        "prefix=%s\nlibdir=${prefix}/lib\nincludedir=${prefix}/include\n\nName: tumble\n"
        "Description: test\nVersion: %s\nLibs: -L${libdir} -ltumble\nCflags: -I${includedir}\n"
        % (prefix, tumble.__version__))


@pytest.mark.skipif(shutil.which("pkg-config") is None, reason="pkg-config is not installed")
def test_the_order_tumble_library_then_pkg_config_then_the_rest(tmp_path):
    fake_install(tmp_path / "prefix")
    empty = tmp_path / "empty"
    empty.mkdir()
    pc = {"PKG_CONFIG_PATH": str(tmp_path / "prefix" / "lib" / "pkgconfig"),
          "PKG_CONFIG_LIBDIR": str(empty)}
    library, header, source = _library.locate(pc)
    assert (library, header, source) == (str(tmp_path / "prefix" / "lib" / "libtumble.so"),
                                         str(tmp_path / "prefix" / "include" / "tumble.h"),
                                         "pkg-config")
    chosen = str(tmp_path / "prefix" / "lib" / "libtumble.so")
    other = dict(pc, TUMBLE_LIBRARY=os.path.realpath(tumble.library_path))
    assert _library.locate(other)[0] == os.path.realpath(tumble.library_path)
    assert _library.locate(other)[2] == "TUMBLE_LIBRARY"
    # Without both, the bundled library, the source tree's or the system loader's.
    library, header, source = _library.locate({"PKG_CONFIG_LIBDIR": str(empty)})
    if os.path.isdir(_library.BUNDLED_LIBRARY_DIR):
        assert source == "bundled" and library.startswith(_library.BUNDLED_LIBRARY_DIR)
    elif _library.CHECKOUT:
        assert source == "checkout" and library == os.path.join(_library.CHECKOUT, "build",
                                                                 "libtumble.so")
    else:
        assert source == "system" and library == "libtumble.so.%d" % tumble.HEADER_VERSION[0]
    # And imported that way, it simulates.
    done = run_python("import tumble; w = tumble.World(); w.step(); "
                      "print(tumble.library_source, tumble.library_path, tumble.header_path)",
                      dict(pc, TUMBLE_LIBRARY=None, TUMBLE_HEADER=None))
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["pkg-config", chosen,
                                   str(tmp_path / "prefix" / "include" / "tumble.h")]


def test_the_readme_example_is_examples_pile_py():
    with open(README) as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    with open(EXAMPLE) as f:
        lines = f.read().splitlines(keepends=True)
    assert lines[0].startswith('"""')                    # its docstring, then the README's
    assert blocks[0] == "".join(lines[1:])


@pytest.mark.parametrize("heading", ["## Triangle meshes", "## Capsules, cylinders and cones",
                                     "## Compounds", "## Joints"])
def test_the_readme_shape_examples_print_what_they_show(heading):
    with open(README) as f:
        text = f.read()
    section = text[text.index(heading):]
    code, shown = re.findall(r"```(?:python)?\n(.*?)```", section, re.S)[:2]
    done = run_python(code, {})
    assert done.returncode == 0, done.stderr
    assert done.stdout == shown


def test_the_example_pile_settles():
    done = run_python(EXAMPLE, {})
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    heights = [tuple(float(x) for x in re.match(
        r"t = \d\.\d s: heights (\S+) to (\S+) m, mean (\S+) m$", line).groups())
        for line in lines if line.startswith("t = ")]
    assert len(heights) == 8
    lowest, highest, mean = zip(*heights)
    assert min(lowest) > 0.45                            # none sinks into the ground
    assert highest[0] > 3.2 and 2.3 < highest[-1] < 2.7  # a pile three boxes high at most
    assert all(a >= b - 0.01 for a, b in zip(mean, mean[1:]))   # falling, then at rest
    assert abs(mean[-1] - mean[-2]) < 0.1
    carried, weight = (float(x) for x in re.search(
        r"the ground carries (\d+) N at \d+ points; the boxes weigh (\d+) N", lines[-1]).groups())
    assert carried == pytest.approx(weight, rel=0.05)


def test_the_example_joints_swing_turn_and_droop():
    done = run_python(JOINTS_EXAMPLE, {})
    assert done.returncode == 0, done.stderr
    text = done.stdout
    gaps = [float(g) for g in re.findall(r"its joints apart by at most (\S+) mm", text)]
    assert len(gaps) == 4 and max(gaps) < 1.0                # the chain holds together
    ends = [float(x) for x in re.findall(r"the chain's end at x = +(\S+),", text)]
    assert max(ends) > 1 and min(ends) < -1                  # and swings
    speeds = [float(s) for s in re.findall(r"at (\S+) rad/s", text)]
    droops = [float(d) for d in re.findall(r"droops (\S+) degrees", text)]
    assert speeds == pytest.approx([3.0, -1.5], abs=0.02)    # the motor, then set_motor
    assert droops == pytest.approx([np.degrees(0.5), np.degrees(1.0)], abs=0.5)  # the limits
    force, torque, weight, lever = (float(x) for x in re.search(
        r"holds the arm up with (\S+) N and (\S+) N m; the arm weighs (\S+) N, (\S+) m out "
        r"\(broken: False\)", text).groups())
    assert force == pytest.approx(weight, rel=0.02)
    assert torque == pytest.approx(weight * lever, rel=0.02)
