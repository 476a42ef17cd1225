"""Tumble from Python: the C API of libtumble through cffi, with numpy arrays for bulk data.

The declarations are read from tumble.h itself (no struct is written twice); how the
library and the header are found is in tumble/_library.py and the package's README.

    import numpy as np, tumble
    with tumble.World() as world:
        world.add_body(world.plane((0, 1, 0)), static=True)
        balls = world.add_bodies(world.sphere(0.5), np.array([[0, 2, 0], [0, 3.5, 0]]))
        world.step(1 / 60, n=60)
        positions, rotations = world.transforms(balls)     # (n, 3) and (n, 4) float32
        contacts = world.contacts()                        # numpy structured array

Arguments are checked before any call: a wrong type raises TypeError and a wrong shape or
value ValueError, each naming the argument. What the library refuses raises TumbleError
with the library's sentence and its tb_result code.
"""
import numbers
import os

import numpy as np

from . import _library
from ._library import LibraryNotFound

ffi, lib, library_path, header_path, library_source = _library.load()

with open(header_path) as _f:
    HEADER_VERSION = _library.header_version(_f.read())
__version__ = "%d.%d.%d" % HEADER_VERSION

__all__ = ["World", "Shape", "Body", "Bodies", "Joint", "Joints", "Plugin", "TumbleError",
           "ClosedError", "LibraryNotFound", "BODY_ID", "JOINT_ID", "CONTACT", "BROADPHASES",
           "SOLVERS", "JOINT_KINDS", "version",
           "library_path", "header_path", "library_source", "ffi", "lib"]


def version():
    """(major, minor, patch) of the library running (tb_version)."""
    v = lib.tb_version()
    return (v >> 22, (v >> 12) & 0x3ff, v & 0xfff)


def _broadphases():
    names = {}
    for value in range(64):
        name = lib.tb_broadphase_name(value)
        if name != ffi.NULL:
            names[ffi.string(name).decode()] = value
    return names


SOLVERS = {"soft": lib.TB_SOLVER_SOFT_STEP, "block": lib.TB_SOLVER_BLOCK}  # tb_solver_kind
JOINT_KINDS = {"ball": lib.TB_JOINT_BALL, "hinge": lib.TB_JOINT_HINGE,   # tb_joint_kind
               "fixed": lib.TB_JOINT_FIXED, "distance": lib.TB_JOINT_DISTANCE,
               "slider": lib.TB_JOINT_SLIDER, "cone_twist": lib.TB_JOINT_CONE_TWIST,
               "six_dof": lib.TB_JOINT_SIX_DOF}

BROADPHASES = _broadphases()   # name -> tb_broadphase value, from tb_broadphase_name
_SHAPE_TYPES = {lib.TB_SHAPE_SPHERE: "sphere", lib.TB_SHAPE_BOX: "box",
                lib.TB_SHAPE_PLANE: "plane", lib.TB_SHAPE_HULL: "hull",
                lib.TB_SHAPE_MESH: "mesh", lib.TB_SHAPE_HEIGHTFIELD: "heightfield",
                lib.TB_SHAPE_COMPOUND: "compound", lib.TB_SHAPE_CAPSULE: "capsule",
                lib.TB_SHAPE_CYLINDER: "cylinder", lib.TB_SHAPE_CONE: "cone"}
_LOG_LEVELS = {lib.TB_LOG_DEBUG: "debug", lib.TB_LOG_INFO: "info",
               lib.TB_LOG_WARNING: "warning", lib.TB_LOG_ERROR: "error"}


# ---- numpy views of C structs: dtypes built from cffi's layout, never written by hand ----

_SCALARS = {"float": "<f4", "double": "<f8", "uint32_t": "<u4", "int32_t": "<i4",
            "uint16_t": "<u2", "uint64_t": "<u8", "int": "<i4"}


def _dtype(ctype):
    """The numpy dtype of a C struct: its fields at cffi's offsets, tb_vec3 and tb_quat as
    3 and 4 float32s, nested id structs as structured fields."""
    t = ffi.typeof(ctype)
    names, formats, offsets = [], [], []
    for name, field in t.fields:
        ft = field.type
        if ft.kind == "struct" and ft.cname in ("tb_vec3", "tb_quat"):
            fmt = ("<f4", (len(ft.fields),))
        elif ft.kind == "struct":
            fmt = _dtype(ft.cname)
        elif ft.kind == "enum":
            fmt = "<i4"
        else:
            fmt = _SCALARS[ft.cname]
        names.append(name)
        formats.append(fmt)
        offsets.append(field.offset)
    dtype = np.dtype({"names": names, "formats": formats, "offsets": offsets,
                      "itemsize": ffi.sizeof(t)})
    assert dtype.itemsize == ffi.sizeof(t)
    return dtype


BODY_ID = _dtype("tb_body_id")    # index1, world, generation
JOINT_ID = _dtype("tb_joint_id")  # index1, world, generation
CONTACT = _dtype("tb_contact")    # a, b, point, normal, separation, normal_impulse, ...


# ---- errors ------------------------------------------------------------------------------

class TumbleError(RuntimeError):
    """The library refused a call: `code` is the tb_result, `result` its name ("invalid
    argument", ...), the message the library's sentence."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code
        self.result = ffi.string(lib.tb_result_string(code)).decode()


class ClosedError(RuntimeError):
    """A World (or what belongs to it) was used after close()."""


# ---- argument checks: each names the argument it refuses -----------------------------------

def _real(name, value):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError("%s must be a real number, got %r" % (name, value))
    return float(value)


def _count(name, value, what="a non-negative integer"):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be %s, got %r" % (name, what, value))
    if not 0 <= value <= 0xffffffff:
        raise ValueError("%s must be %s below 2^32, got %d" % (name, what, value))
    return int(value)


def _reals(name, value):
    """`value` as a float32 array, refusing what is not real numbers (strings, complex,
    booleans, objects, ragged lists)."""
    if isinstance(value, (str, bytes)):
        raise TypeError("%s must be real numbers, got %r" % (name, value))
    try:
        a = np.asarray(value)
    except (ValueError, TypeError) as e:
        raise ValueError("%s must be a rectangular array of real numbers (%s)" % (name, e)) \
            from None
    if a.dtype.kind not in "iuf":
        raise TypeError("%s must hold real numbers, got an array of %s" % (name, a.dtype))
    return np.ascontiguousarray(a, dtype=np.float32)


def _indices(name, value):
    """`value` as a uint32 array, refusing what is not integers (floats, strings, complex,
    booleans, objects, ragged lists) and integers a uint32 cannot hold."""
    if isinstance(value, (str, bytes)):
        raise TypeError("%s must be integers, got %r" % (name, value))
    try:
        a = np.asarray(value)
    except (ValueError, TypeError) as e:
        raise ValueError("%s must be a rectangular array of integers (%s)" % (name, e)) \
            from None
    if a.dtype.kind not in "iu" and not (a.size == 0 and a.dtype.kind == "f"):  # [] is float
        raise TypeError("%s must hold integers, got an array of %s" % (name, a.dtype))
    if a.size and (a.min() < 0 or a.max() > 0xffffffff):
        bad = a.min() if a.min() < 0 else a.max()
        raise ValueError("%s must be indices from 0 to 2^32 - 1, got %d" % (name, bad))
    return np.ascontiguousarray(a, dtype=np.uint32)


def _vector(name, value, size):
    a = _reals(name, value)
    if a.shape != (size,):
        raise ValueError("%s must be %d numbers, got an array of shape %s"
                         % (name, size, a.shape))
    return a


def _vec3(name, value):
    x, y, z = (float(c) for c in _vector(name, value, 3))
    return ffi.new("tb_vec3*", (x, y, z))[0]


def _quat(name, value):
    x, y, z, w = (float(c) for c in _vector(name, value, 4))
    return ffi.new("tb_quat*", (x, y, z, w))[0]


def _rows(name, value, columns, n=None, read=_reals, what="bodies"):
    """An (n, columns) array, float32 (or as `read` makes it). One row of `columns` numbers
    is taken as one row, or, when `n` is given, as the row of all n (`what` there are)."""
    a = read(name, value)
    if a.ndim == 1 and a.shape[0] == columns:
        a = a.reshape(1, columns) if n is None else np.tile(a, (n, 1))
    if a.ndim != 2 or a.shape[1] != columns:
        raise ValueError("%s must be an (n, %d) array (or %d numbers), got an array of "
                         "shape %s" % (name, columns, columns, a.shape))
    if n is not None and a.shape[0] != n:
        raise ValueError("%s has %d rows but there are %d %s" % (name, a.shape[0], n, what))
    return np.ascontiguousarray(a)


def _path(name, value):
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise TypeError("%s must be a path (str, bytes or os.PathLike), got %r"
                        % (name, value))
    return os.fsencode(value)


# ---- ids -----------------------------------------------------------------------------------

class _Id:
    """An id of the C API: index1, world serial, generation (equal ids compare equal)."""
    __slots__ = ("index1", "world", "generation")
    _ctype = None

    def __init__(self, index1, world, generation):
        self.index1, self.world, self.generation = int(index1), int(world), int(generation)

    def _c(self):
        return ffi.new(self._ctype + "*", (self.index1, self.world, self.generation))[0]

    @classmethod
    def _from_c(cls, c):
        return cls(c.index1, c.world, c.generation)

    def _key(self):
        return (type(self), self.index1, self.world, self.generation)

    def __eq__(self, other):
        return isinstance(other, _Id) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __repr__(self):
        return "%s(%d, %d, %d)" % (type(self).__name__, self.index1, self.world,
                                   self.generation)


class Shape(_Id):
    """A shape's id (World.sphere, box, capsule, cylinder, cone, plane, hull, mesh,
    heightfield, compound). Any number of bodies may use it; a plane, a mesh or a
    heightfield, static ones only."""
    __slots__ = ()
    _ctype = "tb_shape_id"


class Body(_Id):
    """One body's id: an element of Bodies, or Body(*contact["a"]) for a contact's body."""
    __slots__ = ()
    _ctype = "tb_body_id"


class Joint(_Id):
    """One joint's id (World.create_joint, an element of the Joints create_joints returns)."""
    __slots__ = ()
    _ctype = "tb_joint_id"


