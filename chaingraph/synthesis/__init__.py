"""Dimensional synthesis: quick-return drives (:mod:`.design`)."""
