"""Tumble from Python: the C API of libtumble.so through cffi, with numpy arrays for bulk data.

The declarations are read from include/tumble.h itself (no struct is written twice): the
header's preprocessor lines are dropped, its integer #defines kept, and the rest handed to
cffi. The library is TUMBLE_LIBRARY, else build/libtumble.so of this checkout, else
libtumble.so on the loader's path; the header is TUMBLE_HEADER, else include/tumble.h.

    import tumble
    with tumble.World(broadphase="lbvh") as world:
        ball = world.sphere(0.5)
        bodies = world.add_bodies(ball, positions)          # one call for any number
        world.step(1 / 60, n=60)
        positions, rotations = world.transforms(bodies)     # (n, 3) and (n, 4) float32
"""
import os
import re

import cffi
import numpy as np

_HERE = os.path.dirname(os.path.abspath(__file__))
_ROOT = os.path.normpath(os.path.join(_HERE, "..", "..", ".."))


def _declarations(header_text):
    """The header as cffi takes it: no preprocessor lines (continued ones included) but
    integer #defines, no blocks for C++ or for building the library, no static constants,
    TB_API gone."""
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
            define = re.match(r"#define\s+(\w+)\s+(\d+)\s*$", s)
            if define:
                out.append("#define %s %s" % define.groups())
            elif not s.startswith("#") and not s.startswith("static const"):
                out.append(line.replace("TB_API ", ""))
    return "\n".join(out)


def _open():
    header = os.environ.get("TUMBLE_HEADER") or os.path.join(_ROOT, "include", "tumble.h")
    with open(header) as f:
        text = f.read()
    ffi = cffi.FFI()
    ffi.cdef(_declarations(text))
    library = os.environ.get("TUMBLE_LIBRARY") or os.path.join(_ROOT, "build", "libtumble.so")
    if not os.path.exists(library):
        library = "libtumble.so"
    return ffi, ffi.dlopen(library)


ffi, lib = _open()

BROADPHASES = {"default": lib.TB_BROADPHASE_DEFAULT, "grid": lib.TB_BROADPHASE_GRID,
               "sap": lib.TB_BROADPHASE_SAP, "lbvh": lib.TB_BROADPHASE_LBVH,
               "isap": lib.TB_BROADPHASE_ISAP}


class TumbleError(RuntimeError):
    """A call failed; `code` is the tb_result, the message the library's sentence."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def _vec3(v):
    x, y, z = (float(c) for c in v)
    return ffi.new("tb_vec3*", (x, y, z))[0]


class Bodies:
    """Ids of bodies made by one add_bodies call, in order (a C array the bulk calls take)."""

    def __init__(self, ids, count):
        self.ids, self.count = ids, count

    def __len__(self):
        return self.count


class Plugin:
    """A plugin loaded into a world: its parameter block and unloading."""

    def __init__(self, world, plugin_id):
        self._world, self.id = world, plugin_id

    def set_params(self, data, offset=0):
        """Write `data` (bytes, or a numpy array such as float32 vectors) at `offset` of the
        plugin's parameter block; the GPU sees it from the next step on."""
        raw = np.ascontiguousarray(data).tobytes() if not isinstance(data, bytes) else data
        self._world._check(lib.tb_world_set_plugin_param(self._world._w, self.id, offset,
                                                        raw, len(raw)))

    def unload(self):
        self._world._check(lib.tb_world_unload_plugin(self._world._w, self.id))


