"""A pytest plugin for trimesh's own test suite: cudahull.ConvexHull in scipy's place, and a record of it all.

Loaded by ``run_trimesh_suite.py`` (``-p cudahull_trimesh_plugin``, this folder on PYTHONPATH); not a test
module and not a conftest, so python/tests' own pytest run never loads it.  Its environment variables:

``CUDAHULL_TRIMESH_SUITE_MODE``
    ``cudahull``: ``cudahull.ConvexHull`` is put in scipy's place before trimesh is imported, under every
    name trimesh can reach it by: ``scipy.spatial.ConvexHull``, ``scipy.spatial._qhull.ConvexHull`` and any
    module's ``ConvexHull`` bound to scipy's class (``from scipy.spatial import ConvexHull`` in
    ``trimesh.convex`` and ``trimesh.bounds``), swept again after collection and before each test so that
    modules imported late are caught too.  ``scipy`` (the baseline): nothing is replaced.
    In both modes the constructors of scipy's ConvexHull and of cudahull's are wrapped to count their
    calls (the wrapper only counts, then calls the original ``__init__``): in cudahull mode scipy's count
    splits into calls made by cudahull itself (4-D and higher, which cudahull hands to Qhull) and calls
    that escaped the swap (there must be none).  The run fails if cudahull's count is zero.
``CUDAHULL_TRIMESH_SUITE_SWAP``
    Where cudahull's class goes in cudahull mode.  ``everywhere`` (the default): as above.  ``trimesh``: only
    into trimesh's modules that bound scipy's (``trimesh.convex.ConvexHull``, ``trimesh.bounds.ConvexHull``),
    after trimesh is imported, as docs/python.md shows; scipy's own names are left as they are.
``CUDAHULL_TRIMESH_SUITE_REPORT``
    A JSON-lines file: one line per test (its outcome, how many ConvexHulls it made and how many of those
    raised, by exception class), written as the run goes (a run that is killed keeps what it finished),
    then one ``"summary"`` line.

trimesh itself is imported here, at configure time, before the tests' folder goes on sys.path: the tests
run against the installed trimesh (``trimesh.__file__`` is in the summary).
"""

import json
import os
import sys
import threading
import time
from collections import Counter

import pytest
import scipy.spatial
import scipy.spatial._qhull as _qhull

MODE = os.environ.get("CUDAHULL_TRIMESH_SUITE_MODE", "cudahull")
SWAP = os.environ.get("CUDAHULL_TRIMESH_SUITE_SWAP", "everywhere")
REPORT = os.environ.get("CUDAHULL_TRIMESH_SUITE_REPORT")

SCIPY_CONVEX_HULL = _qhull.ConvexHull  # scipy's own class, kept before anything is replaced

_local = threading.local()
_lock = threading.Lock()
STATS = {
    "cudahull_calls": 0,           # cudahull.ConvexHull constructed from outside cudahull
    "cudahull_reentrant_calls": 0,  # cudahull.ConvexHull constructed while one is already being built
    "scipy_calls_direct": 0,        # scipy's ConvexHull constructed from outside cudahull
    "scipy_calls_via_cudahull": 0,  # scipy's ConvexHull constructed by cudahull (4-D and higher)
    "swept_bindings": [],           # module.attribute names replaced
}
BY_KIND = Counter()       # (ndim, backend, qhull_options) of cudahull's calls
ERRORS = Counter()        # exception types raised by the constructors, by class
_per_test = Counter()     # calls made during the current test


def _depth():
    return getattr(_local, "depth", 0)


def _wrap_scipy():
    original = SCIPY_CONVEX_HULL.__init__

    def __init__(self, *args, **kwargs):
        key = "scipy_calls_via_cudahull" if _depth() > 0 else "scipy_calls_direct"
        with _lock:
            STATS[key] += 1
            _per_test[key] += 1
        try:
            original(self, *args, **kwargs)
        except BaseException as error:
            with _lock:
                ERRORS[f"scipy: {type(error).__module__}.{type(error).__qualname__}"] += 1
                _per_test[f"scipy raised {type(error).__qualname__}"] += 1
            raise

    __init__.__wrapped__ = original
    SCIPY_CONVEX_HULL.__init__ = __init__


