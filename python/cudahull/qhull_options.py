"""scipy's ``qhull_options`` string, parsed as Qhull parses it, into what cudahull does with each option.

design:
    split the string on white space; each word is read as Qhull's qh_initflags reads it: its first letter
    names a group (Q, P, T, C, A; a leading '-' is allowed), and the rest of the word continues that group
    ("Qcx" is Qc and Qx, "QbB" one option; "QbBPp" is an error in Qhull too, P not being a Q option)
    C and A take a number ("C-0", "A0.99"); QG takes a point ("QG4", "QG-4"); QJ an optional number
    for each option, look up its meaning here (the README's table says the same in words)
    an option with no meaning here raises QhullError naming it: code that passes it expects something
    cudahull would silently not do

What the options mean here (the hull itself is exact unless a tolerance asks for merging):
    Qt             triangulated output: always so; accepted
    Qbb, QbB, Qbk:n, QBk:n
                   Qhull scales the input against its own roundoff; the exact hull needs none.  As scipy's,
                   ``volume`` and ``area`` are those of the scaled points (QbB: each coordinate mapped onto
                   [-0.5, 0.5]; Qbb: the last onto [0, the largest magnitude of the others]; Qbk:n, QBk:n:
                   coordinate k's low or high bound onto n).  Unlike scipy's, the equations stay in the
                   input's coordinates.  Qbk:0Bk:0 (Qhull drops coordinate k) has no defined behaviour here
    Qc             ``coplanar`` also lists every point that is not a vertex but lies within the tolerance of
                   a facet (scipy's Qc), with its facet and nearest vertex
    Qi             ``coplanar`` also lists every interior point, with its nearest facet and vertex
    Qx, Qz, Q12, Qs, Qv, Pp, Tv
                   Qhull's internal search, checks and warnings: accepted, no effect on the result
    QJ, QJn        joggle the input so that the output is simplicial: the exact hull already is, without
                   joggling; no merging (tolerance None).  Flat points are joggled as Qhull joggles them
                   (by up to 30,000 times its roundoff), and their thin full-dimensional hull returned
    QGn, QG-n      ``good``: the facets visible (QGn) or not visible (QG-n) from point n, which is left out
                   of the hull, as in Qhull
    Cn, C-n        merge facets within the distance n (absolute, as in Qhull); C0 and C-0 are Qhull's
                   roundoff-based tolerance (tolerance "qhull")
    An, A-n        merge facets whose normals' angle has a cosine above n (A0 and A-0: Qhull's default,
                   as C-0): a vertex is dropped where it stands within the distance tolerance (Cn's, else
                   Qhull's) plus sqrt(1 - n^2) times half its distance to its farthest neighbour, so the facets
                   that replace it tilt by at most about that angle; Qhull merges pairs of facets, so the
                   counts differ from Qhull's
"""

from __future__ import annotations

import math
import re
from typing import Any, Callable, NoReturn

import numpy as np
import numpy.typing as npt

Error = Callable[[str], Exception]

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_INTEGER = re.compile(r"[-+]?\d+")
# Q's one-letter options with no effect here, and those whose meaning ParsedOptions records.
_Q_FLAGS = {"t", "x", "z", "s", "v", "c", "i"}
# The groups of which one option has a meaning here (Pp: no precision warnings; Tv: Qhull's check).
_ONE_OPTION_GROUPS = {"P": "p", "T": "v"}


