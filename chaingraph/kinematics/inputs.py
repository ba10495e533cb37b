"""The one front door for a mechanism's inputs: parsed and checked once, for a sweep
(:func:`sweep_drive`, what :func:`~chaingraph.kinematics.motion.solve` starts from) and
for one pose (:func:`pose_drive`, what
:func:`~chaingraph.kinematics.pose.pose_motion` starts from) alike.

Each gives a :class:`Drive`: the plan that moves the chosen inputs (its fixed link, its
driver or input joints, cached per chain), the input speed, and the sweep's ends or the
pose's value.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import TypeAlias

from chaingraph.errors import MechanismError
from chaingraph.kinematics.plan import Plan, build_plan
from chaingraph.model.chain import Chain, Input, chosen_inputs

__all__ = ["Drive", "sweep_drive", "pose_drive", "input_items", "check_input_value",
           "plan_of", "memory_budget", "LARGEST_INPUT", "InputsGiven"]

#: inputs as given: a joint id, an Input, or a sequence of them, of ``(joint, from, to)``
#: tuples or of ``{"joint", "from", "to"}`` dicts
InputsGiven: TypeAlias = "str | Input | Sequence[str | Input | tuple | dict] | None"
#: the largest input value a sweep may start or stop at
LARGEST_INPUT = 1e9
#: bytes a sweep holds per step and column (the columns and the working arrays, measured)
_BYTES_PER_VALUE = 24


@dataclass(frozen=True)
class Drive:
    """A mechanism's inputs, chosen and checked: ``plan`` moves them and ``omega`` is
    the lead input's speed (as given, else the file's, else 1); for a sweep, ``start``
    and ``stop`` the lead input's ends (None: its cycle decides); for one pose, ``tau``
    the path parameter of the value asked for."""

    plan: Plan
    omega: float
    start: float | None = None
    stop: float | None = None
    tau: float | None = None


def plan_of(chain: Chain, fixed: str | None, driver: str | None,
            inputs: tuple[Input, ...] | None = None) -> Plan:
    """The solve plan of ``chain`` with ``fixed`` fixed, moved by ``driver`` or by the
    input joints ``inputs`` (cached)."""
    # the file is part of the key: chains equal but for their file share no plan, whose
    # messages name the file
    return _cached_plan(chain, chain.source, fixed, driver, inputs)


@lru_cache(maxsize=256)
def _cached_plan(chain, source, fixed, driver, inputs):
    return build_plan(chain, fixed, driver, inputs=inputs)


def check_input_value(value: object, what: str, mechanism: str | None) -> None:
    """Refuse an input value (or speed) that is not a finite number or is past
    ``LARGEST_INPUT``; ``what`` names it in the message."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value):
        raise MechanismError(f"{what} must be a finite number, got {value}",
                             mechanism=mechanism)
    if abs(value) > LARGEST_INPUT:
        raise MechanismError(
            f"{what} {value:g} is too large: at most {LARGEST_INPUT:g} in size (beyond "
            "it a float cannot hold a thousandth of a degree or a millimetre)",
            mechanism=mechanism)


def input_items(inputs: InputsGiven, chain: Chain) -> tuple[Input, ...] | None:
    """Inputs given as joint ids, :class:`Input` items, ``{"joint", "from", "to"}``
    dicts or ``(joint, from, to)`` tuples, as Input items (None when none are given)."""
    if inputs is None:
        return None
    given = [inputs] if isinstance(inputs, (str, Input)) else inputs
    out = []
    for item in given:
        if isinstance(item, Input):
            out.append(item)
        elif isinstance(item, str):
            out.append(Input(item))
        elif isinstance(item, dict) and "joint" in item:
            out.append(Input(item["joint"], item.get("from"), item.get("to")))
        elif isinstance(item, (tuple, list)) and len(item) == 3:
            out.append(Input(*item))
        else:
            raise MechanismError(f"an input must be a joint id, an Input or (joint, from, to), "
                                 f"got {item!r}", mechanism=chain.name)
    for item in out:
        for value in (item.start, item.stop):
            if value is not None and (isinstance(value, bool) or
                                      not isinstance(value, (int, float)) or
                                      not math.isfinite(value)):
                raise MechanismError(f"the input {item.joint!r} has a sweep value that is "
                                     f"not a finite number: {value!r}", mechanism=chain.name)
    if not out:
        raise MechanismError("no inputs given", mechanism=chain.name)
    return tuple(out)


def _chosen(chain, fixed, driver, inputs, omega, name):
    """(fixed, driver, input items, speed): those given, checked, else the file's."""
    if omega is not None:
        check_input_value(omega, "the input speed omega", name)
    else:
        omega = chain.mechanism.omega if chain.mechanism else 1.0
    return (*chosen_inputs(chain, fixed, driver, input_items(inputs, chain)), omega)


