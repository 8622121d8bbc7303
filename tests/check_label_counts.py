#!/usr/bin/env python3
"""Checks that a ctest run ran every test it should: per label, how many ran, against a committed minimum.

A test that is not registered (a module not built, a discovery that failed) or that skips is a test that
did not run, and CI would stay green without it.  So after ctest, this prints for each label the tests that
ran, passed, failed and skipped, and the property tests' case ranges, and exits 1 where a label ran fewer
tests than its minimum in tests/label_counts.txt or skipped any.  Raise a minimum when you add tests.

    tests/check_label_counts.py BUILD_DIR JUNIT_XML [--exclude REGEX] KEY=LABEL [KEY=LABEL ...]

KEY names the minimum (a line `KEY COUNT` in tests/label_counts.txt); LABEL is the ctest label it counts;
--exclude leaves out the tests that ctest was told to leave out (its -E REGEX).
"""
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

MINIMUMS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "label_counts.txt")


def registered(build_dir, label, exclude):
    """The names of the tests registered under `label` in `build_dir`, less those matching `exclude`."""
    command = ["ctest", "--test-dir", build_dir, "-N", "-L", f"^{label}$"] + (["-E", exclude] if exclude else [])
    listing = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return {m.group(1).strip() for m in re.finditer(r"^ *Test +#\d+: (.+)$", listing, re.M)}


def main(argv):
    if len(argv) < 4:
        print(__doc__.strip().split("\n\n")[-2], file=sys.stderr)
        return 2
    build_dir, junit, pairs, exclude = argv[1], argv[2], argv[3:], None
    if pairs[0] == "--exclude":
        exclude, pairs = pairs[1], pairs[2:]
    with open(MINIMUMS) as f:
        minimums = {k: int(v) for k, v in (line.split() for line in f if line.strip() and line[0] != "#")}
    cases = {c.get("name"): c for c in ElementTree.parse(junit).getroot().iter("testcase")}
    ok = True
    for pair in pairs:
        key, label = pair.split("=")
        names = registered(build_dir, label, exclude)
        status = {n: cases[n].get("status") if n in cases else "absent" for n in names}
        ran = sum(s in ("run", "fail") for s in status.values())
        failed = sum(s == "fail" for s in status.values())
        skipped = sorted(n for n, s in status.items() if s not in ("run", "fail"))
        minimum = minimums.get(key)
        print(f"tests: {key}: {ran} ran (minimum {minimum}), {ran - failed} passed, {failed} failed, "
              f"{len(skipped)} did not run")
        for name in skipped:
            print(f"tests: {key}: did not run: {name} ({status[name]})")
        if minimum is None:
            print(f"tests: {key}: no minimum in {MINIMUMS}")
            ok = False
        elif ran < minimum or skipped:
            ok = False
    # The property tests' fixed case ranges, as each printed them.
    for c in cases.values():
        out = c.findtext("system-out") or ""
        for line in re.findall(r"^property \(.*$", out, re.M):
            print(f"tests: {line}")
    if not ok:
        print("tests: FAILED: a label ran fewer tests than its minimum, or some did not run", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
