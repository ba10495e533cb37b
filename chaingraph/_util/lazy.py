"""Names a package's face loads only when first used (PEP 562), so that importing the
package loads no heavy dependency (pynauty, matplotlib, dask) it does not need yet."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Mapping
from typing import Any

__all__ = ["lazy_attribute"]


def lazy_attribute(package: str, lazy: Mapping[str, tuple[str, str | None]],
                   name: str) -> Any:
    """The value of ``name`` in ``package``, imported now and kept in the package.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    lazy : mapping
        Each lazily loaded name to (its module, the attribute of that module, or None
        for the module itself).
    name : str
        The name asked for, as the package's ``__getattr__`` receives it.

    Raises
    ------
    AttributeError
        When ``name`` is not one of ``lazy``'s, as for any missing attribute.

    Examples
    --------
    >>> import types
    >>> sys.modules["example"] = types.ModuleType("example")
    >>> lazy_attribute("example", {"root": ("math", "sqrt")}, "root")(4.0)
    2.0
    >>> sys.modules["example"].root.__name__        # kept: asked once, imported once
    'sqrt'
    >>> lazy_attribute("example", {}, "nothing")
    Traceback (most recent call last):
    ...
    AttributeError: module 'example' has no attribute 'nothing'
    >>> del sys.modules["example"]
    """
    if name not in lazy:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    module, attribute = lazy[name]
    value: Any = importlib.import_module(module)
    if attribute is not None:
        value = getattr(value, attribute)
    setattr(sys.modules[package], name, value)
    return value
