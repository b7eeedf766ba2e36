"""The shared library and the prototypes of its API (fm_*.h, FM_API).

ctypes checks nothing against the headers: a wrong prototype is silent
memory corruption. So every function the package calls is declared here,
in one table, and tests/tools/symbols_test.sh checks that the table names
exactly the functions the public headers mark FM_API.
"""

import ctypes
import ctypes.util
import os

# The version of the API this package was written for (FM_VERSION_NUMBER).
API_VERSION = 100  # 0.1.0
SONAME = "libfaultmesh.so.0"

c_int32_p = ctypes.POINTER(ctypes.c_int32)
c_double_p = ctypes.POINTER(ctypes.c_double)


class Error(ctypes.Structure):
    """fm_error (fm_status.h): its layout is part of the ABI."""

    _fields_ = [
        ("code", ctypes.c_int),
        ("line", ctypes.c_long),
        ("message", ctypes.c_char * 768),
    ]


class Progress(ctypes.Structure):
    """fm_progress (fm_run.h)."""

    _fields_ = [
        ("event", ctypes.c_int),
        ("stage", ctypes.c_char_p),
        ("done", ctypes.c_size_t),
        ("count", ctypes.c_size_t),
        ("unit", ctypes.c_char_p),
        ("weight", ctypes.c_double),
    ]


LOG_FN = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int, ctypes.c_char_p)
PROGRESS_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(Progress))
c_int_p = ctypes.POINTER(ctypes.c_int)
# fm_option_fn: (user, argc, argv, &i, err) -> 1 taken, 0 not known, -1 bad value
OPTION_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int,
                             ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_int),
                             ctypes.c_void_p)

_p = ctypes.c_void_p
_err = ctypes.POINTER(Error)
_size = ctypes.c_size_t
_str = ctypes.c_char_p
_status = ctypes.c_int