class ParsedOptions:
    """What a ``qhull_options`` string asks for, as ``parse`` reads it.

    Attributes
    ----------
    good_point : int or None
        n of QGn (None without).
    good_visible : bool
        True for QGn, False for QG-n.
    interior, coplanar, joggle : bool
        Qi, Qc, QJ.
    centrum : float or None
        The distance of Cn / C-n (None without; 0 for C-0 and A-0).
    angle_cosine : float or None
        An's n.
    words : list of str
        The options as read.
    scalings : list of tuple
        Qhull's scalings in the order given: ("box",) for QbB, ("last",) for Qbb, ("low" or "high", k, n)
        for Qbk:n and QBk:n.
    """

    def __init__(self) -> None:
        self.good_point: int | None = None
        self.good_visible = True
        self.interior = False
        self.coplanar = False
        self.joggle = False
        self.centrum: float | None = None
        self.angle_cosine: float | None = None  # An's n
        self.words: list[str] = []
        # Qhull's scaling, in the order given: ("box",) for QbB, ("last",) for Qbb, ("low" or "high", k, n).
        self.scalings: list[tuple[Any, ...]] = []

    def check_dimension(self, ndim: int, error: Error) -> None:
        """Raises ``error`` as Qhull does for a Qbk:n or QBk:n naming an axis the points do not have."""
        for scaling in self.scalings:
            if scaling[0] in ("low", "high") and scaling[1] >= ndim:
                option = "Qb" if scaling[0] == "low" else "QB"
                raise error(f"QH7048 qhull option warning: dimension {scaling[1]} for Qhull option '{option}' is >= "
                            f"{ndim}.  Ignored\nQH6036 qhull option error: see previous warnings")

    def scaled_axes(self, ndim: int) -> set[int]:
        """The axes QbB maps onto [-0.5, 0.5] (Qhull's QH6022 names the first that holds one value)."""
        return set(range(ndim)) if ("box",) in self.scalings else set()

    def scaling(self, points: npt.NDArray[np.float64]) -> tuple[list[float], list[float]] | None:
        """(scale, shift) per axis of the map Qhull applies to ``points`` under QbB, Qbb, Qbk:n and QBk:n, or
        None without them: each axis' [low, high] onto its new bounds (a bound not given stays)."""
        if not self.scalings:
            return None
        ndim = int(points.shape[1])
        low, high = points.min(axis=0), points.max(axis=0)
        if list(self.scalings) == [("box",)]:
            # QbB alone (trimesh passes it on every call), by arrays: each axis onto [-0.5, 0.5].
            widths = high - low
            factors = 1.0 / np.where(widths > 0, widths, 1.0)
            return list(map(float, factors)), list(map(float, -0.5 - low * factors))
        new_low, new_high = [float(v) for v in low], [float(v) for v in high]
        last = False
        for scaling in self.scalings:
            if scaling[0] == "box":
                new_low, new_high = [-0.5] * ndim, [0.5] * ndim
            elif scaling[0] == "last":
                last = True
            elif scaling[1] < ndim:
                (new_low if scaling[0] == "low" else new_high)[scaling[1]] = scaling[2]
        if last:
            # Qbb: the last coordinate onto [0, m], m the largest magnitude among the other coordinates.
            new_low[-1] = 0.0
            new_high[-1] = float(np.abs(points[:, :-1]).max(initial=0.0))
        scale, shift = [], []
        for k in range(ndim):
            width = float(high[k] - low[k])
            factor = (new_high[k] - new_low[k]) / width if width > 0 else 1.0
            scale.append(factor)
            shift.append(new_low[k] - float(low[k]) * factor)
        return scale, shift

    def merge(self, default: Any) -> Any:
        """The merging these options ask for: None (the exact hull) with QJ; ``"qhull"`` for C-0, C0, A-0
        (Qhull's own roundoff-based tolerance); ``("options", distance, cosine)`` for Cn (distance, else
        None: Qhull's) and An (cosine, else None); else ``default``."""
        if (self.centrum or 0) > 0 or self.angle_cosine is not None:
            return ("options", self.centrum or None, self.angle_cosine)
        if self.centrum is not None:
            return "qhull"
        if self.joggle:
            return None
        return default


def parse(options: str | bytes, error: Error) -> ParsedOptions:
    """Parses a ``qhull_options`` string as Qhull reads it.

    Parameters
    ----------
    options : str or bytes
        The options, as scipy's ``qhull_options``.
    error : callable
        Makes the exception to raise from a message (``QhullError``'s).

    Returns
    -------
    ParsedOptions
        What the options ask for.

    Raises
    ------
    TypeError
        For options that are not a string.
    Exception
        ``error``'s, naming the first option with no meaning here.
    """
    if isinstance(options, bytes):
        options = options.decode("latin-1")
    if not isinstance(options, str):
        raise TypeError(f"qhull_options must be a string, not {type(options).__name__}")
    parsed = ParsedOptions()
    for word in options.split():
        _parse_word(word[1:] if word.startswith("-") and len(word) > 1 else word, parsed, error)
    return parsed


