"""The dynamics tests' shared test engine."""

from __future__ import annotations

import math

from chaingraph import Chain, Joint, Mechanism

R, L = 50.0, 200.0                       # crank and rod of the test engine, mm


def slider_crank(*loads, friction=None, masses=(), gravity=None, units="mm") -> Chain:
    """An in-line slider crank drawn at 90 degrees: crank O-A, rod A-B, piston on S
    (axis +x, away from the crank), with ``loads``, ``masses`` and ``gravity``."""
    bx = math.sqrt(L * L - R * R)
    return Chain("engine", (
        Joint("O", "R", ("frame", "crank"), at=(0.0, 0.0)),
        Joint("A", "R", ("crank", "rod"), at=(0.0, R)),
        Joint("B", "R", ("rod", "piston"), at=(bx, 0.0)),
        Joint("S", "P", ("frame", "piston"), at=(bx, 0.0), axis=0.0, friction=friction)),
        units=units, mechanism=Mechanism("frame", driver="crank"), loads=loads,
        masses=masses, gravity=gravity)
