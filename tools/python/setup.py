"""Building the tumble package: the version and the API declarations come from tumble.h.

The header is copied into the package (tumble/tumble.h) at build time: TUMBLE_HEADER when
set, else include/tumble.h of the source tree this directory lies in. With
TUMBLE_BUNDLE_LIBRARY set to a built libtumble.so.X.Y.Z (make wheel does it), that file is
bundled too (tumble/_lib/libtumble.so.MAJOR) and the wheel is tagged for this platform.
"""
import os
import re
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))


def header():
    for path in (os.environ.get("TUMBLE_HEADER"),
                 os.path.join(HERE, "..", "..", "include", "tumble.h"),
                 os.path.join(HERE, "tumble", "tumble.h")):
        if path and os.path.isfile(path):
            return os.path.normpath(path)
    raise SystemExit("tumble.h not found: build from a Tumble source tree (tools/python) "
                     "or set TUMBLE_HEADER")


def version(text):
    parts = [re.search(r"^#define TB_VERSION_%s (\d+)" % p, text, re.M).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    return ".".join(parts)


HEADER = header()
with open(HEADER) as f:
    HEADER_TEXT = f.read()
BUNDLE = os.environ.get("TUMBLE_BUNDLE_LIBRARY")
if BUNDLE and not os.path.isfile(BUNDLE):
    raise SystemExit("TUMBLE_BUNDLE_LIBRARY is %r, but no file is there" % BUNDLE)


class BuildPy(build_py):
    """The package plus tumble.h and, when asked, the library."""

    def run(self):
        super().run()
        target = os.path.join(self.build_lib, "tumble")
        self.mkpath(target)
        shutil.copyfile(HEADER, os.path.join(target, "tumble.h"))
        if os.path.isdir(os.path.join(target, "_lib")):   # from an earlier build
            shutil.rmtree(os.path.join(target, "_lib"))
        if BUNDLE:
            major = version(HEADER_TEXT).split(".")[0]
            self.mkpath(os.path.join(target, "_lib"))
            shutil.copyfile(BUNDLE, os.path.join(target, "_lib", "libtumble.so." + major))


class PlatformDistribution(Distribution):
    """A wheel that bundles the library is for this platform only."""

    def has_ext_modules(self):
        return bool(BUNDLE)


setup(version=version(HEADER_TEXT), cmdclass={"build_py": BuildPy},
      distclass=PlatformDistribution)