def _unknown(name: str, error: Error, word: str | None = None) -> NoReturn:
    where = f" (in '{word}': a word continues its first letter's group, as in Qhull)" if word and word != name else ""
    raise error(f"qhull_options: the option '{name}'{where} has no defined behaviour in cudahull "
                f"(see the README's table of options)")


def _number(word: str, at: int, name: str, pattern: re.Pattern[str], error: Error) -> tuple[str, int]:
    match = pattern.match(word, at)
    if match is None:
        raise error(f"qhull_options: '{name}' needs a number")
    return match.group(0), match.end()


def _parse_word(word: str, parsed: ParsedOptions, error: Error) -> None:
    group = word[0]
    if group in "CA":
        text, end = _number(word, 1, word, _NUMBER, error)
        if end != len(word):
            _unknown(word, error)
        value = abs(float(text))
        if not math.isfinite(value):
            raise error(f"qhull_options: '{word}' needs a finite number")
        if group == "C":
            parsed.centrum = max(parsed.centrum or 0.0, value)
        elif value > 1:
            raise error(f"qhull_options: '{word}' needs the cosine of an angle, at most 1")
        elif value == 0:
            parsed.centrum = parsed.centrum or 0.0  # Qhull's default test, as C-0
        else:
            parsed.angle_cosine = value if parsed.angle_cosine is None else max(parsed.angle_cosine, value)
        parsed.words.append(word)
        return
    if group in _ONE_OPTION_GROUPS:  # Pp, Tv: the group's one option here, as often as it is written
        for letter in word[1:] or "?":
            if letter != _ONE_OPTION_GROUPS[group]:
                _unknown(group + letter, error)
            parsed.words.append(group + letter)
        return
    if group != "Q":
        _unknown(word, error)
    at = 1
    if at == len(word):
        _unknown(word, error)
    while at < len(word):
        letter = word[at]
        at += 1
        if letter in _Q_FLAGS:
            parsed.words.append("Q" + letter)
            parsed.interior = parsed.interior or letter == "i"
            parsed.coplanar = parsed.coplanar or letter == "c"
        elif letter == "b" and at < len(word) and word[at] in "bB":
            parsed.words.append("Qb" + word[at])
            parsed.scalings.append(("box",) if word[at] == "B" else ("last",))
            at += 1
        elif letter in "bB" and at < len(word) and word[at].isdigit():
            # Qbk:n, QBk:n: coordinate k's low or high bound scaled to n (the measures follow, as scipy's); without
            # ":n" (or with n 0), Qhull's default.
            axis, at = _number(word, at, "Q" + letter, _INTEGER, error)
            name = "Q" + letter + axis
            bound = -0.5 if letter == "b" else 0.5  # Qhull's default for Qbk, QBk
            if at < len(word) and word[at] == ":":
                text, at = _number(word, at + 1, name + ":", _NUMBER, error)
                name += ":" + text
                bound = float(text) if float(text) != 0 else bound
                if float(text) == 0 and re.search(rf"B{axis}:0*\.?0*(?![\d.])", word[at:]) and letter == "b":
                    _unknown(name + "B" + axis + ":0", error, word)  # Qbk:0Bk:0: Qhull drops coordinate k
            parsed.words.append(name)
            parsed.scalings.append(("low" if letter == "b" else "high", int(axis), bound))
        elif letter == "J":
            match = _NUMBER.match(word, at)
            at = match.end() if match else at
            parsed.joggle = True
            parsed.words.append("QJ")
        elif letter == "G":
            text, at = _number(word, at, "QG", _INTEGER, error)
            parsed.good_visible = not text.startswith("-")
            parsed.good_point = abs(int(text))
            parsed.words.append("QG" + text)
        elif letter.isdigit():
            digits = re.compile(r"\d+").match(word, at - 1)
            assert digits is not None  # word[at - 1] is a digit
            at = digits.end()
            if digits.group(0) != "12":
                _unknown("Q" + digits.group(0), error, word)
            parsed.words.append("Q12")
        else:
            _unknown("Q" + letter, error, word)
