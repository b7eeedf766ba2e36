"""faultmesh from Python: a whole remesh run through the shared library.

    import faultmesh
    res = faultmesh.remesh(["a.ts", "b.ts"], size=1000)
    for f in res.faults:
        print(f.name, f.status, len(f.points), len(f.triangles))
    res.report["summary"]          # report.json, parsed
    import meshio
    meshio.Mesh(res.faults[0].points, [("triangle", res.faults[0].triangles)])

The package is ctypes over libfaultmesh.so (no compiled extension),
found through $FAULTMESH_LIBRARY, the install prefix it was installed
into, the build tree beside the source tree, or the dynamic loader.
numpy arrays come out; the library's own arrays are copied, so the
result owns nothing the library frees.
"""

import ctypes
import json
import os
import shutil
import tempfile
import threading

import numpy as np

from . import _lib

__all__ = ["remesh", "Result", "Fault", "FaultmeshError", "OPTIONS", "FORMATS", "version"]

_L = None


def _lib_handle():
    global _L
    if _L is None:
        _L = _lib.load()
    return _L


def version():
    """The library's version string."""
    return _lib_handle().fm_version_string().decode()


class FaultmeshError(RuntimeError):
    """A run that could not go on (fm_status and the library's message)."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


# FM_OUT_* (fm_run.h)
FORMATS = {
    "vtu": 1 << 0, "msh": 1 << 1, "stl": 1 << 2, "obj": 1 << 3, "exo": 1 << 4,
    "ts": 1 << 5, "igs": 1 << 6, "rsqsim": 1 << 7, "eqsim": 1 << 8, "html": 1 << 9,
    "names": 1 << 10,
}
FORMATS_ALL = (1 << 11) - 1

_TOP = {"cut": 0, "keep": 1, "extend": 2}
_KEEP = {"smaller": 0, "larger": 1}
_MSH = {"4.1": 0, "2.2": 1}
_TAGS = {"default": 0, "tandem": 1, "seissol": 2, "pylith": 3}
_EQSIM = {"spherical": 0, "rectangular": 1}

# keyword: (fm_run_option, kind, names of an int option's values)
OPTIONS = {
    "size": (100, float, None),
    "top": (101, int, _TOP),
    "top_extend": (102, float, None),
    "sea_level": (103, float, None),
    "connect": (200, bool, None),
    "join_distance": (201, float, None),
    "keep": (202, int, _KEEP),
    "carve": (203, bool, None),
    "max_triangles": (204, int, None),
    "threads": (300, int, None),
    "crs": (400, str, None),
    "crs_out": (401, str, None),
    "cache_dir": (402, str, None),
    "cache": (403, bool, None),
    "msh_version": (500, int, _MSH),
    "msh_tags": (501, int, _TAGS),
    "formats": (502, int, None),
    "report_html": (503, bool, None),
    "quads": (504, bool, None),
    "slip": (600, str, None),
    "metadata": (601, str, None),
    "eqsim_coords": (602, int, _EQSIM),
    "kinematics": (603, str, None),
    "kinematics_distance": (604, float, None),
    "kinematics_fallback": (605, float, None),
}

LOG_ERROR, LOG_WARN, LOG_INFO, LOG_DETAIL = 1, 2, 3, 4


def _formats_mask(formats):
    if isinstance(formats, int):
        return formats
    mask = 0
    for name in formats:
        if name not in FORMATS:
            raise ValueError("unknown format %r (one of %s)" % (name, ", ".join(FORMATS)))
        mask |= FORMATS[name]
    return mask


def _check(st, err):
    if st != 0:
        msg = err.message.decode(errors="replace")
        name = _lib_handle().fm_status_string(st).decode()
        raise FaultmeshError(st, msg or name)


class Fault:
    """One fault of a result: its mesh (own vertex numbering) and outcome.

    points (n, 3) float64 x east, y north, z up (m); triangles (m, 3) int32
    into points; vertices: each point's index in the result's whole mesh
    (Result.points), which is how two faults' shared nodes are found."""

    def __init__(self, index, name, status, why, points, triangles, vertices):
        self.index = index
        self.name = name
        self.status = status
        self.why = why
        self.points = points
        self.triangles = triangles
        self.vertices = vertices

    def to_meshio(self):
        import meshio

        return meshio.Mesh(self.points, [("triangle", self.triangles)])

    def __repr__(self):
        return "Fault(%r, %s, %d points, %d triangles)" % (
            self.name, self.status, len(self.points), len(self.triangles))


