#!/usr/bin/env python3
"""trimesh's own test suite, run twice: on scipy's ConvexHull (the baseline) and with cudahull.ConvexHull in
scipy's place; then the two runs compared, test by test (issue 42: "a library that calls scipy's ConvexHull
passes its whole test suite with cudahull in scipy's place").  Results for trimesh 4.8.3:
docs/data/trimesh_suite_4.8.3.txt.

trimesh's tests are not vendored here: pass the folder of a trimesh source tree at the installed version
(its ``tests/`` and ``models/``; the versions are checked), e.g. extracted from git at tag 4.8.3::

    git clone https://github.com/mikedh/trimesh && git -C trimesh archive 4.8.3 | tar -x -C /tmp/trimesh-src
    # (or, from a bare mirror: git --git-dir=REPO archive 4.8.3 | tar -x -C /tmp/trimesh-src)

Run, from the repository's root, with the Python that has trimesh, scipy and pytest and cudahull importable::

    PYTHONPATH=build/python build-venv/bin/python python/tests/trimesh_suite/run_trimesh_suite.py \\
        /tmp/trimesh-src --out /tmp/trimesh-suite --results /tmp/trimesh-suite/results.txt

Options: ``--runs scipy`` or ``--runs cudahull`` for one run only (the other's report, if already in
``--out``, is still compared); ``--swap trimesh`` to put cudahull's class only where trimesh bound scipy's
(``trimesh.convex``, ``trimesh.bounds``: docs/python.md's recipe) instead of in scipy's own names too;
``--files test_convex.py test_bounds.py ...`` for some of tests/ only (default: every tests/test_*.py);
``--timeout`` seconds per run; arguments after ``--`` go to pytest.

trimesh's optional dependencies: without them (as in build-venv, which has numpy and scipy only) about a
third of trimesh's tests fail alike in both runs on ``ModuleNotFoundError`` (trimesh's tests fail rather
than skip) and reach no hull.  For the fuller run, install trimesh's "easy" extras outside the venv and put
them first on PYTHONPATH (``--no-deps``: the venv's numpy and scipy stay the ones used; typing-extensions,
which ``referencing`` needs, is not in every venv, and without it jsonschema's import fails in both runs)::

    build-venv/bin/python -m pip install --target /tmp/trimesh-extras --no-deps colorlog manifold3d \\
        charset-normalizer lxml jsonschema jsonschema-specifications referencing rpds-py attrs networkx \\
        svg.path pycollada python-dateutil six shapely xxhash rtree httpx httpcore anyio h11 idna certifi \\
        sniffio pillow embreex vhacdx mapbox_earcut pyinstrument typing-extensions
    PYTHONPATH=/tmp/trimesh-extras:build/python build-venv/bin/python python/tests/trimesh_suite/...

Each run is ``python -m pytest -p cudahull_trimesh_plugin <trimesh-src>/tests/...`` in its own process, from
``--out`` (not from the source tree, so that the installed trimesh is the one imported: the plugin imports it
before the tests' folder goes on sys.path, and the summary names its file).  cudahull_trimesh_plugin.py (this
folder) says how the swap is made and counted.  The output per run: ``<out>/<run>.log`` (pytest's) and
``<out>/<run>.jsonl`` (one line a test, and a summary line).

Exit status 0 when cudahull was called, no scipy call escaped the swap, no test's outcome differs between
the runs, and both runs finished; 1 otherwise (the differing tests listed).  Neither file here is collected
by python/tests' pytest run (no ``test_`` prefix, no conftest).
"""

import argparse
import glob
import json
import os
import platform
import re
import signal
import subprocess
import sys
import time
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))
PLUGIN = "cudahull_trimesh_plugin"
RUNS = ("scipy", "cudahull")


def stem(run, args):
    """The run's file names in --out: the cudahull run's say which swap it made."""
    return run if run == "scipy" or args.swap == "everywhere" else f"{run}-swap-{args.swap}"


def source_version(src):
    with open(os.path.join(src, "pyproject.toml")) as stream:
        match = re.search(r'^version\s*=\s*"([^"]+)"', stream.read(), re.MULTILINE)
    return match.group(1) if match else None


def installed_version(python):
    return subprocess.run([python, "-c", "import trimesh; print(trimesh.__version__)"], capture_output=True,
                          text=True, check=True, cwd="/").stdout.strip()


