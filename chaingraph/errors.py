"""The exceptions chaingraph raises.

Every error is a :class:`ChainGraphError`. Each specific error also subclasses the
builtin it behaves like, so ``except ValueError`` keeps working for callers who do
not know chaingraph. Errors carry their details as fields, and ``str(error)`` is one
clear message naming what is wrong and where. ``exit_status`` is what the command
line exits with: 2 for bad input, 1 for a failure of the analysis.
"""

from __future__ import annotations

__all__ = [
    "ChainGraphError",
    "ChainFileError",
    "ChainStructureError",
    "MechanismError",
    "AssemblyError",
    "AtlasSizeError",
    "DesignError",
]


class ChainGraphError(Exception):
    """Base class of every error chaingraph raises on purpose."""

    exit_status = 2


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


class ChainStructureError(ChainGraphError, ValueError):
    """A valid chain that an analysis cannot take (empty, disconnected...)."""

    def __init__(self, problem, *, chain=None, pieces=None):
        self.problem = problem
        self.chain = chain
        self.pieces = pieces
        super().__init__(f"{chain}: {problem}" if chain else problem)


class MechanismError(ChainGraphError, ValueError):
    """A mechanism that cannot be solved as asked (wrong driver, mobility, joints)."""

    def __init__(self, problem, *, mechanism=None, where=None, mobility=None):
        self.problem = problem
        self.mechanism = mechanism
        self.where = where
        self.mobility = mobility
        parts = [p for p in (mechanism, where) if p]
        parts.append(problem)
        super().__init__(": ".join(parts))


class AssemblyError(ChainGraphError, RuntimeError):
    """A pose that cannot be assembled; the analysis failed (exit status 1)."""

    exit_status = 1

    def __init__(self, problem, *, mechanism=None, angle=None, feasible_range=None):
        self.problem = problem
        self.mechanism = mechanism
        self.angle = angle
        self.feasible_range = feasible_range
        super().__init__(f"{mechanism}: {problem}" if mechanism else problem)


class AtlasSizeError(ChainGraphError, ValueError):
    """A number of links and degrees of freedom that admits no chain."""

    def __init__(self, problem, *, links=None, dof=None):
        self.problem = problem
        self.links = links
        self.dof = dof
        super().__init__(problem)


class DesignError(ChainGraphError, ValueError):
    """Design requirements that no mechanism of the asked kind can meet."""

    def __init__(self, problem, *, kind=None, parameter=None):
        self.problem = problem
        self.kind = kind
        self.parameter = parameter
        super().__init__(f"design {kind}: {problem}" if kind else problem)
