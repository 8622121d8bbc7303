"""The package's errors, and Qhull's words for the inputs that have no full-dimensional hull.

``QhullError`` subclasses scipy's ``scipy.spatial.QhullError`` so that code catching scipy's catches
ours.  Importing ``scipy.spatial`` takes some 0.3 s, so the class is built the first time it is raised or
asked for (``qhull_error_class()``, the package's module ``__getattr__``), not when cudahull is imported.
"""

from __future__ import annotations

import decimal
import math
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from ._cudahull import DeviceError, InputError

__all__ = ["DeviceError", "InputError", "QhullError", "qhull_error", "qhull_error_class", "degenerate_error",
           "too_few_points_error", "number_text", "value_text"]

InputError.__doc__ = """Raised for bad points: a NaN or infinite coordinate (naming the point and its axis), or
a value beyond float's range for ``precision="float"``.

A subclass of ``ValueError``.
"""

DeviceError.__doc__ = """Raised where a GPU is asked for and none is usable: ``backend="cuda"``, or points in
GPU memory, without a working CUDA device and driver (the message says why).

A subclass of ``RuntimeError``.
"""

_QHULL_ERROR_DOC = """Raised where ``scipy.spatial.ConvexHull`` raises ``QhullError``.

That is: fewer than ndim + 1 points, flat input (its lower-dimensional hull is ``cudahull.convex_hull()``'s
answer), and ``qhull_options`` with an option that has no defined behaviour here.  The message begins with
Qhull's own code and words for the case (``QH6214``, ``QH6154 Qhull precision error: Initial simplex is
flat``, ``QH6013``, ``QH6421``, ``QH6022``), so that code matching Qhull's text matches ours.

A subclass of ``scipy.spatial.QhullError`` where scipy is importable, else of ``RuntimeError``.
"""



def number_text(value: float) -> str:
    """A number as every error message writes it: as the module's C++ does (std::to_chars, the shortest text
    that reads back as the same double, in fixed or scientific notation, whichever is shorter, fixed on a
    tie): ``1e+39``, ``0.25``, ``-3``, ``nan``, ``-inf``; never NumPy's ``np.float64(1e+39)``."""
    number = float(value)
    if math.isnan(number):
        return "-nan" if math.copysign(1.0, number) < 0 else "nan"
    if math.isinf(number):
        return "-inf" if number < 0 else "inf"
    if number == 0:
        return "-0" if math.copysign(1.0, number) < 0 else "0"
    sign, digits, exponent = decimal.Decimal(repr(number)).as_tuple()
    assert isinstance(exponent, int)
    text = "".join(map(str, digits)).lstrip("0")
    stripped = text.rstrip("0")
    exponent += len(text) - len(stripped)
    text = stripped  # |value| = text * 10**exponent, without leading or trailing zeros
    point = len(text) + exponent  # digits before the decimal point
    if exponent >= 0:
        fixed = str(abs(int(number)))  # a whole number in fixed notation: its exact digits, as to_chars
    elif point > 0:
        fixed = text[:point] + "." + text[point:]
    else:
        fixed = "0." + "0" * -point + text
    power = point - 1
    scientific = text[0] + ("." + text[1:] if len(text) > 1 else "") + f"e{'-' if power < 0 else '+'}{abs(power):02d}"
    chosen = fixed if len(fixed) <= len(scientific) else scientific
    return ("-" if sign else "") + chosen


def value_text(value: object) -> str:
    """An argument as an error message names it: a real number as ``number_text`` writes it, anything else
    as its repr."""
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_)):
        return str(int(value)) if isinstance(value, (int, np.integer)) else number_text(float(value))
    return repr(value)


if TYPE_CHECKING:
    # What type checkers see: scipy's QhullError is a RuntimeError, and scipy need not be installed.
    class QhullError(RuntimeError):
        """Raised where ``scipy.spatial.ConvexHull`` raises ``QhullError`` (see the package's docs)."""


_built: type[RuntimeError] | None = None


def qhull_error_class() -> type[RuntimeError]:
    """The ``QhullError`` class, built on first use on scipy's base (``RuntimeError`` without scipy)."""
    global _built
    if _built is None:
        base: type[RuntimeError] = RuntimeError
        try:
            import scipy.spatial  # type: ignore[import-untyped, unused-ignore]

            base = scipy.spatial.QhullError
        except ImportError:
            pass
        # __module__ "cudahull": pickling finds the class as cudahull.QhullError.
        _built = type("QhullError", (base,), {"__doc__": _QHULL_ERROR_DOC, "__module__": "cudahull"})
    return _built


def qhull_error(message: str) -> RuntimeError:
    """A ``QhullError`` carrying ``message``."""
    return qhull_error_class()(message)


def __getattr__(name: str) -> object:
    if name == "QhullError":
        return qhull_error_class()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def too_few_points_error(count: int, ndim: int) -> RuntimeError:
    """Qhull's QH6214, word for word."""
    return qhull_error(f"QH6214 qhull input error: not enough points({count}) to construct initial simplex "
                       f"(need {ndim + 1})")


def degenerate_error(low: npt.NDArray[Any], high: npt.NDArray[Any], dimension: int,
                     scaled_axes: set[int]) -> RuntimeError:
    """The error for points (per-axis bounds ``low``, ``high``) whose hull spans only ``dimension`` < d
    dimensions, with the code and first line Qhull gives for them, in the order Qhull checks: an axis QbB
    rescales (``scaled_axes``) holding one value (QH6022), every point the same (QH6421), every x the same
    (QH6013), else flat (QH6154)."""
    ndim = int(low.shape[0])
    span = f"the points span {dimension} of {ndim} dimensions"
    hint = "cudahull.convex_hull() gives their lower-dimensional hull"
    for axis in sorted(scaled_axes):
        if axis < ndim and low[axis] == high[axis]:
            return qhull_error(
                f"QH6022 qhull input error: {axis}'th dimension's new bounds [-0.5, 0.5] too wide for\n"
                f"existing bounds [{low[axis]:2.2g}, {high[axis]:2.2g}]\n\n({span}: every point has the "
                f"same {'xyz'[axis] if axis < 3 else f'coordinate {axis}'}; {hint})")
    if dimension <= 0:
        return qhull_error(
            "QH6421 qhull internal error (qh_maxsimplex): qh.MAXwidth required for qh_maxsimplex.  Used to "
            f"estimate determinate\n\n(every point is the same point: {hint})")
    if low[0] == high[0]:
        return qhull_error(
            f"QH6013 qhull input error: input is less than {ndim}-dimensional since all points have the "
            f"same x coordinate {float(low[0]):4.4g}\n\n({span}; {hint})")
    return qhull_error(f"QH6154 Qhull precision error: Initial simplex is flat ({span}; {hint})")
