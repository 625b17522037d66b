"""gomboc from Python: scenes loaded from a file, a string or a dict, run by the C library, the history and the
impacts as numpy arrays, the fingerprints and the results by name.

    import gomboc
    scene = gomboc.load("cases/table1-gomboc-I.ini", {"integrator.periods": 20})
    run = scene.run()
    run.fingerprint          # ('8d37...', '1f30...'): `gomboc run`'s, bit for bit
    run.history["omega_x"]   # every sample, unrounded (the history file's columns)
    run.values["energy_residual"]   # and lambda_max, lambda_error where the scene asks for lambda
    scene.massprops()["inertia"], scene.contact([0, 0, -1])["height"]

The binding is cffi's ABI mode (Debian python3-cffi): it declares the library's opaque-handle interface
(src/gb_handle.h) and opens the shared library, with no compiler at import. Why cffi and not ctypes: the
declarations are the C header's own text, checked by cffi's parser, and callbacks need no hand-written types.

The shared library is $GOMBOC_LIB when it is set (a path to libgomboc.so.0 or its build's file; that one only), else
found in order: the library installed beside this package (PREFIX/lib, when `make install` put the package under PREFIX/lib/python3.X), the
build tree's (build/libgomboc.so.0.*, when the package is used from the source tree), then the system's
libgomboc.so.0. A library that cannot be loaded is an ImportError that says so.

Errors are GombocError, with the library's message and, where the message names them, the file, line, section,
key and the allowed range as attributes."""
import glob
import os
import re

import numpy as np
from cffi import FFI

__all__ = ["GombocError", "Scene", "Run", "load", "loads", "scan", "columns", "impact_columns", "blas_single_thread"]

_CDEF = """
typedef struct gb_handle_scene gb_handle_scene;
typedef struct gb_handle_run gb_handle_run;
int gb_handle_scene_load(const char *path, const char *const *overrides, size_t count, gb_handle_scene **out);
int gb_handle_scene_text(const char *name, const char *text, const char *const *overrides, size_t count,
                         gb_handle_scene **out);
void gb_handle_scene_free(gb_handle_scene *scene);
int gb_handle_run_scene(const gb_handle_scene *scene, int keep_history, int keep_impacts, gb_handle_run **out);
void gb_handle_run_free(gb_handle_run *run);
const char *const *gb_handle_columns(void);
const double *gb_handle_run_history(const gb_handle_run *run, size_t *rows);
const char *const *gb_handle_impact_columns(void);
const double *gb_handle_run_impacts(const gb_handle_run *run, size_t *rows);
uint64_t gb_handle_run_fingerprint(const gb_handle_run *run, int which);
const char *const *gb_handle_values(void);
double gb_handle_run_value(const gb_handle_run *run, const char *name);
int gb_handle_scene_massprops(const gb_handle_scene *scene, double out[13]);
int gb_handle_scene_contact(const gb_handle_scene *scene, const double zb[3], double out[6]);
int gb_handle_scene_equilibria(const gb_handle_scene *scene, double *out, size_t capacity, size_t *count);
int gb_handle_scene_melnikov(const gb_handle_scene *scene, double out[2]);
int gb_handle_scene_tangle(const gb_handle_scene *scene, double spacing, int halvings, double out[6]);
typedef void (*gb_handle_progress)(void *user, int phase, size_t done, size_t total, double seconds);
int gb_handle_scan(const char *path, unsigned threads, gb_handle_progress progress, void *user, char **csv);
void gb_handle_text_free(char *text);
const char *gb_error_message(void);
void gb_error_init_gsl(void);
int gb_integrate_blas_single_thread(void);
"""

_ffi = FFI()
_ffi.cdef(_CDEF)


def _library_path():
    here = os.path.dirname(os.path.abspath(__file__))
    if os.environ.get("GOMBOC_LIB"):  # named: that library or none, never another found elsewhere
        return os.environ["GOMBOC_LIB"]
    candidates = []
    # installed: PREFIX/lib/python3.X/dist-packages/gomboc -> PREFIX/lib
    candidates.append(os.path.normpath(os.path.join(here, "..", "..", "..", "libgomboc.so.0")))
    # the source tree: python/gomboc -> build/
    candidates += sorted(glob.glob(os.path.join(here, "..", "..", "build", "libgomboc.so.0.*")))
    for path in candidates:
        if os.path.exists(path):
            return path
    return "libgomboc.so.0"


try:
    _lib = _ffi.dlopen(_library_path())
except OSError as error:
    raise ImportError(f"gomboc: the shared library libgomboc.so.0 was not found or not loaded ({error}); set GOMBOC_LIB to "
                      "its path (the build tree's build/libgomboc.so.0.*, made by make verify or make install), or install "
                      "it with make install") from None
_lib.gb_error_init_gsl()