def _wrap_cudahull(cudahull_hull):
    original = cudahull_hull.__init__

    def __init__(self, *args, **kwargs):
        depth = _depth()
        key = "cudahull_calls" if depth == 0 else "cudahull_reentrant_calls"
        with _lock:
            STATS[key] += 1
            _per_test[key] += 1
        _local.depth = depth + 1
        try:
            original(self, *args, **kwargs)
        except BaseException as error:
            if depth == 0:
                with _lock:
                    ERRORS[f"cudahull: {type(error).__module__}.{type(error).__qualname__}"] += 1
                    _per_test[f"cudahull raised {type(error).__qualname__}"] += 1
            raise
        finally:
            _local.depth = depth
        if depth == 0:
            options = kwargs.get("qhull_options", args[2] if len(args) > 2 else None)
            with _lock:
                BY_KIND[f"{getattr(self, 'ndim', '?')}-D, backend {getattr(self, 'backend', '?')!r}, "
                        f"qhull_options {options!r}"] += 1

    __init__.__wrapped__ = original
    cudahull_hull.__init__ = __init__


def _swept(name):
    if name == "cudahull" or name.startswith("cudahull."):
        return False
    return SWAP == "everywhere" or name == "trimesh" or name.startswith("trimesh.")


def sweep(replacement):
    """Every module's ConvexHull that is scipy's class, replaced (cudahull's own modules left alone; with
    CUDAHULL_TRIMESH_SUITE_SWAP=trimesh, trimesh's modules only)."""
    for name, module in list(sys.modules.items()):
        if module is None or not _swept(name):
            continue
        try:
            namespace = vars(module)
        except TypeError:
            continue
        if namespace.get("ConvexHull") is SCIPY_CONVEX_HULL:
            setattr(module, "ConvexHull", replacement)
            STATS["swept_bindings"].append(f"{name}.ConvexHull")


_replacement = None
_current = None  # the running test: its nodeid, its phases' outcomes, its failure's or skip's message


def pytest_configure(config):
    global _replacement
    _wrap_scipy()
    if MODE == "cudahull":
        import cudahull

        _wrap_cudahull(cudahull.ConvexHull)
        _replacement = cudahull.ConvexHull
        if SWAP == "everywhere":
            scipy.spatial.ConvexHull = cudahull.ConvexHull
            _qhull.ConvexHull = cudahull.ConvexHull
            STATS["swept_bindings"] += ["scipy.spatial.ConvexHull", "scipy.spatial._qhull.ConvexHull"]
            sweep(_replacement)
        elif SWAP != "trimesh":
            raise pytest.UsageError(f"CUDAHULL_TRIMESH_SUITE_SWAP must be 'everywhere' or 'trimesh', not {SWAP!r}")
    elif MODE != "scipy":
        raise pytest.UsageError(f"CUDAHULL_TRIMESH_SUITE_MODE must be 'scipy' or 'cudahull', not {MODE!r}")
    # trimesh imported now (and all its modules that bind ConvexHull), from site-packages: the tests' rootdir
    # is not on sys.path yet.
    import trimesh
    import trimesh.bounds  # noqa: F401
    import trimesh.convex  # noqa: F401

    if _replacement is not None:
        sweep(_replacement)
    if REPORT:
        open(REPORT, "w").close()
    config._cudahull_trimesh_started = time.time()


def pytest_collection_finish(session):
    if _replacement is not None:
        sweep(_replacement)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    global _current
    if _replacement is not None:
        sweep(_replacement)
    _per_test.clear()
    _current = {"nodeid": item.nodeid, "phases": {}}
    started = time.time()
    yield
    record = {"nodeid": item.nodeid, "outcome": _outcome(_current["phases"]),
              "seconds": round(time.time() - started, 3), "hulls": dict(_per_test)}
    if _current.get("message"):
        record["message"] = _current["message"]
    _current = None
    _write(record)


def _outcome(phases):
    if any(p == "failed" for w, p in phases.items() if w != "call"):
        return "error"
    if phases.get("call") == "failed":
        return "failed"
    if "xfailed" in phases.values():
        return "xfailed"
    if "xpassed" in phases.values():
        return "xpassed"
    if "skipped" in phases.values():
        return "skipped"
    if phases.get("call") == "passed":
        return "passed"
    return "unknown"


def pytest_runtest_logreport(report):
    if _current is None or report.nodeid != _current["nodeid"]:
        return
    if hasattr(report, "wasxfail"):
        outcome = "xfailed" if report.skipped else "xpassed"
    else:
        outcome = report.outcome
    _current["phases"][report.when] = outcome
    if report.failed:
        text = str(report.longrepr)
        lines = [line for line in text.splitlines() if line.startswith("E ")]
        _current["message"] = f"{report.when}: " + (" | ".join(lines[-3:]) if lines else text[-300:])
    elif report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        _current["message"] = f"skip: {reason}"