class _Ids:
    """Ids in order as a numpy array of a structured id dtype; Bodies and Joints."""
    _dtype, _dtype_name, _one = None, None, None

    def __init__(self, ids):
        ids = np.asarray(ids)
        if ids.dtype != self._dtype or ids.ndim != 1:
            raise TypeError("ids must be a 1-D array of tumble.%s, got %s of %s"
                            % (self._dtype_name, ids.shape, ids.dtype))
        self.ids = np.ascontiguousarray(ids)

    def __len__(self):
        return len(self.ids)

    def __iter__(self):
        return (self._one(*i) for i in self.ids.tolist())

    def __getitem__(self, k):
        if isinstance(k, numbers.Integral) and not isinstance(k, (bool, np.bool_)):
            return self._one(*self.ids[k].tolist())
        return type(self)(self.ids[k])

    def __repr__(self):
        return "%s(%d)" % (type(self).__name__, len(self))

    def __add__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return type(self)(np.concatenate([self.ids, other.ids]))

    def index(self, ids):
        """Where each of `ids` (this collection's kind, an id array of its dtype, or one id)
        is in this collection, -1 where it is not: an int array, or an int for one id."""
        if isinstance(ids, self._one):
            return int(self.index(np.array([(ids.index1, ids.world, ids.generation)],
                                            dtype=self._dtype))[0])
        if isinstance(ids, type(self)):
            ids = ids.ids
        ids = np.asarray(ids)
        if ids.dtype != self._dtype:
            raise TypeError("ids must be a %s, %s or an array of tumble.%s, got an array of %s"
                            % (self._one.__name__, type(self).__name__, self._dtype_name,
                               ids.dtype))
        mine = self.ids.view(np.uint64)
        order = np.argsort(mine, kind="stable")
        wanted = np.ascontiguousarray(ids).view(np.uint64).reshape(ids.shape)
        at = np.searchsorted(mine, wanted, sorter=order) if len(mine) else \
            np.zeros(wanted.shape, dtype=np.intp)
        at = np.minimum(at, max(len(mine) - 1, 0))
        found = order[at] if len(mine) else at
        hit = mine[found] == wanted if len(mine) else np.zeros(wanted.shape, dtype=bool)
        return np.where(hit, found, -1)


class Bodies(_Ids):
    """Ids of bodies in order, as a numpy array of BODY_ID (the C array the bulk calls
    take). Indexing with an int gives a Body; with a slice, mask or index array, Bodies.
    index(ids) says where each of `ids` (Bodies, a BODY_ID array such as contacts()["a"],
    or a Body) is, -1 where it is not."""
    _dtype, _dtype_name, _one = BODY_ID, "BODY_ID", Body


class Joints(_Ids):
    """Ids of joints in order, as a numpy array of JOINT_ID (the C array the bulk calls
    take). Indexing with an int gives a Joint; with a slice, mask or index array, Joints.
    index(ids) says where each of `ids` (Joints, a JOINT_ID array or a Joint) is, -1 where
    it is not."""
    _dtype, _dtype_name, _one = JOINT_ID, "JOINT_ID", Joint


def _as_body(name, value):
    if isinstance(value, Body):
        return value
    if isinstance(value, Bodies) and len(value) == 1:
        return value[0]
    raise TypeError("%s must be a tumble.Body (an element of the Bodies add_bodies "
                    "returned), got %r" % (name, value))


def _as_shape(name, value):
    if not isinstance(value, Shape):
        raise TypeError("%s must be a tumble.Shape (from World.sphere, box, capsule, "
                        "cylinder, cone, plane, hull or mesh), got %r" % (name, value))
    return value


_AXIS_MODES = {"locked": lib.TB_JOINT_AXIS_LOCKED, "free": lib.TB_JOINT_AXIS_FREE}


def _set_axes(template, axes):
    """A 6-dof def's six axes from "locked", "free" or (lower, upper) each."""
    if isinstance(axes, (str, bytes)) or not hasattr(axes, "__len__") or len(axes) != 6:
        raise ValueError("axes must be six entries (x, y, z offsets, then turns about x, y, "
                         "z), each \"locked\", \"free\" or (lower, upper); got %r" % (axes,))
    for i, entry in enumerate(axes):
        axis = template.axes[i]
        if isinstance(entry, str):
            if entry not in _AXIS_MODES:
                raise ValueError("axes[%d] must be \"locked\", \"free\" or (lower, upper), "
                                 "got %r" % (i, entry))
            axis.mode = _AXIS_MODES[entry]
            continue
        pair = _vector("axes[%d]" % i, entry, 2).tolist()
        axis.mode = lib.TB_JOINT_AXIS_LIMITED
        axis.lower, axis.upper = pair


def _as_joint(name, value):
    if isinstance(value, Joint):
        return value
    if isinstance(value, Joints) and len(value) == 1:
        return value[0]
    raise TypeError("%s must be a tumble.Joint (from World.create_joint, or an element of "
                    "the Joints create_joints returned), got %r" % (name, value))


def _as_ids(name, value, many):
    """(C array of ids, count, what keeps the C array alive) for one id or a collection of
    `many` (Bodies, Joints)."""
    one = many._one
    if isinstance(value, one):
        ids = np.array([(value.index1, value.world, value.generation)], dtype=many._dtype)
    elif isinstance(value, many):
        ids = value.ids
    else:
        raise TypeError("%s must be tumble.%s or a tumble.%s, got %r"
                        % (name, many.__name__, one.__name__, value))
    ctype = one._ctype + "[]"
    return (ffi.from_buffer(ctype, ids) if len(ids) else ffi.NULL), len(ids), ids


def _as_bodies(name, value):
    """(C array of ids, count, what keeps the C array alive) for a Body or Bodies."""
    return _as_ids(name, value, Bodies)


def _as_joints(name, value):
    """(C array of ids, count, what keeps the C array alive) for a Joint or Joints."""
    return _as_ids(name, value, Joints)


# ---- plugins ---------------------------------------------------------------------------------