def run_suite(run, args, test_paths):
    report = os.path.join(args.out, f"{stem(run, args)}.jsonl")
    log = os.path.join(args.out, f"{stem(run, args)}.log")
    env = dict(os.environ)
    # absolute: the run's working folder is --out
    env["PYTHONPATH"] = os.pathsep.join([HERE] + [os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(
        os.pathsep) if p])
    env.setdefault("PYTHONDONTWRITEBYTECODE", "1")  # no __pycache__ beside the plugin in the source tree
    env["CUDAHULL_TRIMESH_SUITE_MODE"] = run
    env["CUDAHULL_TRIMESH_SUITE_SWAP"] = args.swap
    env["CUDAHULL_TRIMESH_SUITE_REPORT"] = report
    command = [args.python, "-m", "pytest", "-p", PLUGIN, "-p", "no:cacheprovider", "--rootdir", args.src,
               "-o", "faulthandler_timeout=600", "--continue-on-collection-errors", "-q", "-rfE", *test_paths,
               *args.pytest_args]
    print(f"[{run}] {' '.join(command)}", flush=True)
    started = time.time()
    with open(log, "w") as stream:
        process = subprocess.Popen(command, cwd=args.out, env=env, stdout=stream, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        try:
            returncode = process.wait(timeout=args.timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            returncode = None
    seconds = time.time() - started
    print(f"[{run}] exit {returncode} after {seconds:.0f} s; log {log}", flush=True)
    return {"returncode": returncode, "seconds": seconds, "command": command}


def load(report):
    tests, summary = {}, None
    if not os.path.exists(report):
        return tests, summary
    with open(report) as stream:
        for line in stream:
            record = json.loads(line)
            if record.get("summary"):
                summary = record
            else:
                tests[record["nodeid"]] = record
    return tests, summary


def short(nodeid):
    return nodeid.split("/tests/", 1)[-1]


def compare(args, runs):
    data = {run: load(os.path.join(args.out, f"{stem(run, args)}.jsonl")) for run in RUNS}
    lines, problems = [], []
    for run in RUNS:
        tests, summary = data[run]
        counts = Counter(record["outcome"] for record in tests.values())
        text = ", ".join(f"{counts[o]} {o}" for o in ("passed", "failed", "error", "skipped", "xfailed",
                                                       "xpassed", "collection error", "unknown") if counts[o])
        timing = runs.get(run, {}).get("seconds")
        lines.append(f"{run:9s}: {len(tests)} tests and uncollectable modules: {text}"
                     + (f"; {timing:.0f} s wall" if timing else ""))
        if summary is None:
            problems.append(f"the {run} run did not finish (no summary line in {stem(run, args)}.jsonl)")
            continue
        if run == "scipy":
            lines.append(f"           scipy ConvexHull constructed {summary['scipy_calls_direct']} times")
        else:
            lines.append(f"           swap: {summary['swap']}; names bound to cudahull's class: "
                         f"{', '.join(summary['cudahull_bindings'])}")
            lines.append(f"           cudahull.ConvexHull constructed {summary['cudahull_calls']} times "
                         f"(scipy's by cudahull, 4-D and higher: {summary['scipy_calls_via_cudahull']}; "
                         f"scipy's escaping the swap: {summary['scipy_calls_direct']})")
            for kind, count in sorted(summary["cudahull_by_kind"].items(), key=lambda kv: -kv[1]):
                lines.append(f"             {count:6d}  {kind}")
            if summary["cudahull_calls"] == 0:
                problems.append("cudahull.ConvexHull was never called")
            if summary["scipy_calls_direct"]:
                problems.append(f"{summary['scipy_calls_direct']} calls of scipy's ConvexHull escaped the swap")
        if summary.get("constructor_errors"):
            lines.append(f"           exceptions from the constructor: {summary['constructor_errors']}")
        lines.append(f"           trimesh {summary['trimesh_version']} ({summary['trimesh_file']}), "
                     f"scipy {summary['scipy_version']}, numpy {summary['numpy_version']}, "
                     f"Python {summary['python']}")
    (base, _), (swap, _) = data["scipy"], data["cudahull"]
    differing = sorted(set(base) | set(swap))
    differing = [n for n in differing if base.get(n, {}).get("outcome") != swap.get(n, {}).get("outcome")]
    reached = sum(1 for record in swap.values() if record.get("hulls", {}).get("cudahull_calls"))
    lines.append(f"tests that constructed a cudahull.ConvexHull: {reached}")
    lines.append(f"tests whose outcome differs: {len(differing)}")
    for nodeid in differing:
        a, b = base.get(nodeid, {}), swap.get(nodeid, {})
        lines.append(f"  {short(nodeid)}: scipy {a.get('outcome', 'absent')}, cudahull {b.get('outcome', 'absent')}")
        if b.get("message") and b.get("outcome") != "passed":
            lines.append(f"      cudahull: {b['message'][:400]}")
        if a.get("message") and a.get("outcome") != "passed":
            lines.append(f"      scipy:    {a['message'][:400]}")
    if differing:
        problems.append(f"{len(differing)} tests differ")
    # Differences that trimesh (or the test) caught: a test whose constructors raised more often on cudahull
    # than on scipy, or that made a different number of hulls.  Not failures; listed to explain the counts.
    quiet = []
    for nodeid in sorted(set(base) & set(swap)):
        a, b = base[nodeid].get("hulls", {}), swap[nodeid].get("hulls", {})
        raised_a = sum(v for k, v in a.items() if k.startswith("scipy raised"))
        raised_b = sum(v for k, v in b.items() if k.startswith("cudahull raised"))
        made_a, made_b = a.get("scipy_calls_direct", 0), b.get("cudahull_calls", 0)
        if nodeid not in differing and (raised_a != raised_b or made_a != made_b):
            quiet.append(f"  {short(nodeid)}: {made_a} hulls on scipy ({raised_a} raised), {made_b} on cudahull "
                         f"({raised_b} raised); {base[nodeid]['outcome']} on both")
    lines.append(f"tests with the same outcome whose hull count or raised errors differ: {len(quiet)}")
    lines += quiet
    return lines, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("src", help="trimesh source tree (its tests/ and models/), at the installed version")
    parser.add_argument("--out", default="/tmp/trimesh-suite", help="folder for logs and reports")
    parser.add_argument("--runs", nargs="+", choices=RUNS, default=list(RUNS))
    parser.add_argument("--files", nargs="+", help="test files of tests/ to run (default: all)")
    parser.add_argument("--swap", choices=("everywhere", "trimesh"), default="everywhere",
                        help="cudahull's class in scipy's names and every module's (default), or only in "
                             "trimesh.convex's and trimesh.bounds' (docs/python.md's recipe)")
    parser.add_argument("--timeout", type=float, default=3600, help="seconds per run")
    parser.add_argument("--python", default=sys.executable)
    parser.add_argument("--results", help="write the comparison here too")
    parser.epilog = "Arguments after -- go to pytest."
    argv = sys.argv[1:]
    pytest_args = argv[argv.index("--") + 1:] if "--" in argv else []
    args = parser.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    args.pytest_args = pytest_args
    args.src = os.path.abspath(args.src)
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)

    src, installed = source_version(args.src), installed_version(args.python)
    if src != installed:
        parser.error(f"the source tree is trimesh {src}, the installed trimesh {installed}")
    if args.files:
        test_paths = [os.path.join(args.src, "tests", name) for name in args.files]
    else:
        test_paths = sorted(glob.glob(os.path.join(args.src, "tests", "test_*.py")))

    runs = {}
    for run in args.runs:
        runs[run] = run_suite(run, args, test_paths)
    lines, problems = compare(args, runs)
    header = [f"trimesh {installed}'s test suite (tests from {args.src}), on scipy and on cudahull",
              "files: " + (" ".join(args.files) if args.files else f"all of tests/test_*.py ({len(test_paths)})"),
              f"machine: {platform.node()}, {os.cpu_count()} CPUs, {platform.platform()}",
              f"command: {' '.join([os.path.relpath(sys.argv[0])] + sys.argv[1:])}"]
    for run, info in runs.items():
        header.append(f"{run} run: exit {info['returncode']}, {info['seconds']:.0f} s")
    text = "\n".join(header + [""] + lines + [""] + (["PROBLEMS: " + "; ".join(problems)] if problems else
                                                    ["OK: every test's outcome is the same on both"]))
    print(text)
    if args.results:
        with open(args.results, "w") as stream:
            stream.write(text + "\n")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