class Result:
    """What a run came to.

    faults: list of Fault in input order; points, triangles,
    fault_of_triangle: every fault in one mesh, nodes where faults meet
    shared; report: report.json as a dict; summary: the text
    `faultmesh remesh` prints; messages: the log records (level, text);
    out: the folder written (None when none was asked for)."""

    def __init__(self, faults, points, triangles, fault_of_triangle, report, summary,
                 messages, nfailed, out):
        self.faults = faults
        self.points = points
        self.triangles = triangles
        self.fault_of_triangle = fault_of_triangle
        self.report = report
        self.summary = summary
        self.messages = messages
        self.nfailed = nfailed
        self.out = out

    def fault(self, key):
        """A fault by index or by name."""
        if isinstance(key, int):
            return self.faults[key]
        for f in self.faults:
            if f.name == key:
                return f
        raise KeyError(key)

    def shared_nodes(self, a, b):
        """Indices into points of the nodes faults a and b (index or
        name) both use."""
        return np.intersect1d(self.fault(a).vertices, self.fault(b).vertices)

    def to_meshio(self):
        """The whole set, the fault index of each triangle as cell data."""
        import meshio

        return meshio.Mesh(self.points, [("triangle", self.triangles)],
                           cell_data={"fault": [self.fault_of_triangle]})


def _set_option(L, run, key, value, err):
    if key not in OPTIONS:
        raise TypeError("unknown option %r (one of %s)" % (key, ", ".join(OPTIONS)))
    opt, kind, names = OPTIONS[key]
    if key == "kinematics":
        values = [value] if isinstance(value, (str, os.PathLike)) or value is None else value
        for v in values:
            _check(L.fm_run_set_string(run, opt, None if v is None else os.fsencode(v), err),
                   err)
        return
    if key == "formats":
        value = _formats_mask(value)
    if names is not None and isinstance(value, str):
        if value not in names:
            raise ValueError("%s: %r is not one of %s" % (key, value, ", ".join(names)))
        value = names[value]
    if kind is float:
        st = L.fm_run_set_double(run, opt, float(value), err)
    elif kind is str:
        st = L.fm_run_set_string(run, opt, None if value is None else os.fsencode(value), err)
    else:
        st = L.fm_run_set_int(run, opt, int(value), err)
    _check(st, err)


def _add_input(L, run, item, err):
    """A path, or an in-memory fault: (name, points, triangles), or an
    object with name, points and triangles (a Fault of a result)."""
    if isinstance(item, (str, os.PathLike)):
        _check(L.fm_run_add_path(run, os.fsencode(item), err), err)
        return
    if isinstance(item, tuple) and len(item) == 3:
        name, points, triangles = item
    else:
        name, points, triangles = item.name, item.points, item.triangles
    # contiguous copies of the library's types: it copies them in turn
    pts = np.ascontiguousarray(points, dtype=np.float64)
    tri = np.ascontiguousarray(triangles, dtype=np.int32)
    if pts.ndim != 2 or pts.shape[1] != 3 or tri.ndim != 2 or tri.shape[1] != 3:
        raise ValueError("%s: points must be (n, 3), triangles (m, 3)" % name)
    _check(L.fm_run_add_mesh(run, str(name).encode(), pts.ctypes.data_as(_lib.c_double_p),
                             len(pts), tri.ctypes.data_as(_lib.c_int32_p), len(tri), err), err)