# "FILE:LINE: [section] key = value: reason (allowed: ...)" (gb_case.h)
_WHERE = re.compile(r"^(?P<file>[^:\n]+?)(?::(?P<line>\d+))?: \[(?P<section>[^\]]+)\] (?P<key>[A-Za-z0-9_.]+)")
_ALLOWED = re.compile(r"\(allowed: (?P<allowed>.*)\)", re.S)  # to the message's last parenthesis: ranges nest them


class GombocError(Exception):
    """A library error: `message`, `status` (gb_ status: 1 a value out of range, 2 malformed input, 3 no memory,
    4 no convergence, 5 input/output, 6 a numerical routine failed), and where the message names them `file`,
    `line`, `section`, `key` and `allowed` (else None)."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status, self.message = status, message
        where, allowed = _WHERE.search(message), _ALLOWED.search(message)
        self.file = where.group("file") if where else None
        self.line = int(where.group("line")) if where and where.group("line") else None
        self.section = where.group("section") if where else None
        self.key = where.group("key") if where else None
        self.allowed = allowed.group("allowed") if allowed else None


def _check(status):
    if status:
        raise GombocError(status, _ffi.string(_lib.gb_error_message()).decode("utf-8", "replace"))


def _names(pointer):
    out, k = [], 0
    while pointer[k] != _ffi.NULL:
        out.append(_ffi.string(pointer[k]).decode())
        k += 1
    return out


def blas_single_thread():
    """Run the BLAS under Siconos's solvers (time-stepping) on one thread, process-wide (OpenBLAS's threads spin on
    the cores for its small matrices: docs/stepping.md); True when it could be set. numpy shares that BLAS."""
    return _lib.gb_integrate_blas_single_thread() == 1


def columns():
    """The history's columns: the history file's (docs/outputs.md), with the slip's two."""
    return _names(_lib.gb_handle_columns())


def impact_columns():
    """The impacts' numeric columns (the impacts file's; `kind` as its code)."""
    return _names(_lib.gb_handle_impact_columns())


def _overrides(overrides):
    """{"section.key": value} (or {"section": {"key": value}}) as the C triples, kept alive with the call."""
    triples = []
    for name, value in (overrides or {}).items():
        if isinstance(value, dict):
            triples += [(name, key, v) for key, v in value.items()]
            continue
        if "." not in name:
            raise GombocError(2, f"override '{name}': not section.key (allowed: a key such as 'forcing.omega')")
        section, key = name.split(".", 1)
        triples.append((section, key, value))
    keep = [_ffi.new("char[]", str(x).encode()) for triple in triples for x in triple]
    array = _ffi.new("const char *[]", keep + [_ffi.NULL]) if keep else _ffi.NULL
    return array, len(triples), keep


class Scene:
    """A loaded scene (a case file's contents over the defaults, with overrides): run it with run()."""

    def __init__(self, handle):
        self._handle = _ffi.gc(handle, _lib.gb_handle_scene_free)

    def massprops(self):
        """The body's volume, centroid (3) and inertia about the centroid (3 × 3, numpy) at the scene's mass."""
        out = _ffi.new("double[13]")
        _check(_lib.gb_handle_scene_massprops(self._handle, out))
        return {"volume": out[0], "centroid": np.array([out[1], out[2], out[3]]),
                "inertia": np.array([out[4 + k] for k in range(9)]).reshape(3, 3)}

    def contact(self, zb):
        """The contact for the body-frame upward vertical zb (any non-zero length): phi, theta, height and r_c, as
        `gomboc contact --method continuous` finds it (every local minimum of the 180 x 360 seed grid polished, the
        lowest)."""
        out = _ffi.new("double[6]")
        _check(_lib.gb_handle_scene_contact(self._handle, _ffi.new("double[3]", [float(x) for x in zb]), out))
        return {"phi": out[0], "theta": out[1], "height": out[2], "rc": np.array([out[3], out[4], out[5]])}

    def equilibria(self):
        """The body's equilibria as `gomboc shape` finds them: every critical point of r(phi, theta), as a dict of
        numpy arrays "type" ("stable", "saddle", "unstable"), "phi", "theta", "r", and the counts by type."""
        count = _ffi.new("size_t *")
        rows = _ffi.new("double[256]")
        _check(_lib.gb_handle_scene_equilibria(self._handle, rows, 64, count))
        n = min(count[0], 64)
        data = np.array([rows[k] for k in range(4 * n)]).reshape(n, 4)
        names = np.array(["stable", "saddle", "unstable"])[data[:, 0].astype(int)] if n else np.empty(0, dtype=str)
        return {"type": names, "phi": data[:, 1], "theta": data[:, 2], "r": data[:, 3],
                "counts": {name: int(np.sum(names == name)) for name in ("stable", "saddle", "unstable")}}

    def melnikov(self):
        """The scene's Melnikov margins as `gomboc scan`'s metric melnikov: "margin" (eq 91's largest oscillatory part
        over mu D) and "margin_eq93"; above 1 the reduced model's manifolds cross."""
        out = _ffi.new("double[2]")
        _check(_lib.gb_handle_scene_melnikov(self._handle, out))
        return {"margin": out[0], "margin_eq93": out[1]}

    def tangle(self, spacing=0.01, threshold=0):
        """The reduced model's manifolds at the scene's whole forcing, as `gomboc melnikov --tangle SPACING
        [--tangle-threshold N]`: "homoclinic_orbits" a fundamental domain crosses, "smallest_angle" [deg],
        "multipliers" of the period map, and with threshold = N > 0 bisections "threshold_A1", the A1 bracket where
        the manifolds start to cross."""
        if threshold != int(threshold) or not 0 <= threshold <= 30:
            raise GombocError(1, f"tangle threshold {threshold} (allowed: an integer from 0 to 30)")
        out = _ffi.new("double[6]")
        _check(_lib.gb_handle_scene_tangle(self._handle, float(spacing), int(threshold), out))
        result = {"homoclinic_orbits": int(out[0]), "smallest_angle": out[1], "multipliers": (out[2], out[3])}
        if threshold:
            result["threshold_A1"] = (out[4], out[5])
        return result

    def run(self, history=True, impacts=False):
        """Run the scene (the same bits as `gomboc run`); history: keep every sample; impacts: every impact."""
        out = _ffi.new("gb_handle_run **")
        _check(_lib.gb_handle_run_scene(self._handle, int(history), int(impacts), out))
        return Run(out[0])