class World:
    """A world on a Vulkan device. Keyword arguments set tb_world_def fields
    (gravity=(0, -9.81, 0), substeps=6, initial_body_capacity=..., ...); broadphase
    takes a name ("grid", "sap", "lbvh", "isap") and device a name substring or index."""

    def __init__(self, broadphase="default", device=None, **fields):
        d = ffi.new("tb_world_def*", lib.tb_default_world_def())
        d.broadphase = BROADPHASES[broadphase]
        self._device = ffi.new("char[]", device.encode()) if device is not None else None
        if self._device is not None:
            d.device = self._device
        for name, value in fields.items():
            setattr(d, name, _vec3(value) if name == "gravity" else value)
        out = ffi.new("tb_world**")
        code = lib.tb_world_create(d, out)
        if code != lib.TB_OK:
            raise TumbleError(code, ffi.string(lib.tb_world_last_error(ffi.NULL)).decode())
        self._w = out[0]

    def close(self):
        if getattr(self, "_w", None):
            lib.tb_world_destroy(self._w)
            self._w = None

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _check(self, code):
        if code != lib.TB_OK:
            raise TumbleError(code, ffi.string(lib.tb_world_last_error(self._w)).decode())

    # ---- shapes -------------------------------------------------------------------------

    def _shape(self, make, density, friction, restitution):
        d = ffi.new("tb_shape_def*", lib.tb_default_shape_def())
        if density is not None:
            d.density = density
        if friction is not None:
            d.friction = friction
        if restitution is not None:
            d.restitution = restitution
        out = ffi.new("tb_shape_id*")
        self._check(make(d, out))
        return out[0]

    def sphere(self, radius, density=None, friction=None, restitution=None):
        return self._shape(lambda d, o: lib.tb_shape_create_sphere(self._w, d, radius, o),
                           density, friction, restitution)

    def box(self, half_extents, density=None, friction=None, restitution=None):
        h = _vec3(half_extents)
        return self._shape(lambda d, o: lib.tb_shape_create_box(self._w, d, h, o),
                           density, friction, restitution)

    def plane(self, normal, offset, friction=None, restitution=None):
        n = _vec3(normal)
        return self._shape(lambda d, o: lib.tb_shape_create_plane(self._w, d, n, offset, o),
                           None, friction, restitution)

    # ---- bodies -------------------------------------------------------------------------

    def add_bodies(self, shape, positions, static=False, velocities=None):
        """One body of `shape` per row of `positions` (n x 3), in one tb_body_create_many
        call (all or none). Returns their Bodies."""
        positions = np.ascontiguousarray(positions, dtype=np.float32).reshape(-1, 3)
        n = len(positions)
        template = ffi.new("tb_body_def*", lib.tb_default_body_def())
        template.shape = shape
        template.type = lib.TB_BODY_STATIC if static else lib.TB_BODY_DYNAMIC
        defs = ffi.new("tb_body_def[]", max(n, 1))
        size = ffi.sizeof("tb_body_def")
        raw = np.frombuffer(ffi.buffer(defs), dtype=np.uint8).reshape(-1, size)
        raw[:] = np.frombuffer(ffi.buffer(template), dtype=np.uint8)
        self._fill(defs, n, "position", positions)
        if velocities is not None:
            self._fill(defs, n, "linear_velocity",
                       np.asarray(velocities, dtype=np.float32).reshape(-1, 3))
        ids = ffi.new("tb_body_id[]", max(n, 1))
        self._check(lib.tb_body_create_many(self._w, defs, n, ids))
        return Bodies(ids, n)

    @staticmethod
    def _fill(defs, n, field, values):
        size = ffi.sizeof("tb_body_def")
        view = np.ndarray((n, 3), dtype=np.float32, buffer=ffi.buffer(defs),
                          offset=ffi.offsetof("tb_body_def", field), strides=(size, 4))
        view[:] = values

    def transforms(self, bodies):
        """Positions (n x 3) and rotations (n x 4, x y z w) as float32 arrays, read in one
        tb_world_read_transforms call."""
        positions = np.empty((len(bodies), 3), dtype=np.float32)
        rotations = np.empty((len(bodies), 4), dtype=np.float32)
        self._check(lib.tb_world_read_transforms(
            self._w, bodies.ids, len(bodies), ffi.from_buffer("tb_vec3[]", positions),
            ffi.from_buffer("tb_quat[]", rotations)))
        return positions, rotations

    def velocity(self, bodies, k):
        linear, angular = ffi.new("tb_vec3*"), ffi.new("tb_vec3*")
        self._check(lib.tb_body_get_velocity(self._w, bodies.ids[k], linear, angular))
        return (linear.x, linear.y, linear.z), (angular.x, angular.y, angular.z)

    # ---- plugins ------------------------------------------------------------------------

    def load_plugin(self, path):
        """Load a plugin (abi/tumble_plugin.h) into the world; returns its Plugin."""
        out = ffi.new("tb_plugin_id*")
        self._check(lib.tb_world_load_plugin(self._w, os.fsencode(path), out))
        return Plugin(self, out[0])

    def set_shader_dir(self, path):
        """Run the step's shaders from the GLSL tree at `path` and reload them when they
        change (shader hot-reload; None stops watching). Compile errors go to the log."""
        self._check(lib.tb_world_set_shader_dir(
            self._w, ffi.NULL if path is None else os.fsencode(path)))

    # ---- stepping and stats ---------------------------------------------------------------

    def step(self, dt=1.0 / 60.0, n=1):
        self._check(lib.tb_world_step_n(self._w, dt, n))

    def stats(self):
        s = ffi.new("tb_world_stats*")
        self._check(lib.tb_world_get_stats(self._w, s))
        stages = {ffi.string(s.stages[i].name).decode(): s.stages[i].ms
                  for i in range(s.stage_count)}
        return {"bodies": s.body_count, "pairs": s.pair_count, "contacts": s.contact_count,
                "steps": s.steps, "gpu_ms": s.gpu_ms, "stages": stages,
                "broadphase": ffi.string(s.broadphase).decode(),
                "validation_messages": s.validation_messages}