def remesh(paths, size=1000, out=None, log=None, progress=None, **options):
    """Remeshes the faults in paths at size (m): TSurf files, folders of
    them, or faults in memory as (name, points, triangles) with points
    (n, 3) x east, y north, z up in m and triangles (m, 3) indices from 0.

    options: the keywords of OPTIONS (connect, join_distance, top, threads,
    cache, crs, formats, ...), as `faultmesh remesh` takes them. out: a
    folder to write the outputs (formats, default all) and report.json
    into; without it only report.json is made, in a temporary folder, and
    read back. log(level, message): the run's records (kept in
    Result.messages as well). progress(stage, done, count): returning True
    cancels. Ctrl-C cancels the run (KeyboardInterrupt). Raises
    FaultmeshError when the run cannot go on; a fault that fails is in the
    result (status "error", why)."""
    L = _lib_handle()
    if isinstance(paths, (str, os.PathLike)) or (isinstance(paths, tuple) and len(paths) == 3
                                                   and isinstance(paths[0], str)):
        paths = [paths]
    err = _lib.Error()
    run = L.fm_run_create(None)
    if not run:
        raise MemoryError("fm_run_create")
    res = ctypes.c_void_p()
    messages = []
    failure = []
    stage = [""]

    def on_log(user, level, message):
        text = message.decode(errors="replace")
        messages.append((level, text))
        if log is not None:
            try:
                log(level, text)
            except BaseException as e:  # noqa: B902 -- said after the run
                failure.append(e)

    def on_progress(user, p):
        ev = p.contents
        if ev.event == 1 and ev.stage:
            stage[0] = ev.stage.decode(errors="replace")
        if progress is None or failure:
            return 1 if failure else 0
        try:
            return 1 if progress(stage[0], ev.done, ev.count) else 0
        except BaseException as e:  # noqa: B902 -- a callback's exception cancels
            failure.append(e)
            return 1

    # kept alive as long as the run may call them
    log_cb = _lib.LOG_FN(on_log)
    progress_cb = _lib.PROGRESS_FN(on_progress)
    tmp = None
    try:
        L.fm_run_set_log(run, LOG_INFO, log_cb, None)
        L.fm_run_set_progress(run, progress_cb, None)
        if out is None:
            # nothing is written but report.json: the cheapest format, and
            # no CAD faces or report.html made for nothing
            options.setdefault("formats", FORMATS["vtu"])
            options.setdefault("report_html", False)
        options["size"] = size
        for key, value in options.items():
            _set_option(L, run, key, value, err)
        for p in paths:
            _add_input(L, run, p, err)
        status = [None]

        def execute():
            status[0] = L.fm_run_execute(run, ctypes.byref(res), err)

        # in a thread of its own, so that Ctrl-C reaches the main thread,
        # which then interrupts the run
        t = threading.Thread(target=execute, name="faultmesh run")
        t.start()
        try:
            while t.is_alive():
                t.join(0.1)
        except KeyboardInterrupt:
            L.fm_run_interrupt(run)
            t.join()
            raise
        if failure:
            raise failure[0]
        _check(status[0], err)

        n = L.fm_run_result_nfaults(res)
        nv = L.fm_run_result_nvertices(res)
        nt = L.fm_run_result_ntriangles(res)
        points = np.zeros((nv, 3), dtype=np.float64)
        triangles = np.zeros((nt, 3), dtype=np.int32)
        fault_of = np.zeros(nt, dtype=np.int32)
        _check(L.fm_run_result_copy_mesh(
            res, points.ctypes.data_as(_lib.c_double_p),
            triangles.ctypes.data_as(_lib.c_int32_p),
            fault_of.ctypes.data_as(_lib.c_int32_p), err), err)
        faults = []
        order = np.argsort(fault_of, kind="stable")
        bounds = np.searchsorted(fault_of[order], np.arange(n + 1))
        for i in range(n):
            why = ctypes.c_char_p()
            status_i = L.fm_run_result_fault_status(res, i, ctypes.byref(why))
            tris = triangles[order[bounds[i]:bounds[i + 1]]]
            used = np.unique(tris)
            local = np.searchsorted(used, tris).astype(np.int32)
            faults.append(Fault(
                i, L.fm_run_result_fault_name(res, i).decode(errors="replace"),
                status_i.decode(), why.value.decode(errors="replace") if why.value else None,
                points[used], local, used))

        if out is None:
            tmp = tempfile.mkdtemp(prefix="faultmesh-")
            where, formats = tmp, 0
        else:
            os.makedirs(out, exist_ok=True)
            where = os.fspath(out)
            formats = _formats_mask(options.get("formats", FORMATS_ALL))
        where_b = os.fsencode(where)
        _check(L.fm_run_result_write(res, where_b, formats, err), err)
        with open(os.path.join(where, "report.json"), encoding="utf-8") as fp:
            report = json.load(fp)
        text = L.fm_run_result_summary(res)
        summary = ctypes.string_at(text).decode(errors="replace") if text else ""
        L.fm_free(text)
        if failure:
            raise failure[0]
        return Result(faults, points, triangles, fault_of, report, summary, messages,
                      L.fm_run_result_nfailed(res), out)
    finally:
        L.fm_run_result_destroy(res)
        L.fm_run_destroy(run)
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