class Run:
    """A finished run: `fingerprint` (state, switches) as `gomboc run` prints them, `values` by name, `history`
    and `impacts` as dicts of numpy arrays (empty when not kept)."""

    def __init__(self, handle):
        self._handle = _ffi.gc(handle, _lib.gb_handle_run_free)
        self.fingerprint = tuple(f"{_lib.gb_handle_run_fingerprint(self._handle, k):016x}" for k in (0, 1))
        self.values = {name: _lib.gb_handle_run_value(self._handle, name.encode())
                       for name in _names(_lib.gb_handle_values())}
        self.history = self._table(_lib.gb_handle_run_history, columns())
        self.impacts = self._table(_lib.gb_handle_run_impacts, impact_columns())

    def _table(self, getter, names):
        rows = _ffi.new("size_t *")
        data = getter(self._handle, rows)
        if rows[0] == 0:
            return {name: np.empty(0) for name in names}
        array = np.frombuffer(_ffi.buffer(data, rows[0] * len(names) * 8), dtype=np.float64).reshape(rows[0], len(names))
        array = array.copy()  # the run's memory is freed with it
        return {name: array[:, k] for k, name in enumerate(names)}


def load(path, overrides=None):
    """The scene in the case file `path`, with `overrides` ({"forcing.omega": 20, ...}) applied in order."""
    array, count, _keep = _overrides(overrides)
    out = _ffi.new("gb_handle_scene **")
    _check(_lib.gb_handle_scene_load(os.fsencode(path), array, count, out))
    return Scene(out[0])


def loads(text, overrides=None, name="scene"):
    """The scene in `text` (a case file's contents, or a dict {"section": {"key": value}}), named `name` in
    messages."""
    if isinstance(text, dict):
        text = "".join(f"[{section}]\n" + "".join(f"{k} = {v}\n" for k, v in keys.items()) for section, keys in text.items())
    array, count, _keep = _overrides(overrides)
    out = _ffi.new("gb_handle_scene **")
    _check(_lib.gb_handle_scene_text(name.encode(), text.encode(), array, count, out))
    return Scene(out[0])


def scan(path, threads=0, progress=None):
    """Run the scan file `path` as `gomboc scan` does (threads 0: one per processor) and return (csv, table): the CSV
    text, byte for byte the command's NAME-scan.csv, and its columns as a dict of numpy arrays (the fingerprints as
    strings). progress(phase, done, total, seconds), if given, hears the Melnikov margins' phase ("melnikov") and the
    points' ("points") from the scan's threads."""
    def hear(user, phase, done, total, seconds):
        try:
            progress("melnikov" if phase == 0 else "points", done, total, seconds)
        except Exception:  # a callback's error must not cross into C
            pass

    callback = _ffi.callback("gb_handle_progress", hear) if progress else _ffi.NULL
    out = _ffi.new("char **")
    _check(_lib.gb_handle_scan(os.fsencode(path), threads, callback, _ffi.NULL, out))
    try:
        text = _ffi.string(out[0]).decode()
    finally:
        _lib.gb_handle_text_free(out[0])
    lines = text.splitlines()
    names = lines[0].split(",")
    cells = [line.split(",") for line in lines[1:]]
    table = {}
    for k, name in enumerate(names):
        column = [row[k] for row in cells]
        try:
            table[name] = np.array([float(x) for x in column])
        except ValueError:
            table[name] = np.array(column)
    return text, table