def sweep_drive(chain: Chain, *, fixed: str | None = None, driver: str | None = None,
                inputs: InputsGiven = None, start: float | None = None,
                stop: float | None = None, steps: int = 360,
                omega: float | None = None) -> Drive:
    """The inputs of a sweep of ``steps`` steps, as :func:`chaingraph.solve` takes them:
    the first input's ``start`` and ``stop`` given here take the place of its own
    sweep's; a sweep that would not fit in memory is refused."""
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise MechanismError(f"steps must be a positive whole number, got {steps!r}",
                             mechanism=chain.name, parameter="steps")
    for value, what in ((start, "start"), (stop, "stop")):
        if value is not None:
            check_input_value(value, f"the sweep's {what}", chain.name)
    fixed, driver, items, omega = _chosen(chain, fixed, driver, inputs, omega, chain.name)
    if items:
        first = items[0]
        if start is not None or stop is not None:
            first = Input(first.joint, start if start is not None else first.start,
                          stop if stop is not None else first.stop)
            start, stop = first.start, first.stop
        elif first.start is not None:
            start, stop = first.start, first.stop
        if (first.start is None) != (first.stop is None):
            if len(items) > 1 and any(i.start is not None for i in items[1:]):
                raise MechanismError(
                    f"the input {first.joint!r} has a sweep's start or stop but not both, "
                    "while other inputs move: give both", mechanism=chain.name)
            first = Input(first.joint)
        plan = plan_of(chain, fixed, None, (first,) + tuple(items[1:]))
    else:
        plan = plan_of(chain, fixed, driver)
    _check_memory(plan, steps)
    lead = plan.inputs[plan.lead]
    if lead.sweep is not None:
        start, stop = lead.sweep
    return Drive(plan, omega, start=start, stop=stop)


def pose_drive(chain: Chain, *, at: float | Sequence[float] | None = None,
               fixed: str | None = None, driver: str | None = None,
               inputs: InputsGiven = None, omega: float | None = None) -> Drive:
    """The inputs at one pose, as :func:`~chaingraph.kinematics.pose.pose_motion` takes
    them: ``at`` the lead input's value, or one value per input (None: the drawn
    pose). With several inputs they move at the rates of their sweeps (an input
    without a sweep is held)."""
    name = chain.source or chain.name
    if not chain.has_pose:
        raise MechanismError("the chain has no drawn pose (joint positions or lengths): "
                             "instant centres and polygons need its dimensions",
                             mechanism=name)
    values = None
    if at is not None:
        values = [at] if isinstance(at, (int, float)) else list(at)
        if not values:
            raise MechanismError("no input value given", mechanism=name)
        for v in values:
            check_input_value(v, "the input value", name)
    fixed, driver, items, omega = _chosen(chain, fixed, driver, inputs, omega, name)
    if items:
        plan = plan_of(chain, fixed, None, items)
        if values is None or len(values) > 1:
            plan = plan_of(chain, fixed, None, _items_at(plan, values))
    else:
        if not driver and not fixed:
            raise MechanismError("the chain has no mechanism: name its fixed link and its "
                                 "driver or inputs ([mechanism])", mechanism=name)
        plan = plan_of(chain, fixed, driver)
    if values is not None and len(values) != 1 and len(values) != len(plan.inputs):
        raise MechanismError(f"{len(values)} input values given for {len(plan.inputs)} "
                             f"inputs: give one per input, or the first input's alone",
                             mechanism=name)
    if values is None:
        value = plan.inputs[plan.lead].value0       # the drawn pose (a P input's slide 0)
    else:
        value = values[plan.lead] if len(values) > 1 else values[0]
    return Drive(plan, omega, tau=float(plan.tau(value)))


def _items_at(plan, values):
    """Inputs that pass through ``values`` (one per input; None: the drawn pose), each
    moving at its sweep's rate (an input without a sweep is held)."""
    items = []
    for n, item in enumerate(plan.inputs):
        value = item.value0 if values is None else values[n]
        _, k = plan.line[n]
        extent = 0.0
        if k != 0 and item.sweep is not None:
            extent = item.sweep[1] - item.sweep[0]
        elif n == plan.lead:
            extent = 1.0
        items.append(Input(item.joint, float(value), float(value) + extent))
    return tuple(items)


def memory_budget() -> int:
    """Bytes a sweep may take: half of this machine's memory, at most 8 GiB."""
    try:
        physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        physical = 4 << 30
    return int(min(physical // 2, 8 << 30))


def _check_memory(plan, steps):
    """Refuse up front a sweep that would not fit in memory, with what it would need."""
    chain = plan.chain
    columns = 10 * (len(chain.joints) + len(chain.points)) + 3 * len(chain.links) + 4
    need = (steps + 1) * columns * _BYTES_PER_VALUE
    budget = memory_budget()
    if need > budget:
        most = budget // (columns * _BYTES_PER_VALUE) - 1
        gib = -(-need // 2**30)                # integers: steps may have any size
        steps_text = f"{steps:,}" if steps < 10**15 else f"about 10^{len(str(steps)) - 1}"
        gib_text = f"{gib:,}" if gib < 10**15 else f"10^{len(str(gib)) - 1}"
        raise MechanismError(
            f"a sweep of {steps_text} steps would need about {gib_text} GiB of memory "
            f"({columns} columns); at most {most:,} steps fit in the {budget / 2**30:.1f} "
            "GiB a sweep may take here (half of this machine's memory, at most 8 GiB)",
            mechanism=chain.name)
