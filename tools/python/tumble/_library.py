"""Finding libtumble and its header, and opening them with cffi.

The library, first found wins:
  1. TUMBLE_LIBRARY, a path (an error when nothing is there);
  2. the libdir of pkg-config's `tumble` (an installed Tumble: make install);
  3. the copy bundled in this package (a wheel built by `make wheel`);
  4. build/ of the source checkout this package lies in (running from tools/python);
  5. libtumble.so.MAJOR through the system loader (LD_LIBRARY_PATH, ld.so.cache).
The header whose declarations cffi reads is TUMBLE_HEADER, else the one that goes with the
library: include/tumble.h beside its lib/ or build/ directory, pkg-config's includedir, the
copy bundled in this package, or the checkout's include/tumble.h.
"""
import glob
import os
import re
import subprocess

import cffi

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
BUNDLED_HEADER = os.path.join(PACKAGE_DIR, "tumble.h")
BUNDLED_LIBRARY_DIR = os.path.join(PACKAGE_DIR, "_lib")
# The checkout this package lies in, when it does (tools/python/tumble of a source tree).
_ROOT = os.path.normpath(os.path.join(PACKAGE_DIR, "..", "..", ".."))


def _checkout():
    try:
        if os.path.isfile(os.path.join(_ROOT, "include", "tumble.h")) and os.path.samefile(
                PACKAGE_DIR, os.path.join(_ROOT, "tools", "python", "tumble")):
            return _ROOT
    except OSError:
        pass
    return None


CHECKOUT = _checkout()


class LibraryNotFound(ImportError):
    """libtumble (or its header) could not be found or opened; the message says where it
    looked."""


def declarations(header_text):
    """The header as cffi takes it: no preprocessor lines (continued ones included) but
    integer #defines (an unsigned one's `u` dropped: TB_MAX_JOINTS), no blocks for C++ or
    for building the library, no static constants, TB_API gone."""
    out, skipping, continued = [], 0, False
    for line in header_text.splitlines():
        s = line.strip()
        if continued:  # the rest of a preprocessor line that ended with a backslash
            continued = s.endswith("\\")
            continue
        if s.startswith("#"):
            continued = s.endswith("\\")
        if s.startswith("#if") and ("__cplusplus" in s or "TB_BUILDING_LIBRARY" in s):
            skipping += 1
        elif skipping and s.startswith("#endif"):
            skipping -= 1
        elif not skipping:
            define = re.match(r"#define\s+(\w+)\s+(\d+)[uU]?\s*$", s)
            if define:
                out.append("#define %s %s" % define.groups())
            elif not s.startswith("#") and not s.startswith("static const"):
                out.append(line.replace("TB_API ", ""))
    return "\n".join(out)


def header_version(header_text):
    """(major, minor, patch) from the header's TB_VERSION_* lines."""
    parts = []
    for part in ("MAJOR", "MINOR", "PATCH"):
        m = re.search(r"^#define TB_VERSION_%s (\d+)" % part, header_text, re.M)
        if not m:
            raise LibraryNotFound("the header has no TB_VERSION_%s line" % part)
        parts.append(int(m.group(1)))
    return tuple(parts)


def pkg_config_variable(name, environ=None):
    """A variable of pkg-config's `tumble` package, or None (no pkg-config, no package)."""
    try:
        done = subprocess.run(["pkg-config", "--variable=" + name, "tumble"], env=environ,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              universal_newlines=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    value = done.stdout.strip()
    return value if done.returncode == 0 and value else None


def _library_in(directory):
    """libtumble.so in `directory`, else its newest libtumble.so.* file, else None."""
    if not directory or not os.path.isdir(directory):
        return None
    plain = os.path.join(directory, "libtumble.so")
    if os.path.exists(plain):
        return plain
    found = sorted(glob.glob(os.path.join(directory, "libtumble.so.*")))
    return found[-1] if found else None


def _header_beside(library):
    """include/tumble.h of the tree a library file lies in (prefix/lib or checkout/build)."""
    path = os.path.join(os.path.dirname(os.path.abspath(library)), "..", "include", "tumble.h")
    return os.path.normpath(path) if os.path.isfile(path) else None


def _fallback_header():
    if os.path.isfile(BUNDLED_HEADER):
        return BUNDLED_HEADER
    if CHECKOUT:
        return os.path.join(CHECKOUT, "include", "tumble.h")
    return None


def locate(environ=None):
    """(library, header, source): where the library and header are, and which step of the
    order in this module's docstring found the library ("TUMBLE_LIBRARY", "pkg-config",
    "bundled", "checkout" or "system"; for "system" the library is a bare soname)."""
    environ = os.environ if environ is None else environ
    library = environ.get("TUMBLE_LIBRARY")
    if library:
        if not os.path.isfile(library):
            raise LibraryNotFound("TUMBLE_LIBRARY is %r, but no file is there" % library)
        found = (library, _header_beside(library) or _fallback_header(), "TUMBLE_LIBRARY")
    else:
        found = None
        libdir = pkg_config_variable("libdir", environ)
        if libdir and _library_in(libdir):
            includedir = pkg_config_variable("includedir", environ)
            header = os.path.join(includedir, "tumble.h") if includedir else None
            if not (header and os.path.isfile(header)):
                header = _fallback_header()
            found = (_library_in(libdir), header, "pkg-config")
        if not found and _library_in(BUNDLED_LIBRARY_DIR):
            found = (_library_in(BUNDLED_LIBRARY_DIR), _fallback_header(), "bundled")
        if not found and CHECKOUT and _library_in(os.path.join(CHECKOUT, "build")):
            found = (os.path.join(CHECKOUT, "build", "libtumble.so"),
                     os.path.join(CHECKOUT, "include", "tumble.h"), "checkout")
        if not found:
            found = (None, _fallback_header(), "system")
    library, header, source = found
    override = environ.get("TUMBLE_HEADER")
    if override:
        if not os.path.isfile(override):
            raise LibraryNotFound("TUMBLE_HEADER is %r, but no file is there" % override)
        header = override
    if not header:
        raise LibraryNotFound(
            "no tumble.h to read the API from: set TUMBLE_HEADER, install Tumble (make "
            "install, found through pkg-config) or install this package from a Tumble "
            "source tree")
    if source == "system":
        with open(header) as f:
            library = "libtumble.so.%d" % header_version(f.read())[0]
    return library, header, source


def load(environ=None):
    """(ffi, lib, library, header, source) with the library opened and its version
    checked against the header's."""
    library, header, source = locate(environ)
    with open(header) as f:
        text = f.read()
    ffi = cffi.FFI()
    ffi.cdef(declarations(text))
    try:
        lib = ffi.dlopen(library)
    except OSError as e:
        if source == "system":
            raise LibraryNotFound(
                "libtumble not found: TUMBLE_LIBRARY is not set, pkg-config knows no "
                "`tumble`, this package bundles no library, and the system loader cannot "
                "open %s (%s)" % (library, e)) from None
        raise LibraryNotFound("cannot open %s (found through %s): %s"
                              % (library, source, e)) from None
    running = lib.tb_version()
    running = (running >> 22, (running >> 12) & 0x3ff, running & 0xfff)
    wanted = header_version(text)
    if running[0] != wanted[0] or running[1] < wanted[1]:
        raise LibraryNotFound(
            "%s is Tumble %d.%d.%d, too old or of another major version for the header %s "
            "(%d.%d.%d)" % ((library,) + running + (header,) + wanted))
    return ffi, lib, library, header, source
