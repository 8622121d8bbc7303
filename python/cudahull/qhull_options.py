"""scipy's ``qhull_options`` string, parsed as Qhull parses it, into what cudahull does with each option.

design:
    split the string on white space, then read each word as Qhull does: a word may run several options
    together ("QbBPp" is "QbB" and "Pp"), and an option may carry a number ("QG4", "C-0", "A0.99")
    for each option, look up its meaning here (the README's table says the same in words)
    an option with no meaning here raises QhullError naming it: code that passes it expects something
    cudahull would silently not do

What the options mean here (the hull itself is exact unless a tolerance asks for merging):
    Qt             triangulated output: always so; accepted
    Qbb, QbB, Qbk:n, QBk:n
                   Qhull scales the input to reduce its own roundoff; the exact hull does not need it, and the
                   output is in the input's coordinates either way: accepted, no effect
    Qc             coplanar points: ``coplanar`` lists the points merging set aside (always kept)
    Qi             ``coplanar`` also lists the interior points, each with its nearest facet and vertex
    Qx, Qz, Q12, Qs, Qv, Pp, Tv
                   Qhull's internal search, checks and warnings: accepted, no effect on the result
    QJ, QJn        joggle the input so that the output is simplicial: the exact hull already is, without
                   joggling; no merging (tolerance None)
    QGn, QG-n      ``good``: the facets visible (QGn) or not visible (QG-n) from point n, which is left out
                   of the hull, as in Qhull
    Cn, C-n        merge facets within the distance n (absolute, as in Qhull); C0 and C-0 are Qhull's
                   roundoff-based tolerance (tolerance "qhull")
    An, A-n        merge facets whose normals' angle has cosine above n: taken as the distance
                   sqrt(1 - n^2) x the bounding box's diagonal (the most such a tilt moves a facet);
                   the larger of C's and A's distances is used
"""

import math
import re

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_TOKEN = re.compile(
    r"(?P<good>QG)(?P<good_value>[-+]?\d+)"
    r"|(?P<joggle>QJ)(?P<joggle_value>" + _NUMBER + r")?"
    r"|(?P<flag>Qt|Qbb|QbB|Qx|Qz|Q12|Qs|Qv|Qc|Qi|Pp|Tv)"
    r"|(?P<scale>Q[bB])(?P<scale_axis>\d)(?::(?P<scale_value>" + _NUMBER + r"))?"
    r"|(?P<centrum>C)(?P<centrum_value>" + _NUMBER + r")"
    r"|(?P<angle>A)(?P<angle_value>" + _NUMBER + r")"
)


class ParsedOptions:
    """What a ``qhull_options`` string asks for.

    ``good_point``: n of QGn (None without); ``good_visible``: True for QGn, False for QG-n;
    ``interior``: Qi; ``joggle``: QJ; ``centrum``: the distance of Cn / C-n (None without);
    ``angle_cosine``: n of An / A-n (None without); ``words``: the options as read.
    """

    def __init__(self):
        self.good_point = None
        self.good_visible = True
        self.interior = False
        self.joggle = False
        self.centrum = None
        self.angle_cosine = None
        self.words = []

    def merge(self, default):
        """The merging these options ask for: None (the exact hull) with QJ; ``"qhull"`` for C-0, C0, A-0
        and the like (Qhull's own roundoff-based tolerance); ``("absolute", distance, angle_cosine)`` for
        C or A with a value; else ``default``."""
        centrum = self.centrum or 0.0
        cosine = self.angle_cosine
        if centrum > 0 or (cosine is not None and cosine < 1):
            return ("absolute", centrum, cosine)
        if self.centrum is not None or self.angle_cosine is not None:
            return "qhull"
        if self.joggle:
            return None
        return default


def parse(options, error):
    """Parses a ``qhull_options`` string (str or bytes); raises ``error`` (QhullError) naming the first
    option with no meaning here."""
    if isinstance(options, bytes):
        options = options.decode("latin-1")
    if not isinstance(options, str):
        raise TypeError(f"qhull_options must be a string, not {type(options).__name__}")
    parsed = ParsedOptions()
    for word in options.split():
        position = 0
        while position < len(word):
            match = _TOKEN.match(word, position)
            if match is None or match.end() == position:
                rest = word[position:]
                raise error(f"qhull_options: the option '{rest}' has no defined behaviour in cudahull "
                            f"(see the README's table of options)")
            _apply(parsed, match, error)
            parsed.words.append(match.group(0))
            position = match.end()
    return parsed


def _apply(parsed, match, error):
    if match.group("good"):
        value = int(match.group("good_value"))
        parsed.good_visible = not match.group("good_value").startswith("-")
        parsed.good_point = abs(value)
    elif match.group("joggle"):
        parsed.joggle = True
    elif match.group("flag") == "Qi":
        parsed.interior = True
    elif match.group("centrum"):
        value = abs(float(match.group("centrum_value")))
        if not math.isfinite(value):
            raise error(f"qhull_options: '{match.group(0)}' needs a finite distance")
        parsed.centrum = max(parsed.centrum or 0.0, value)
    elif match.group("angle"):
        value = abs(float(match.group("angle_value")))
        if not 0 <= value <= 1:
            raise error(f"qhull_options: '{match.group(0)}' needs a cosine between 0 and 1")
        parsed.angle_cosine = value if parsed.angle_cosine is None else min(parsed.angle_cosine, value)
    # Everything else (Qt, Qbb, QbB, Qx, Qz, Q12, Qs, Qv, Qc, Pp, Tv, Qb/QB scaling) changes nothing here.
