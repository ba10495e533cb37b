"""Dimensional synthesis: quick-return drives from a time ratio and a stroke
(:mod:`.design`: the crank and slotted lever, Whitworth's drive)."""

from chaingraph.synthesis.design import KINDS, Design, slotted_lever, whitworth

__all__ = ["Design", "slotted_lever", "whitworth", "KINDS"]