class Plugin:
    """A plugin loaded into a world (World.load_plugin): its parameter block and unloading."""

    def __init__(self, world, plugin_id):
        self._world, self.id = world, plugin_id

    def set_params(self, data, offset=0):
        """Write `data` (bytes, or a numpy array such as float32 vectors) at byte `offset`
        of the plugin's parameter block; the GPU sees it from the next step on."""
        offset = _count("offset", offset)
        if isinstance(data, (bytes, bytearray, memoryview)):
            raw = bytes(data)
        elif isinstance(data, np.ndarray) and data.dtype.kind in "biuf":
            raw = np.ascontiguousarray(data).tobytes()
        else:
            raise TypeError("data must be bytes or a numpy array of numbers, got %r"
                            % (data,))
        w = self._world._handle()
        self._world._check(lib.tb_world_set_plugin_param(w, self.id, offset, raw, len(raw)))

    def unload(self):
        """Remove the plugin's stages and callbacks and unload it."""
        self._world._check(lib.tb_world_unload_plugin(self._world._handle(), self.id))


# ---- the world -------------------------------------------------------------------------------

_WORLD_FIELDS_SET_ELSEWHERE = ("device", "log", "log_user", "broadphase", "internal_cookie")


class World:
    """A world on a Vulkan device, destroyed by close() (or leaving a with block).

    broadphase: "default", "grid", "sap", "lbvh" or "isap". device: an index into the
    Vulkan device list or a substring of the device's name (None: TUMBLE_DEVICE, else the
    library's choice). log: a callable log(level, message), level one of "debug", "info",
    "warning", "error", that receives the library's messages (validation ones included).
    Other keyword arguments set tb_world_def fields: gravity=(0, -9.81, 0), substeps=6,
    solver_iterations, initial_body_capacity, contact_hertz, validation=True, ...
    """

    def __init__(self, broadphase="default", device=None, log=None, **fields):
        self._w = None
        if not isinstance(broadphase, str) or broadphase not in BROADPHASES:
            raise ValueError("broadphase must be one of %s, got %r"
                             % (", ".join(repr(b) for b in BROADPHASES), broadphase))
        d = ffi.new("tb_world_def*", lib.tb_default_world_def())
        d.broadphase = BROADPHASES[broadphase]
        self._keep = []
        if device is not None:
            if isinstance(device, numbers.Integral) and not isinstance(device, bool):
                device = str(_count("device", device))
            if not isinstance(device, str):
                raise TypeError("device must be a device index or a substring of a device "
                                "name, got %r" % (device,))
            self._keep.append(ffi.new("char[]", device.encode()))
            d.device = self._keep[-1]
        if log is not None:
            if not callable(log):
                raise TypeError("log must be a callable log(level, message), got %r" % (log,))

            def sink(user, level, message):
                try:
                    log(_LOG_LEVELS.get(level, str(level)), ffi.string(message).decode())
                except Exception:     # an exception cannot cross the C call; show it
                    import traceback
                    traceback.print_exc()

            self._keep.append(ffi.callback("tb_log_fn*", sink))
            d.log = self._keep[-1]
        self._set_fields(d, fields)
        out = ffi.new("tb_world**")
        code = lib.tb_world_create(d, out)
        if code != lib.TB_OK:
            raise TumbleError(code, ffi.string(lib.tb_world_last_error(ffi.NULL)).decode())
        self._w = out[0]

    def _set_fields(self, d, fields):
        known = {name: f.type for name, f in ffi.typeof("tb_world_def").fields
                 if name not in _WORLD_FIELDS_SET_ELSEWHERE}
        for name, value in fields.items():
            if name not in known:
                raise TypeError("World() got an unexpected keyword argument %r; tb_world_def "
                                "fields are %s" % (name, ", ".join(sorted(known))))
            ctype = known[name].cname
            if ctype == "tb_vec3":
                setattr(d, name, _vec3(name, value))
            elif ctype == "float":
                setattr(d, name, _real(name, value))
            elif ctype == "uint32_t":
                setattr(d, name, _count(name, value))
            elif ctype == "int":
                if not isinstance(value, (bool, numbers.Integral)):
                    raise TypeError("%s must be True or False, got %r" % (name, value))
                setattr(d, name, int(bool(value)))
            elif ctype == "char *":
                if value is not None:
                    self._keep.append(ffi.new("char[]", _path(name, value)))
                    setattr(d, name, self._keep[-1])
            else:
                raise TypeError("World() cannot set %s (%s)" % (name, ctype))

    # ---- lifetime --------------------------------------------------------------------------

    def close(self):
        """Destroy the world and everything in it; using it afterwards raises ClosedError."""
        w, self._w = getattr(self, "_w", None), None
        if w is not None and lib is not None:
            lib.tb_world_destroy(w)

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    @property
    def closed(self):
        return self._w is None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _handle(self):
        if self._w is None:
            raise ClosedError("this tumble.World was closed; make a new World")
        return self._w

    def _check(self, code):
        if code != lib.TB_OK:
            raise TumbleError(code, ffi.string(lib.tb_world_last_error(self._w)).decode())

    # ---- world settings --------------------------------------------------------------------

    @property
    def gravity(self):
        """Gravity, m/s^2, as a (3,) float32 array; assign 3 numbers to change it (from the
        next step on)."""
        g = lib.tb_world_get_gravity(self._handle())
        return np.array([g.x, g.y, g.z], dtype=np.float32)

    @gravity.setter
    def gravity(self, value):
        g = _vec3("gravity", value)
        self._check(lib.tb_world_set_gravity(self._handle(), g))

    @property
    def contact_reuse(self):
        """(distance m, angle rad): a pair that moved and turned less than these since its
        contact points were found keeps them, measured again, instead of running the
        narrowphase (round shapes' pairs; defaults 0.001 and 2 degrees). Assign two numbers
        to change them; 0 for either turns reuse off. tb_world_set_contact_reuse."""
        d, a = ffi.new("float*"), ffi.new("float*")
        lib.tb_world_get_contact_reuse(self._handle(), d, a)
        return (float(d[0]), float(a[0]))

    @contact_reuse.setter
    def contact_reuse(self, value):
        pair = _reals("contact_reuse", value)
        if pair.shape != (2,):
            raise ValueError("contact_reuse must be two numbers (distance, angle), got shape %s"
                             % (pair.shape,))
        distance, angle = float(pair[0]), float(pair[1])
        self._check(lib.tb_world_set_contact_reuse(self._handle(), distance, angle))

    def set_solver(self, solver, iterations=0):
        """Choose the contact solver before the world's first step: "block" (the default:
        hard contacts, deep piles and tall pyramids stand), with `iterations` sweeps a step
        (0: its default, 30), or "soft" (the soft step: contacts are stiff springs, set by
        the world's substeps, solver_iterations and contact_hertz). tb_world_set_solver."""
        if solver not in SOLVERS:
            raise ValueError("solver must be one of %s, got %r"
                             % (", ".join(repr(k) for k in SOLVERS), solver))
        n = _count("iterations", iterations)
        self._check(lib.tb_world_set_solver(self._handle(), SOLVERS[solver], n))

    @property
    def solver(self):
        """The contact solver, "soft" or "block" (set_solver chooses it)."""
        kind = lib.tb_world_get_solver(self._handle(), ffi.NULL)
        return next(name for name, value in SOLVERS.items() if value == kind)

    def device_info(self):
        """The Vulkan device: name, driver, vendor_id, device_id, api_version,
        subgroup_size, is_cpu."""
        info = ffi.new("tb_device_info*")
        self._check(lib.tb_world_device_info(self._handle(), info))
        return {"name": ffi.string(info.name).decode(), "driver": ffi.string(info.driver).decode(),
                "vendor_id": info.vendor_id, "device_id": info.device_id,
                "api_version": info.api_version, "subgroup_size": info.subgroup_size,
                "is_cpu": bool(info.is_cpu)}

    # ---- shapes ----------------------------------------------------------------------------

    def _shape(self, make, density, friction, restitution):
        w = self._handle()
        d = ffi.new("tb_shape_def*", lib.tb_default_shape_def())
        for name, value in (("density", density), ("friction", friction),
                            ("restitution", restitution)):
            if value is not None:
                setattr(d, name, _real(name, value))
        out = ffi.new("tb_shape_id*")
        self._check(make(w, d, out))
        return Shape._from_c(out[0])

    def sphere(self, radius, density=None, friction=None, restitution=None):
        """A sphere of `radius` m about the body's origin."""
        r = _real("radius", radius)
        return self._shape(lambda w, d, o: lib.tb_shape_create_sphere(w, d, r, o),
                           density, friction, restitution)

    def box(self, half_extents, density=None, friction=None, restitution=None):
        """A box of `half_extents` (3 numbers, m) about the body's origin."""
        h = _vec3("half_extents", half_extents)
        return self._shape(lambda w, d, o: lib.tb_shape_create_box(w, d, h, o),
                           density, friction, restitution)

    def _round(self, create, radius, half_height, density, friction, restitution):
        r, h = _real("radius", radius), _real("half_height", half_height)
        return self._shape(lambda w, d, o: create(w, d, r, h, o), density, friction,
                           restitution)

    def capsule(self, radius, half_height, density=None, friction=None, restitution=None):
        """A capsule along the body's y axis: the points within `radius` m of the segment
        from (0, -half_height, 0) to (0, half_height, 0) (half_height 0: a sphere). Its
        origin is its centre of mass."""
        return self._round(lib.tb_shape_create_capsule, radius, half_height, density,
                           friction, restitution)

    def cylinder(self, radius, half_height, density=None, friction=None, restitution=None):
        """A cylinder of `radius` m along the body's y axis, from y = -half_height to
        y = half_height (half_height > 0). Its origin is its centre of mass."""
        return self._round(lib.tb_shape_create_cylinder, radius, half_height, density,
                           friction, restitution)

    def cone(self, radius, half_height, density=None, friction=None, restitution=None):
        """A cone of base `radius` m and height 2 half_height along the body's y axis. Its
        origin is its centre of mass: the base circle lies at y = -half_height / 2 and the
        apex at y = 3 half_height / 2."""
        return self._round(lib.tb_shape_create_cone, radius, half_height, density,
                           friction, restitution)

    def plane(self, normal, offset=0.0, friction=None, restitution=None):
        """The half-space dot(normal, p) <= offset, for static bodies (the ground)."""
        n, off = _vec3("normal", normal), _real("offset", offset)
        return self._shape(lambda w, d, o: lib.tb_shape_create_plane(w, d, n, off, o),
                           None, friction, restitution)

    def hull(self, points, density=None, friction=None, restitution=None):
        """The convex hull of `points` ((n, 3) m). Its body frame is its principal frame
        (origin at the centre of mass): hull_info says where that lies among the points."""
        p = _rows("points", points, 3)
        return self._shape(lambda w, d, o: lib.tb_shape_create_hull(
            w, d, ffi.from_buffer("tb_vec3[]", p), len(p), o), density, friction, restitution)

    def hull_info(self, shape):
        """What a hull became: vertex_count, face_count, edge_count, volume (m^3),
        center_of_mass and principal_axes (in the input points' frame), unit_inertia."""
        s = _as_shape("shape", shape)
        info = ffi.new("tb_hull_info*")
        self._check(lib.tb_shape_get_hull_info(self._handle(), s._c(), info))
        v3 = lambda v: np.array([v.x, v.y, v.z], dtype=np.float32)  # noqa: E731
        q = info.principal_axes
        return {"vertex_count": info.vertex_count, "face_count": info.face_count,
                "edge_count": info.edge_count, "volume": info.volume,
                "center_of_mass": v3(info.center_of_mass),
                "principal_axes": np.array([q.x, q.y, q.z, q.w], dtype=np.float32),
                "unit_inertia": v3(info.unit_inertia)}

    def hull_vertices(self, shape):
        """A hull's vertices in its body frame, (n, 3) float32."""
        s = _as_shape("shape", shape)._c()
        w = self._handle()
        count = ffi.new("uint32_t*")
        self._check(lib.tb_shape_get_hull_vertices(w, s, ffi.NULL, 0, count))
        out = np.empty((count[0], 3), dtype=np.float32)
        if count[0]:
            self._check(lib.tb_shape_get_hull_vertices(
                w, s, ffi.from_buffer("tb_vec3[]", out), count[0], count))
        return out

    def mesh(self, vertices, triangles, friction=None, restitution=None):
        """A triangle mesh, for static bodies: `vertices` ((n, 3) m, body frame) and
        `triangles` ((m, 3) integer indices into them). A triangle collides on its front,
        the side from which its vertices run counter-clockwise; neighbours share vertex
        indices. mesh_info says what it became."""
        v = _rows("vertices", vertices, 3)
        t = _rows("triangles", triangles, 3, read=_indices)
        return self._shape(lambda w, d, o: lib.tb_shape_create_mesh(
            w, d, ffi.from_buffer("tb_vec3[]", v), len(v), ffi.from_buffer("uint32_t[]", t),
            len(t), o), None, friction, restitution)

    def heightfield(self, heights, cell=(1.0, 1.0), holes=None, friction=None,
                    restitution=None):
        """A heightfield, for static bodies: `heights` a (count_z, count_x) array of y (m),
        row k along x, sample (i, k) at x = (i - (count_x - 1) / 2) * cell[0] and
        z = (k - (count_z - 1) / 2) * cell[1] (centred on the body's origin); each cell two
        triangles facing +y. `holes`, if given, a (count_z - 1, count_x - 1) array of
        booleans or integers: nonzero cells are holes."""
        h = _reals("heights", heights)
        if h.ndim != 2:
            raise ValueError("heights must be a (count_z, count_x) array, got an array of "
                             "shape %s" % (h.shape,))
        cx, cz = (float(c) for c in _vector("cell", cell, 2))
        mask = ffi.NULL
        if holes is not None:
            m = np.asarray(holes)
            if m.dtype.kind not in "biu":
                raise TypeError("holes must hold booleans or integers, got an array of %s"
                                % m.dtype)
            if m.shape != (h.shape[0] - 1, h.shape[1] - 1):
                raise ValueError("holes must be a (%d, %d) array, one per cell, got shape %s"
                                 % (h.shape[0] - 1, h.shape[1] - 1, m.shape))
            holes_u8 = np.ascontiguousarray(m != 0, dtype=np.uint8)
            mask = ffi.from_buffer("uint8_t[]", holes_u8)
        nz, nx = h.shape
        return self._shape(lambda w, d, o: lib.tb_shape_create_heightfield(
            w, d, ffi.from_buffer("float[]", h), nx, nz, cx, cz, mask, o), None, friction,
            restitution)

    def mesh_info(self, shape):
        """What a mesh became: vertex_count, triangle_count, degenerate_count (triangles of
        zero area, which touch nothing), active_edge_count (edges a body may touch with
        their own normal), aabb_min and aabb_max (body frame)."""
        s = _as_shape("shape", shape)
        info = ffi.new("tb_mesh_info*")
        self._check(lib.tb_shape_get_mesh_info(self._handle(), s._c(), info))
        v3 = lambda v: np.array([v.x, v.y, v.z], dtype=np.float32)  # noqa: E731
        return {"vertex_count": info.vertex_count, "triangle_count": info.triangle_count,
                "degenerate_count": info.degenerate_count,
                "active_edge_count": info.active_edge_count,
                "aabb_min": v3(info.aabb_min), "aabb_max": v3(info.aabb_max)}

    def mesh_geometry(self, shape):
        """A mesh's vertices ((n, 3) float32) and triangles ((m, 3) uint32), as given."""
        s = _as_shape("shape", shape)._c()
        w = self._handle()
        nv, nt = ffi.new("uint32_t*"), ffi.new("uint32_t*")
        self._check(lib.tb_shape_get_mesh_geometry(w, s, ffi.NULL, 0, ffi.NULL, 0, nv, nt))
        vertices = np.empty((nv[0], 3), dtype=np.float32)
        triangles = np.empty((nt[0], 3), dtype=np.uint32)
        self._check(lib.tb_shape_get_mesh_geometry(
            w, s, ffi.from_buffer("tb_vec3[]", vertices), nv[0],
            ffi.from_buffer("uint32_t[]", triangles), nt[0], nv, nt))
        return vertices, triangles

    def compound(self, children):
        """A compound of 1 to 64 convex children (spheres, boxes, hulls, capsules, cylinders,
        cones): a sequence of (shape, position) or (shape, position, rotation), position 3
        numbers (m) and rotation a unit quaternion (x, y, z, w), in the frame the compound is
        built in. Each child keeps its density, friction and restitution. The body frame is
        the composed principal frame (origin at the centre of mass): compound_info says
        where it lies."""
        if isinstance(children, (str, bytes)) or not hasattr(children, "__len__"):
            raise TypeError("children must be a sequence of (shape, position[, rotation])")
        c = ffi.new("tb_compound_child[]", max(len(children), 1))
        for i, child in enumerate(children):
            if not isinstance(child, (tuple, list)) or len(child) not in (2, 3):
                raise TypeError("child %d must be (shape, position) or (shape, position, "
                                "rotation)" % i)
            c[i].shape = _as_shape("child %d shape" % i, child[0])._c()
            c[i].position = _vec3("child %d position" % i, child[1])
            c[i].rotation = _quat("child %d rotation" % i,
                                  child[2] if len(child) == 3 else (0, 0, 0, 1))
        out = ffi.new("tb_shape_id*")
        self._check(lib.tb_shape_create_compound(self._handle(), c, len(children), out))
        return Shape._from_c(out[0])

    def compound_info(self, shape):
        """What a compound became: child_count, volume (m^3), mass_per_volume (kg/m^3),
        center_of_mass and principal_axes (in the children's frame), unit_inertia."""
        s = _as_shape("shape", shape)
        info = ffi.new("tb_compound_info*")
        self._check(lib.tb_shape_get_compound_info(self._handle(), s._c(), info))
        v3 = lambda v: np.array([v.x, v.y, v.z], dtype=np.float32)  # noqa: E731
        q = info.principal_axes
        return {"child_count": info.child_count, "volume": info.volume,
                "mass_per_volume": info.mass_per_volume,
                "center_of_mass": v3(info.center_of_mass),
                "principal_axes": np.array([q.x, q.y, q.z, q.w], dtype=np.float32),
                "unit_inertia": v3(info.unit_inertia)}

    def compound_children(self, shape):
        """A compound's children as (shape, position, rotation) in its body frame."""
        s = _as_shape("shape", shape)._c()
        w = self._handle()
        count = ffi.new("uint32_t*")
        self._check(lib.tb_shape_get_compound_children(w, s, ffi.NULL, 0, count))
        c = ffi.new("tb_compound_child[]", max(count[0], 1))
        self._check(lib.tb_shape_get_compound_children(w, s, c, count[0], count))
        return [(Shape._from_c(c[i].shape),
                 np.array([c[i].position.x, c[i].position.y, c[i].position.z], dtype=np.float32),
                 np.array([c[i].rotation.x, c[i].rotation.y, c[i].rotation.z, c[i].rotation.w],
                          dtype=np.float32)) for i in range(count[0])]

    def sphere_radius(self, shape):
        """A sphere shape's radius, m."""
        out = ffi.new("float*")
        self._check(lib.tb_shape_get_sphere_radius(self._handle(),
                                                   _as_shape("shape", shape)._c(), out))
        return out[0]

    def box_half_extents(self, shape):
        """A box shape's half extents, m (3 float32)."""
        out = ffi.new("tb_vec3*")
        self._check(lib.tb_shape_get_box_half_extents(self._handle(),
                                                      _as_shape("shape", shape)._c(), out))
        return np.array([out.x, out.y, out.z], dtype=np.float32)

    def round_size(self, shape):
        """A capsule's, cylinder's or cone's (radius, half_height), m, as created."""
        r, h = ffi.new("float*"), ffi.new("float*")
        self._check(lib.tb_shape_get_round_size(self._handle(),
                                                _as_shape("shape", shape)._c(), r, h))
        return r[0], h[0]

    def shape_type(self, shape):
        """"sphere", "box", "capsule", "cylinder", "cone", "plane", "hull", "mesh",
        "heightfield" or "compound"."""
        out = ffi.new("tb_shape_type*")
        self._check(lib.tb_shape_get_type(self._handle(), _as_shape("shape", shape)._c(), out))
        return _SHAPE_TYPES[out[0]]

    # ---- bodies ----------------------------------------------------------------------------

    def add_bodies(self, shape, positions, static=False, rotations=None, velocities=None,
                   angular_velocities=None, mass=None, inertia=None, linear_damping=None,
                   angular_damping=None, gravity_scale=None):
        """Bodies of `shape`, one per row of `positions` ((n, 3) m; 3 numbers for one), in
        one tb_body_create_many call: all are made or none. rotations ((n, 4) x y z w),
        velocities and angular_velocities ((n, 3), m/s and rad/s) take a row per body or
        one row for all; mass (kg), inertia (3 numbers), linear_damping, angular_damping
        and gravity_scale apply to all. Returns their Bodies."""
        s = _as_shape("shape", shape)
        positions = _rows("positions", positions, 3)
        n = len(positions)
        per_body = {"position": positions}
        for name, field, columns, value in (
                ("rotations", "rotation", 4, rotations),
                ("velocities", "linear_velocity", 3, velocities),
                ("angular_velocities", "angular_velocity", 3, angular_velocities)):
            if value is not None:
                per_body[field] = _rows(name, value, columns, n)
        if not isinstance(static, (bool, np.bool_)):
            raise TypeError("static must be True or False, got %r" % (static,))
        w = self._handle()
        template = ffi.new("tb_body_def*", lib.tb_default_body_def())
        template.shape = s._c()
        template.type = lib.TB_BODY_STATIC if static else lib.TB_BODY_DYNAMIC
        for name, value in (("mass", mass), ("linear_damping", linear_damping),
                            ("angular_damping", angular_damping),
                            ("gravity_scale", gravity_scale)):
            if value is not None:
                setattr(template, name, _real(name, value))
        if inertia is not None:
            template.inertia = _vec3("inertia", inertia)
        defs = ffi.new("tb_body_def[]", max(n, 1))
        size = ffi.sizeof("tb_body_def")
        raw = np.frombuffer(ffi.buffer(defs), dtype=np.uint8).reshape(-1, size)
        raw[:] = np.frombuffer(ffi.buffer(template), dtype=np.uint8)
        for field, values in per_body.items():
            view = np.ndarray((n, values.shape[1]), dtype=np.float32, buffer=ffi.buffer(defs),
                              offset=ffi.offsetof("tb_body_def", field), strides=(size, 4))
            view[:] = values
        ids = np.zeros(n, dtype=BODY_ID)
        out = ffi.from_buffer("tb_body_id[]", ids) if n else ffi.NULL
        self._check(lib.tb_body_create_many(w, defs, n, out))
        return Bodies(ids)

    def add_body(self, shape, position=(0.0, 0.0, 0.0), static=False, rotation=None,
                 velocity=None, angular_velocity=None, **others):
        """One body (see add_bodies for the other keywords); returns its Body."""
        return self.add_bodies(
            shape, _vector("position", position, 3), static=static,
            rotations=None if rotation is None else _vector("rotation", rotation, 4),
            velocities=None if velocity is None else _vector("velocity", velocity, 3),
            angular_velocities=None if angular_velocity is None else
            _vector("angular_velocity", angular_velocity, 3), **others)[0]

    def destroy(self, what):
        """Destroy a Body (and its joints), all of Bodies (all or none: each must be live,
        and none twice), a Joint, all of Joints (likewise), or a Shape (refused while bodies
        use it)."""
        w = self._handle()
        if isinstance(what, Shape):
            self._check(lib.tb_shape_destroy(w, what._c()))
            return
        if isinstance(what, Body):
            self._check(lib.tb_body_destroy(w, what._c()))
            return
        if isinstance(what, Joint):
            self._check(lib.tb_joint_destroy(w, what._c()))
            return
        if isinstance(what, Bodies):
            destroy, kind = lib.tb_body_destroy, "body"
        elif isinstance(what, Joints):
            destroy, kind = lib.tb_joint_destroy, "joint"
        else:
            raise TypeError("what must be a tumble.Body, Bodies, Joint, Joints or Shape, got "
                            "%r" % (what,))
        live = self.is_valid(what)
        if not live.all():
            k = int(np.argmin(live))
            try:    # the library's sentence for why this one is not live
                self._check(destroy(w, what[k]._c()))
            except TumbleError as e:
                raise TumbleError(e.code, "what[%d]: %s; nothing was destroyed" % (k, e)) \
                    from None
        if len(np.unique(what.ids.view(np.uint64))) != len(what):
            raise ValueError("what names a %s twice; nothing was destroyed" % kind)
        for one in what:
            self._check(destroy(w, one._c()))

    def is_valid(self, what):
        """Whether a Body, Joint or Shape is live in this world; for Bodies or Joints a bool
        array. A joint dies with either of its bodies."""
        w = self._handle()
        if isinstance(what, Shape):
            return bool(lib.tb_shape_is_valid(w, what._c()))
        if isinstance(what, Body):
            return bool(lib.tb_body_is_valid(w, what._c()))
        if isinstance(what, Joint):
            return bool(lib.tb_joint_is_valid(w, what._c()))
        if isinstance(what, Bodies):
            return np.array([bool(lib.tb_body_is_valid(w, b._c())) for b in what], dtype=bool)
        if isinstance(what, Joints):
            return np.array([bool(lib.tb_joint_is_valid(w, j._c())) for j in what], dtype=bool)
        raise TypeError("what must be a tumble.Body, Bodies, Joint, Joints or Shape, got %r"
                        % (what,))

    def body_ids(self):
        """Every live body of the world, in slot order, as Bodies."""
        w = self._handle()
        n = 0
        stats = ffi.new("tb_world_stats*")
        self._check(lib.tb_world_get_stats(w, stats))
        ids = np.zeros(stats.body_count, dtype=BODY_ID)
        if len(ids):
            n = lib.tb_world_body_ids(w, ffi.from_buffer("tb_body_id[]", ids), len(ids))
        return Bodies(ids[:n])

    def isolated_bodies(self):
        """The bodies the step's guard isolated because their pose or velocity stopped being
        finite (they keep their last finite pose and no longer move or collide), in slot
        order, as Bodies."""
        w = self._handle()
        n = lib.tb_world_isolated_bodies(w, ffi.NULL, 0)
        ids = np.zeros(n, dtype=BODY_ID)
        if n:
            n = min(n, lib.tb_world_isolated_bodies(w, ffi.from_buffer("tb_body_id[]", ids), n))
        return Bodies(ids[:n])

    def shape_ids(self):
        """Every live shape of the world, in slot order, as a list of Shape."""
        w = self._handle()
        stats = ffi.new("tb_world_stats*")
        self._check(lib.tb_world_get_stats(w, stats))
        ids = ffi.new("tb_shape_id[]", max(stats.shape_count, 1))
        n = lib.tb_world_shape_ids(w, ids, stats.shape_count)
        return [Shape(ids[i].index1, ids[i].world, ids[i].generation) for i in range(n)]

    def body_type(self, body):
        """"static" or "dynamic"."""
        out = ffi.new("tb_body_type*")
        self._check(lib.tb_body_get_type(self._handle(), _as_body("body", body)._c(), out))
        return "static" if out[0] == lib.TB_BODY_STATIC else "dynamic"

    def pose(self, body):
        """(position (3,), rotation (4,) x y z w) of one body, float32."""
        p, q = ffi.new("tb_vec3*"), ffi.new("tb_quat*")
        self._check(lib.tb_body_get_pose(self._handle(), _as_body("body", body)._c(), p, q))
        return (np.array([p.x, p.y, p.z], dtype=np.float32),
                np.array([q.x, q.y, q.z, q.w], dtype=np.float32))

    def set_pose(self, body, position, rotation=(0.0, 0.0, 0.0, 1.0)):
        """Move one body (teleport) to `position`, turned by `rotation` (x y z w)."""
        b = _as_body("body", body)
        p, q = _vec3("position", position), _quat("rotation", rotation)
        self._check(lib.tb_body_set_pose(self._handle(), b._c(), p, q))

    def velocity(self, body):
        """(linear m/s (3,), angular rad/s (3,)) of one body, float32."""
        v, a = ffi.new("tb_vec3*"), ffi.new("tb_vec3*")
        self._check(lib.tb_body_get_velocity(self._handle(), _as_body("body", body)._c(), v, a))
        return (np.array([v.x, v.y, v.z], dtype=np.float32),
                np.array([a.x, a.y, a.z], dtype=np.float32))

    def set_velocity(self, body, linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0)):
        b = _as_body("body", body)
        v, a = _vec3("linear", linear), _vec3("angular", angular)
        self._check(lib.tb_body_set_velocity(self._handle(), b._c(), v, a))

    def apply_impulse(self, body, impulse, point=None):
        """Apply `impulse` (N s) at world `point` (default: the body's origin, so it does
        not spin it); no effect on static bodies."""
        b = _as_body("body", body)
        j = _vec3("impulse", impulse)
        at = self.pose(b)[0] if point is None else point
        self._check(lib.tb_body_apply_impulse(self._handle(), b._c(), j, _vec3("point", at)))

    def mass(self, body):
        """(mass kg, principal inertia (3,) kg m^2); mass 0 for a static body."""
        m, i = ffi.new("float*"), ffi.new("tb_vec3*")
        self._check(lib.tb_body_get_mass(self._handle(), _as_body("body", body)._c(), m, i))
        return m[0], np.array([i.x, i.y, i.z], dtype=np.float32)

    def _read_bulk(self, read, bodies, second):
        """Two float32 arrays from one bulk read of a Body or Bodies: (n, 3) as tb_vec3,
        and (n, 3) tb_vec3 or (n, 4) tb_quat as `second` says."""
        ids, n, keep = _as_bodies("bodies", bodies)
        first = np.empty((n, 3), dtype=np.float32)
        other = np.empty((n, 4 if second == "tb_quat" else 3), dtype=np.float32)
        if n:
            self._check(read(self._handle(), ids, n, ffi.from_buffer("tb_vec3[]", first),
                             ffi.from_buffer(second + "[]", other)))
        else:
            self._handle()
        return first, other

    def transforms(self, bodies):
        """Positions (n, 3) and rotations (n, 4, x y z w) of a Body or Bodies as float32
        arrays, in one tb_world_read_transforms call."""
        return self._read_bulk(lib.tb_world_read_transforms, bodies, "tb_quat")

    def aabbs(self, bodies):
        """World-space boxes (mins (n, 3), maxs (n, 3)) as the last step's broadphase saw
        them."""
        return self._read_bulk(lib.tb_world_read_aabbs, bodies, "tb_vec3")

    def contacts(self):
        """Contact points of the last step, grouped by pair, as a numpy structured array of
        tumble.CONTACT: a and b (BODY_ID; the normal points from a to b), point, normal,
        separation, normal_impulse, friction_impulse, feature."""
        w = self._handle()
        count = ffi.new("uint32_t*")
        self._check(lib.tb_world_read_contacts(w, ffi.NULL, 0, count))
        out = np.zeros(count[0], dtype=CONTACT)
        if count[0]:
            self._check(lib.tb_world_read_contacts(
                w, ffi.from_buffer("tb_contact[]", out), len(out), count))
        return out[:count[0]]

    # ---- joints ----------------------------------------------------------------------------

    def create_joints(self, kind, bodies_a, bodies_b, at=None, axis=None, anchors_a=None,
                      anchors_b=None, frames_a=None, frames_b=None, length=None, limit=None,
                      motor=None, spring=None, collide_connected=False, break_force=None,
                      break_torque=None, cone_angle=None, axes=None, soft=None):
        """Joints of one `kind` ("ball", "hinge", "fixed", "distance", "slider", "cone_twist"
        or "six_dof"), joint i
        between bodies_a[i] and bodies_b[i], in one tb_joint_create_many call: all are made
        or none. bodies_a and bodies_b are Bodies of one length, or a Body that every joint
        shares (a hook that all hang from). Where each joint holds, either:

        - at ((n, 3) m, world; 3 numbers for all) and axis (likewise, default (1, 0, 0)):
          the anchors at that world point and the frames' x axes (a hinge's or slider's
          axis) along that world direction, from the bodies' present poses
          (tb_joint_def_at); or
        - anchors_a, anchors_b ((n, 3) m, each in its body's frame; default the origins)
          and frames_a, frames_b ((n, 4) x y z w quaternions in the bodies' frames; default
          identity). A distance joint's two anchors are two points: give these.

        The options apply to all: length (distance joints, m; default 1), limit=(lower,
        upper) (hinges and a cone-twist's twist rad in [-pi, pi], sliders and distance joints
        m), motor=(speed, max_force) (hinges rad/s and N m, sliders m/s and N),
        spring=(hertz, damping_ratio) or (hertz, damping_ratio, target) (distance joints: a
        spring to `length` instead of a rod; hinges: to the angle `target`, rad; sliders: to
        the offset `target`, m; default target 0), cone_angle (cone-twist joints: the
        largest angle between the frames' x axes, rad; default pi/4), axes (6-dof joints:
        six entries, the offsets along a's frame's x, y, z then the turns about them, each
        "locked" (the default), "free" or (lower, upper)), soft=(hertz, damping_ratio) (what
        the kind holds is held by springs of that frequency and damping instead of rigidly;
        limits stay hard; default rigid), collide_connected (whether the
        two bodies collide; default False), break_force (N) and break_torque (N m): the
        joint breaks once it holds more (None or 0: never). Each holds from the next step
        on. Returns their Joints."""
        return self._create_joints(kind, bodies_a, bodies_b, at, axis, anchors_a, anchors_b,
                                   frames_a, frames_b, length, limit, motor, spring,
                                   collide_connected, break_force, break_torque, False,
                                   cone_angle, axes, soft)

    def create_joint(self, kind, body_a, body_b, at=None, axis=None, anchor_a=None,
                     anchor_b=None, frame_a=None, frame_b=None, length=None, limit=None,
                     motor=None, spring=None, collide_connected=False, break_force=None,
                     break_torque=None, cone_angle=None, axes=None, soft=None):
        """One joint of `kind` (one of JOINT_KINDS) between
        body_a and body_b: at a world point `at` (3 numbers) with the hinge's or slider's
        `axis` (a world direction, default (1, 0, 0)), or at anchor_a and anchor_b (each in
        its body's frame) with frame_a and frame_b (x y z w). The other keywords are
        create_joints'. Returns its Joint."""
        a, b = _as_body("body_a", body_a), _as_body("body_b", body_b)
        one = {}
        for name, value, size in (("at", at, 3), ("axis", axis, 3), ("anchor_a", anchor_a, 3),
                                  ("anchor_b", anchor_b, 3), ("frame_a", frame_a, 4),
                                  ("frame_b", frame_b, 4)):
            one[name] = None if value is None else _vector(name, value, size)
        return self._create_joints(kind, a, b, one["at"], one["axis"], one["anchor_a"],
                                   one["anchor_b"], one["frame_a"], one["frame_b"], length,
                                   limit, motor, spring, collide_connected, break_force,
                                   break_torque, True, cone_angle, axes, soft)[0]

    def _create_joints(self, kind, bodies_a, bodies_b, at, axis, anchors_a, anchors_b,
                       frames_a, frames_b, length, limit, motor, spring, collide_connected,
                       break_force, break_torque, single, cone_angle=None, axes=None,
                       soft=None):
        if not isinstance(kind, str) or kind not in JOINT_KINDS:
            raise ValueError("kind must be one of %s, got %r"
                             % (", ".join(repr(k) for k in JOINT_KINDS), kind))
        suffix = "" if single else "s"
        ends = []
        for name, value in (("body_a" if single else "bodies_a", bodies_a),
                            ("body_b" if single else "bodies_b", bodies_b)):
            if not isinstance(value, (Body, Bodies)):
                raise TypeError("%s must be a tumble.Body%s, got %r"
                                % (name, "" if single else " or Bodies", value))
            ends.append(value)
        counts = [len(e) for e in ends if isinstance(e, Bodies)]
        if len(counts) == 2 and counts[0] != counts[1]:
            raise ValueError("bodies_a has %d bodies but bodies_b has %d (one of each a joint)"
                             % tuple(counts))
        n = counts[0] if counts else 1
        ids_a, ids_b = (e.ids if isinstance(e, Bodies) else
                        np.array([(e.index1, e.world, e.generation)] * n, dtype=BODY_ID)
                        for e in ends)
        placed = [("anchor%s_a" % suffix, "anchor_a", 3, anchors_a),
                  ("anchor%s_b" % suffix, "anchor_b", 3, anchors_b),
                  ("frame%s_a" % suffix, "frame_a", 4, frames_a),
                  ("frame%s_b" % suffix, "frame_b", 4, frames_b)]
        placed = [p for p in placed if p[3] is not None]
        if at is not None and placed:
            raise ValueError("give at (and axis) or %s, not both: at sets the anchors and the "
                             "frames" % ", ".join(p[0] for p in placed))
        if at is None and axis is not None:
            raise ValueError("axis goes with at (the world point the joint is made at); "
                             "without at, give frame%s_a and frame%s_b" % (suffix, suffix))
        per_joint = {field: _rows(name, value, columns, n, what="joints")
                     for name, field, columns, value in placed}
        if at is not None:
            at = _rows("at", at, 3, n, what="joints")
            axis = _rows("axis", (1.0, 0.0, 0.0) if axis is None else axis, 3, n,
                         what="joints")
        template = ffi.new("tb_joint_def*", lib.tb_default_joint_def())
        template.kind = JOINT_KINDS[kind]
        for name, value in (("length", length), ("break_force", break_force),
                            ("break_torque", break_torque), ("cone_angle", cone_angle)):
            if value is not None:
                setattr(template, name, _real(name, value))
        if spring is not None and np.size(spring) == 3:
            hertz, damping_ratio, template.spring_target = _vector("spring", spring, 3).tolist()
            spring = (hertz, damping_ratio)
        for name, value, enable, fields in (
                ("limit", limit, "enable_limit", ("lower", "upper")),
                ("motor", motor, "enable_motor", ("motor_speed", "max_motor_force")),
                ("spring", spring, "enable_spring", ("spring_hertz", "spring_damping_ratio")),
                ("soft", soft, None, ("constraint_hertz", "constraint_damping_ratio"))):
            if value is not None:
                pair = _vector(name, value, 2)
                if enable:
                    setattr(template, enable, 1)
                for field, number in zip(fields, pair.tolist()):
                    setattr(template, field, number)
        if axes is not None:
            _set_axes(template, axes)
        if not isinstance(collide_connected, (bool, np.bool_)):
            raise TypeError("collide_connected must be True or False, got %r"
                            % (collide_connected,))
        template.collide_connected = int(bool(collide_connected))
        w = self._handle()
        defs = ffi.new("tb_joint_def[]", max(n, 1))
        size = ffi.sizeof("tb_joint_def")
        raw = np.frombuffer(ffi.buffer(defs), dtype=np.uint8).reshape(-1, size)
        raw[:] = np.frombuffer(ffi.buffer(template), dtype=np.uint8)
        for field, ids in (("body_a", ids_a), ("body_b", ids_b)):
            view = np.ndarray((n,), dtype=BODY_ID, buffer=ffi.buffer(defs),
                              offset=ffi.offsetof("tb_joint_def", field), strides=(size,))
            view[:] = ids
        for field, values in per_joint.items():
            view = np.ndarray((n, values.shape[1]), dtype=np.float32, buffer=ffi.buffer(defs),
                              offset=ffi.offsetof("tb_joint_def", field), strides=(size, 4))
            view[:] = values
        if at is not None:
            for i in range(n):
                code = lib.tb_joint_def_at(w, defs + i, tuple(at[i].tolist()),
                                           tuple(axis[i].tolist()))
                if code != lib.TB_OK and not single:   # its sentence says "joint def 0"
                    why = ffi.string(lib.tb_world_last_error(w)).decode()
                    why = why[len("joint def 0: "):] if why.startswith("joint def 0: ") else why
                    raise TumbleError(code, "joint %d (at[%d], axis[%d]): %s; no joint was "
                                      "made" % (i, i, i, why))
                self._check(code)
        ids = np.zeros(n, dtype=JOINT_ID)
        out = ffi.from_buffer("tb_joint_id[]", ids) if n else ffi.NULL
        self._check(lib.tb_joint_create_many(w, defs, n, out))
        return Joints(ids)

    def joint_bodies(self, joint):
        """The two bodies of a Joint, (body_a, body_b); of Joints, (Bodies, Bodies)."""
        w = self._handle()
        if isinstance(joint, Joints):
            a, b = np.zeros(len(joint), dtype=BODY_ID), np.zeros(len(joint), dtype=BODY_ID)
            out_a, out_b = ffi.new("tb_body_id*"), ffi.new("tb_body_id*")
            for i, j in enumerate(joint):
                self._check(lib.tb_joint_get_bodies(w, j._c(), out_a, out_b))
                a[i] = (out_a.index1, out_a.world, out_a.generation)
                b[i] = (out_b.index1, out_b.world, out_b.generation)
            return Bodies(a), Bodies(b)
        j = _as_joint("joint", joint)
        out_a, out_b = ffi.new("tb_body_id*"), ffi.new("tb_body_id*")
        self._check(lib.tb_joint_get_bodies(w, j._c(), out_a, out_b))
        return Body._from_c(out_a[0]), Body._from_c(out_b[0])

    def _set_pair(self, set_pair, joint, names, first, second, enable):
        """tb_joint_set_motor or tb_joint_set_limit: both numbers when turning it on; when
        turning it off, the numbers given or 0."""
        j = _as_joint("joint", joint)
        if not isinstance(enable, (bool, np.bool_)):
            raise TypeError("enable must be True or False, got %r" % (enable,))
        if enable and (first is None or second is None):
            raise TypeError("give %s and %s (or enable=False to turn it off)" % names)
        first = 0.0 if first is None else _real(names[0], first)
        second = 0.0 if second is None else _real(names[1], second)
        self._check(set_pair(self._handle(), j._c(), int(bool(enable)), first, second))

    def set_motor(self, joint, speed=None, max_force=None, enable=True):
        """A hinge's or slider's motor, from the next step on: target `speed` (hinges rad/s
        of body b about the axis relative to a, sliders m/s) with at most `max_force` (N m,
        N; >= 0). set_motor(joint, enable=False) turns it off."""
        self._set_pair(lib.tb_joint_set_motor, joint, ("speed", "max_force"), speed,
                       max_force, enable)

    def set_spring(self, joint, hertz=None, damping_ratio=None, target=0.0, enable=True):
        """A hinge's, slider's or distance joint's spring, from the next step on: `hertz`
        (> 0) and `damping_ratio` (>= 0) on the bodies' effective mass or moment, pulling to
        `target` (hinges: the angle, rad, in [-pi, pi]; sliders: the offset, m; distance
        joints: the length, m). A hinge's target moved each step makes a position servo.
        set_spring(joint, enable=False) turns it off."""
        j = _as_joint("joint", joint)
        if not isinstance(enable, (bool, np.bool_)):
            raise TypeError("enable must be True or False, got %r" % (enable,))
        if enable and (hertz is None or damping_ratio is None):
            raise TypeError("give hertz and damping_ratio (or enable=False to turn it off)")
        hertz = 1.0 if hertz is None else _real("hertz", hertz)
        damping_ratio = 0.0 if damping_ratio is None else _real("damping_ratio", damping_ratio)
        self._check(lib.tb_joint_set_spring(self._handle(), j._c(), int(bool(enable)), hertz,
                                            damping_ratio, _real("target", target)))

    def set_limit(self, joint, lower=None, upper=None, enable=True):
        """A hinge's or cone-twist's twist (rad, within [-pi, pi]), slider's or distance
        joint's (m) limit, from
        the next step on, lower <= upper. set_limit(joint, enable=False) turns it off."""
        self._set_pair(lib.tb_joint_set_limit, joint, ("lower", "upper"), lower, upper,
                       enable)

    def joint_forces(self, joints):
        """What a Joint or Joints held in the last step, in one tb_joint_read_forces call:
        forces (n, 3) N and torques (n, 3) N m (about b's anchor) each applied to its body b,
        world frame, float32, and broken (n,) bool (a broken joint holds nothing from then
        on and stays broken until destroyed). Zeros for a joint that has not stepped yet."""
        ids, n, keep = _as_joints("joints", joints)
        forces = np.zeros((n, 3), dtype=np.float32)
        torques = np.zeros((n, 3), dtype=np.float32)
        broken = np.zeros(n, dtype=np.int32)
        w = self._handle()
        if n:
            self._check(lib.tb_joint_read_forces(w, ids, n, ffi.from_buffer("tb_vec3[]", forces),
                                                 ffi.from_buffer("tb_vec3[]", torques),
                                                 ffi.from_buffer("int32_t[]", broken)))
        return forces, torques, broken != 0

    def joint_anchors(self, joints):
        """The anchors (anchors_a (n, 3), anchors_b (n, 3), float32, m) of a Joint or Joints
        in world space from the bodies' present poses, in one tb_joint_read_anchors call."""
        ids, n, keep = _as_joints("joints", joints)
        anchors_a = np.zeros((n, 3), dtype=np.float32)
        anchors_b = np.zeros((n, 3), dtype=np.float32)
        w = self._handle()
        if n:
            self._check(lib.tb_joint_read_anchors(w, ids, n,
                                                  ffi.from_buffer("tb_vec3[]", anchors_a),
                                                  ffi.from_buffer("tb_vec3[]", anchors_b)))
        return anchors_a, anchors_b

    def joint_ids(self):
        """Every live joint of the world, in slot order, as Joints."""
        w = self._handle()
        n = lib.tb_world_joint_ids(w, ffi.NULL, 0)   # how many there are
        ids = np.zeros(n, dtype=JOINT_ID)
        if n:
            n = lib.tb_world_joint_ids(w, ffi.from_buffer("tb_joint_id[]", ids), n)
        return Joints(ids[:n])

    # ---- stepping and stats ----------------------------------------------------------------

    def step(self, dt=1.0 / 60.0, n=1):
        """Advance `n` steps of `dt` seconds in one queue submission (n = 0 does nothing)."""
        dt = _real("dt", dt)
        n = _count("n", n, "a non-negative integer (the number of steps)")
        self._check(lib.tb_world_step_n(self._handle(), dt, n))

    def snapshot(self):
        """The world's state as bytes (tb_world_snapshot): restore() puts it back, here or in
        a world made alike (the same def, solver, broadphase and shapes, made in the same
        order), and the world then continues bit for bit as it did from there. A world with
        joints is refused (the library does not save joints yet)."""
        w = self._handle()
        size = ffi.new("size_t*")
        self._check(lib.tb_world_snapshot(w, ffi.NULL, 0, size))
        out = bytearray(size[0])
        self._check(lib.tb_world_snapshot(w, ffi.from_buffer(out), len(out), size))
        return bytes(out)

    def restore(self, snapshot):
        """Put back a snapshot() (bytes-like); one that is damaged or from a world whose
        shapes, solver or broadphase differ is refused and nothing changes."""
        if not isinstance(snapshot, (bytes, bytearray, memoryview)):
            raise TypeError("snapshot must be bytes from World.snapshot(), got %s"
                            % type(snapshot).__name__)
        data = bytes(snapshot)
        self._check(lib.tb_world_restore(self._handle(), ffi.from_buffer(data), len(data)))

    def stats(self):
        """tb_world_stats as a dict of its field names (body_count, contact_count, steps,
        gpu_ms, validation_messages, ...); broadphase as its name, stages as a dict of
        stage name to GPU ms."""
        s = ffi.new("tb_world_stats*")
        self._check(lib.tb_world_get_stats(self._handle(), s))
        out = {}
        for name, _ in ffi.typeof("tb_world_stats").fields:
            if name in ("stage_count", "stages"):
                continue
            value = getattr(s, name)
            out[name] = ffi.string(value).decode() if name == "broadphase" else value
        out["stages"] = {ffi.string(s.stages[i].name).decode(): s.stages[i].ms
                         for i in range(s.stage_count)}
        return out

    # ---- plugins and shaders ---------------------------------------------------------------

    def load_plugin(self, path):
        """Load a plugin (abi/tumble_plugin.h) into the world; returns its Plugin."""
        p = _path("path", path)
        out = ffi.new("tb_plugin_id*")
        self._check(lib.tb_world_load_plugin(self._handle(), p, out))
        return Plugin(self, out[0])

    def set_shader_dir(self, path):
        """Run the step's shaders from the GLSL tree at `path` and reload them when they
        change (shader hot-reload; None stops watching). Compile errors go to the log."""
        p = ffi.NULL if path is None else _path("path", path)
        self._check(lib.tb_world_set_shader_dir(self._handle(), p))
