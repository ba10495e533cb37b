"""The exceptions chaingraph raises.

Every error is a :class:`ChainGraphError`. Each specific error also subclasses the
builtin it behaves like, so ``except ValueError`` keeps working for callers who do
not know chaingraph. Errors carry their details as fields, and ``str(error)`` is one
clear message naming what is wrong and where, in the words of the library (a
parameter by its name, ``time_ratio``); the command line maps parameters to its flags
and errors to its exit statuses.
"""

from __future__ import annotations

__all__ = [
    "ChainGraphError",
    "ChainFileError",
    "DimensionError",
    "DegenerateDrawingError",
    "ChainStructureError",
    "MechanismError",
    "AssemblyError",
    "UnboundedRangeError",
    "AtlasSizeError",
    "AtlasRunError",
    "OutputError",
    "DesignError",
    "InterchangeError",
    "ChainGraphWarning",
    "PoseAdjustedWarning",
]


class ChainGraphError(Exception):
    """Base class of every error chaingraph raises on purpose."""


class ChainFileError(ChainGraphError, ValueError):
    """A chain file (or document) that is not a valid chain.

    Parameters
    ----------
    problem : str
        What is wrong, in a sentence.
    source : str, optional
        The file (or ``"<string>"``) the chain came from.
    where : str, optional
        The joint, point or key at fault, e.g. ``"joint 'B'"`` or ``"key 'name'"``.
    line : int, optional
        The line of a TOML syntax error.
    """

    def __init__(self, problem, *, source=None, where=None, line=None):
        self.problem = problem
        self.source = source
        self.where = where
        self.line = line
        super().__init__(self._message())

    def _message(self):
        parts = [p for p in (self.source, self.where) if p]
        parts.append(self.problem)
        return ": ".join(parts)


class DimensionError(ChainFileError):
    """Dimensions (lengths, offsets, the input's value, assembly modes) that give no
    pose: a missing or non-positive length, a triangle that cannot close, a mechanism
    that cannot be assembled at the given input. Bad input: exit status 2.

    Extra fields: ``part`` (the link, joint or dyad at fault) and ``feasible_range``
    (the input values where the mechanism can be assembled, when it was found).
    """

    def __init__(self, problem, *, source=None, where=None, part=None,
                 feasible_range=None):
        self.part = part
        self.feasible_range = feasible_range
        super().__init__(problem, source=source, where=where)


class DegenerateDrawingError(DimensionError):
    """A drawn pose in which a link has no size: every joint that turns it (its R
    joints, two or more, and no sliding pair to set its direction) drawn at one point,
    so that it has zero length and its direction is undefined. Bad input: exit
    status 2.

    Extra fields: ``link`` (the link, also ``part``), ``joints`` (its joints drawn
    there) and ``at`` (the point, in the file's units).
    """

    def __init__(self, problem, *, source=None, link=None, joints=(), at=None):
        self.link = link
        self.joints = tuple(joints)
        self.at = at
        super().__init__(problem, source=source, part=link)


class ChainStructureError(ChainGraphError, ValueError):
    """A valid chain that an analysis cannot take (empty, disconnected...)."""

    def __init__(self, problem, *, chain=None, pieces=None):
        self.problem = problem
        self.chain = chain
        self.pieces = pieces
        super().__init__(f"{chain}: {problem}" if chain else problem)


class MechanismError(ChainGraphError, ValueError):
    """A mechanism that cannot be solved as asked (wrong driver, mobility, joints).
    ``parameter`` names the parameter of the call at fault (``"fixed"``, ``"steps"``),
    where one is: the command line names its option from it."""

    def __init__(self, problem, *, mechanism=None, where=None, mobility=None,
                 parameter=None):
        self.problem = problem
        self.mechanism = mechanism
        self.where = where
        self.mobility = mobility
        self.parameter = parameter      # the function's parameter at fault, e.g. "fixed"
        parts = [p for p in (mechanism, where) if p]
        parts.append(problem)
        super().__init__(": ".join(parts))


class AssemblyError(ChainGraphError, RuntimeError):
    """A pose that cannot be assembled: the analysis failed (not the input)."""

    def __init__(self, problem, *, mechanism=None, angle=None, feasible_range=None):
        self.problem = problem
        self.mechanism = mechanism
        self.angle = angle
        self.feasible_range = feasible_range
        super().__init__(f"{mechanism}: {problem}" if mechanism else problem)


class UnboundedRangeError(AssemblyError):
    """An input that runs on without a limit and without coming back to the drawn pose
    (a slide whose guides never stop it): it has no whole cycle to sweep by default,
    only a sweep given with its ends."""


class OutputError(ChainGraphError, OSError):
    """An output (a file or folder to write) that cannot be written: a folder where a
    file is asked for, a file where a folder is needed, no permission, a full disk, a
    format nobody draws. Bad input: exit status 2. ``path`` is the output at fault and
    ``reason`` why."""

    def __init__(self, path, reason):
        self.path = str(path)
        self.reason = reason
        super().__init__(f"{path}: {reason}")

    def __str__(self):
        return f"{self.path}: {self.reason}"


class AtlasRunError(ChainGraphError, RuntimeError):
    """An atlas run that cannot go on: a Dask scheduler that cannot be reached, Dask not
    installed, an output folder that holds no run to resume or a different one, or an
    empty output path. ``reason`` is ``"unreachable"``, ``"missing"``, ``"resume"`` or
    ``"out"``; ``parameter`` the parameter of the call at fault (``"scheduler"``,
    ``"out"``, ``"resume"``)."""

    def __init__(self, problem, *, reason=None, parameter=None):
        self.problem = problem
        self.reason = reason
        self.parameter = parameter
        super().__init__(problem)


class AtlasSizeError(ChainGraphError, ValueError):
    """A number of links and degrees of freedom that admits no chain, or an atlas too
    big to run here; ``parameter`` the parameter at fault (``"links"``, ``"dof"``), or
    the one that would help (``"scheduler"``)."""

    def __init__(self, problem, *, links=None, dof=None, parameter=None):
        self.problem = problem
        self.links = links
        self.dof = dof
        self.parameter = parameter
        super().__init__(problem)


class DesignError(ChainGraphError, ValueError):
    """Design requirements that no mechanism of the asked kind can meet."""

    def __init__(self, problem, *, kind=None, parameter=None):
        self.problem = problem
        self.kind = kind
        self.parameter = parameter
        super().__init__(f"design {kind}: {problem}" if kind else problem)


class InterchangeError(ChainFileError):
    """A model another tool wrote that cannot be read (malformed, an unknown joint type),
    or a mechanism that another tool's format cannot hold (a sliding pair between two
    moving links for pylinkage, a cam for either). Bad input: exit status 2. Extra
    field: ``format`` (``"pylinkage"``, ``"pyslvs"``)."""

    def __init__(self, problem, *, format=None, source=None, where=None, line=None):
        self.format = format
        super().__init__(problem, source=source, where=where, line=line)


class ChainGraphWarning(UserWarning):
    """Base class of the warnings chaingraph gives (the command line prints each as one
    line on standard error)."""


class PoseAdjustedWarning(ChainGraphWarning):
    """A drawn pose that was off by drawing-level rounding and was moved to the nearest
    consistent pose. Fields: ``joint`` (the joint or point that moved most), ``distance``
    (how far it moved, in the file's units) and ``size`` (the mechanism's size)."""

    def __init__(self, message, *, joint=None, distance=None, size=None):
        self.joint = joint
        self.distance = distance
        self.size = size
        super().__init__(message)
