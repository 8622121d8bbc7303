"""The console commands ``cudahull`` and ``cudahull-viewer`` of an installed wheel.

The wheel carries the two C++ programs inside the package (``cudahull/_bin``), with the libraries they need
bundled beside them; these entry points replace the Python process with the program, so exit codes,
signals and output are the program's own.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import NoReturn

_PACKAGE = Path(__file__).resolve().parent
_BIN = _PACKAGE / "_bin"
_DATA = _PACKAGE / "data"

#: The model the viewer opens when given no input (the Stanford bunny, as ``scripts/run`` shows it).
BUNDLED_MODEL = _DATA / "bun_zipper.ply"


def _program(name: str) -> Path:
    path = _BIN / name
    if not path.is_file():
        sys.stderr.write(
            f"{name}: this installation of cudahull has no {name} program (a source build without it; the "
            "binary wheel from scripts/wheel carries it, and scripts/build builds it)\n"
        )
        raise SystemExit(1)
    return path


def _exec(path: Path, arguments: list[str], env: dict[str, str] | None = None) -> NoReturn:
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(path, [path.name, *arguments], os.environ.copy() if env is None else env)


def cli() -> NoReturn:
    """Run the ``cudahull`` command line (``cudahull --help``)."""
    _exec(_program("cudahull"), sys.argv[1:])


def _has_input(arguments: list[str]) -> bool:
    """Whether the viewer's arguments name points: a positional INPUT or ``--gen``."""
    with_value = {"--seed", "--backend", "--engine", "--precision", "--width", "--height", "--steps",
                  "--screenshot", "--script", "--frames", "--bench-frames", "--ui-layout", "--record",
                  "--record-fps", "--window-screenshot"}
    skip = 0
    for argument in arguments:
        if skip:
            skip -= 1
        elif argument == "--gen":
            return True
        elif argument in with_value:
            skip = 1
        elif not argument.startswith("-"):
            return True
    return False


def viewer_arguments(arguments: list[str], environ: dict[str, str]) -> list[str]:
    """The viewer's command line as ``cudahull-viewer`` runs it.

    With no input it opens the bundled bunny; with no display (no ``DISPLAY`` or ``WAYLAND_DISPLAY``) and no
    ``--headless`` or ``--screenshot`` of the caller's, it renders the stepping sequence headless to
    ``out/bunny/step_NNN.png`` (``out/viewer`` for other input) in the working directory, as ``scripts/run``
    does.  ``--help`` passes through unchanged.
    """
    if any(a in ("-h", "--help", "--version") for a in arguments):
        return arguments
    result = list(arguments)
    bundled = not _has_input(arguments)
    if bundled:
        result.insert(0, str(BUNDLED_MODEL))
    has_display = bool(environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"))
    if not has_display and "--headless" not in arguments:
        folder = Path("out") / ("bunny" if bundled else "viewer")
        folder.mkdir(parents=True, exist_ok=True)
        result += ["--headless"]
        if "--screenshot" not in arguments and "--script" not in arguments:
            result += ["--screenshot", str(folder / "step_%03d.png")]
            if "--width" not in arguments:
                result += ["--width", "1280", "--height", "800"]
            sys.stderr.write(f"cudahull-viewer: no display: rendering the stepping sequence headless to "
                             f"{folder}/step_NNN.png\n")
    return result


def viewer() -> NoReturn:
    """Run ``cudahull-viewer`` (``cudahull-viewer --help``): the bundled bunny when given no input."""
    program = _program("cudahull-viewer")
    env = os.environ.copy()
    # The labels' font travels in the wheel: used where the machine has no DejaVu Sans of its own.
    font = _DATA / "DejaVuSans.ttf"
    if "CUDAHULL_VIEWER_FONT" not in env and font.is_file():
        env["CUDAHULL_VIEWER_FONT"] = str(font)
    _exec(program, viewer_arguments(sys.argv[1:], env), env)