def pytest_collectreport(report):
    # a test module that cannot be imported (trimesh's optional dependencies): one record, "collection error"
    if report.failed:
        text = str(report.longrepr)
        lines = [line for line in text.splitlines() if line.startswith("E ")]
        _write({"nodeid": report.nodeid, "outcome": "collection error", "seconds": 0, "hulls": {},
                "message": "collect: " + (" | ".join(lines[-3:]) if lines else text[-300:])})


def _write(record):
    if REPORT:
        with open(REPORT, "a") as stream:
            stream.write(json.dumps(record) + "\n")


def _summary(config):
    import numpy
    import trimesh

    summary = dict(STATS)
    summary["swept_bindings"] = sorted(set(STATS["swept_bindings"]))
    # every module's ConvexHull that is cudahull's now: replaced by the sweep, or bound to it at import
    summary["cudahull_bindings"] = sorted(
        f"{name}.ConvexHull" for name, module in list(sys.modules.items())
        if module is not None and _replacement is not None and isinstance(getattr(module, "__dict__", None), dict)
        and vars(module).get("ConvexHull") is _replacement and _swept(name))
    summary.update({
        "summary": True, "mode": MODE, "swap": SWAP if MODE == "cudahull" else None,
        "trimesh_version": trimesh.__version__, "trimesh_file": trimesh.__file__,
        "scipy_version": scipy.__version__, "numpy_version": numpy.__version__, "python": sys.version.split()[0],
        "cudahull_by_kind": dict(BY_KIND), "constructor_errors": dict(ERRORS),
        "seconds": round(time.time() - getattr(config, "_cudahull_trimesh_started", time.time()), 1),
    })
    if MODE == "cudahull":
        import cudahull

        summary["cudahull_file"] = cudahull.__file__
    return summary


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    summary = _summary(config)
    write = terminalreporter.write_line
    terminalreporter.section(f"ConvexHull calls ({MODE} mode)")
    write(f"trimesh {summary['trimesh_version']} from {summary['trimesh_file']}")
    if MODE == "cudahull":
        write(f"cudahull.ConvexHull calls: {summary['cudahull_calls']} (from {summary['cudahull_file']})")
        for kind, count in sorted(BY_KIND.items(), key=lambda kv: -kv[1]):
            write(f"    {count:6d}  {kind}")
        write(f"scipy ConvexHull calls made by cudahull (4-D and higher): {summary['scipy_calls_via_cudahull']}")
        write(f"scipy ConvexHull calls that escaped the swap: {summary['scipy_calls_direct']}")
        write(f"swap: {SWAP}; names replaced: {', '.join(summary['swept_bindings']) or 'none'}; names now "
              f"bound to cudahull's class: {', '.join(summary['cudahull_bindings'])}")
    else:
        write(f"scipy ConvexHull calls: {summary['scipy_calls_direct']}")
    if ERRORS:
        write(f"constructors' exceptions: {dict(ERRORS)}")


_exitstatus = None


def pytest_sessionfinish(session, exitstatus):
    global _exitstatus
    summary = _summary(session.config)
    summary["pytest_exitstatus"] = int(exitstatus)
    if MODE == "cudahull" and summary["cudahull_calls"] == 0:
        sys.stderr.write("cudahull_trimesh_plugin: cudahull.ConvexHull was never called: the swap did not work\n")
        session.exitstatus = 3
    summary["threads_left"] = [thread.name for thread in _threads_left()]
    _write(summary)
    _exitstatus = int(session.exitstatus)


def _threads_left():
    return [thread for thread in threading.enumerate()
            if thread is not threading.main_thread() and thread.is_alive() and not thread.daemon]


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    # trimesh's tests/generic.py serve_meshes() starts a non-daemon HTTP server thread and stops it only when
    # its with-block ends normally: a test that fails inside it (httpx not installed) leaves the thread
    # serving, and the interpreter would wait for it forever at exit.  Such threads are named, and the
    # process ends without waiting for them.
    threads = _threads_left()
    if threads and _exitstatus is not None:
        sys.stdout.write(f"cudahull_trimesh_plugin: non-daemon threads left running by the tests "
                         f"({', '.join(thread.name for thread in threads)}): exiting without joining them\n")
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(_exitstatus)