# name: (restype, argtypes)
PROTOTYPES = {
    "fm_version_number": (ctypes.c_int, []),
    "fm_version_string": (_str, []),
    "fm_status_string": (_str, [_status]),
    "fm_error_clear": (None, [_err]),
    "fm_free": (None, [_p]),
    "fm_run_create": (_p, [_p]),
    "fm_run_destroy": (None, [_p]),
    "fm_run_set_log": (None, [_p, ctypes.c_int, LOG_FN, _p]),
    "fm_run_set_progress": (None, [_p, PROGRESS_FN, _p]),
    "fm_run_interrupt": (None, [_p]),
    "fm_run_set_int": (_status, [_p, ctypes.c_int, ctypes.c_int64, _err]),
    "fm_run_set_double": (_status, [_p, ctypes.c_int, ctypes.c_double, _err]),
    "fm_run_set_string": (_status, [_p, ctypes.c_int, _str, _err]),
    "fm_run_option_bounds": (_status, [ctypes.c_int, c_double_p, c_double_p]),
    "fm_run_add_path": (_status, [_p, _str, _err]),
    "fm_run_add_mesh": (_status, [_p, _str, c_double_p, _size, c_int32_p, _size, _err]),
    "fm_run_prepare": (_status, [_p, ctypes.POINTER(_str), _size, _err]),
    "fm_run_execute": (_status, [_p, ctypes.POINTER(_p), _err]),
    "fm_run_result_destroy": (None, [_p]),
    "fm_run_result_nfaults": (_size, [_p]),
    "fm_run_result_nfailed": (_size, [_p]),
    "fm_run_result_fault_name": (_str, [_p, _size]),
    "fm_run_result_fault_status": (_str, [_p, _size, ctypes.POINTER(_str)]),
    "fm_run_result_nvertices": (_size, [_p]),
    "fm_run_result_ntriangles": (_size, [_p]),
    "fm_run_result_copy_mesh": (_status, [_p, c_double_p, c_int32_p, c_int32_p, _err]),
    "fm_run_result_write": (_status, [_p, _str, ctypes.c_uint, _err]),
    "fm_run_result_unwritten": (_size, [_p]),
    # malloc'ed text: a plain pointer, so that fm_free gets it back
    "fm_run_result_summary": (_p, [_p]),
    # options in the command line's words, settings files, inputs
    "fm_run_take_option": (ctypes.c_int, [_p, ctypes.c_int, ctypes.POINTER(_str), c_int_p, _err]),
    "fm_run_set_option": (_status, [_p, _str, _str, _err]),
    "fm_run_read_settings": (_status, [_p, _str, OPTION_FN, _p, _err]),
    "fm_run_settings_ninputs": (_size, [_p]),
    "fm_run_settings_input": (_str, [_p, _size]),
    "fm_run_settings_path": (_str, [_p]),
    "fm_run_check_options": (_status, [_p, _err]),
    "fm_run_get_int": (_status, [_p, ctypes.c_int, ctypes.POINTER(ctypes.c_int64)]),
    "fm_run_list_inputs": (ctypes.c_long, [ctypes.POINTER(_str), _size, LOG_FN, _p,
                                           ctypes.POINTER(ctypes.POINTER(_str)), _err]),
    "fm_run_list_free": (None, [ctypes.POINTER(_str), ctypes.c_long]),
    "fm_run_check_output_dir": (_status, [_str, ctypes.POINTER(_str), _size,
                                          ctypes.POINTER(_str), _size, _err]),
    # faultmesh info and fit (FILE * streams: a plain pointer)
    "fm_info_create": (_p, []),
    "fm_info_destroy": (None, [_p]),
    "fm_info_take_option": (ctypes.c_int, [_p, ctypes.c_int, ctypes.POINTER(_str), c_int_p, _err]),
    "fm_info_set_log": (None, [_p, LOG_FN, _p]),
    "fm_info_write": (_size, [_p, ctypes.POINTER(_str), _size, _p]),
    "fm_fit_job_create": (_p, []),
    "fm_fit_job_destroy": (None, [_p]),
    "fm_fit_job_take_option": (ctypes.c_int, [_p, ctypes.c_int, ctypes.POINTER(_str), c_int_p,
                                              _err]),
    "fm_fit_job_set_log": (None, [_p, LOG_FN, _p]),
    "fm_fit_job_write": (_status, [_p, _str, ctypes.POINTER(_str), _size, _p,
                                   ctypes.POINTER(_size), _err]),
    # the synthetic fault system
    "fm_synth_spec_create": (_p, []),
    "fm_synth_spec_destroy": (None, [_p]),
    "fm_synth_spec_take_option": (ctypes.c_int, [_p, ctypes.c_int, ctypes.POINTER(_str), c_int_p,
                                                 _err]),
    "fm_synth_generate": (_status, [_p, ctypes.POINTER(_p), _err]),
    "fm_synth_destroy": (None, [_p]),
    "fm_synth_nfaults": (_size, [_p]),
    "fm_synth_fault_name": (_str, [_p, _size]),
    "fm_synth_fault_description": (_str, [_p, _size]),
    "fm_synth_write": (_status, [_p, _str, _err]),
    # once per process
    "fm_remove_pending_files": (None, []),
    "fm_make_dirs": (_status, [_str, _err]),
    "fm_report_cleanup": (None, []),
}


def _candidates():
    """Where the library may be, first found first taken."""
    env = os.environ.get("FAULTMESH_LIBRARY")
    if env:
        yield env
        return
    here = os.path.dirname(os.path.abspath(__file__))
    try:  # an installed package: made by CMake beside this file
        from . import _config

        yield os.path.normpath(os.path.join(here, _config.LIBDIR_FROM_PACKAGE, _config.SONAME))
    except ImportError:
        pass
    # the source tree's python/faultmesh: the build tree beside it
    root = os.path.dirname(os.path.dirname(here))
    build = os.environ.get("FAULTMESH_BUILD", os.path.join(root, "build"))
    yield os.path.join(build, "lib", SONAME)
    found = ctypes.util.find_library("faultmesh")
    if found:
        yield found
    yield SONAME  # the dynamic loader's own search (LD_LIBRARY_PATH, ld.so.cache)


def load():
    """The library with every prototype set; OSError when none is found."""
    tried = []
    lib = None
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path)
            continue
        try:
            lib = ctypes.CDLL(path)
            break
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    if lib is None:
        raise OSError(
            "libfaultmesh not found (set FAULTMESH_LIBRARY to its path); tried: "
            + "; ".join(tried)
        )
    for name, (res, args) in PROTOTYPES.items():
        f = getattr(lib, name)
        f.restype = res
        f.argtypes = args
    v = lib.fm_version_number()
    if v // 100 != API_VERSION // 100:
        raise OSError(
            "libfaultmesh %s is not the version this package was written for (%d)"
            % (lib.fm_version_string().decode(), API_VERSION)
        )
    return lib
