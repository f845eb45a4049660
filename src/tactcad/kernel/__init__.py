"""The CAD kernel's one door: the only package that imports build123d or OCP.

Everything above speaks tactcad's words to it: the modelling verbs of
:mod:`~tactcad.kernel.shapes` (boxes, cylinders, prisms of 2D profiles,
booleans that must leave one solid), placements and joints
(:mod:`~tactcad.kernel.locations`, :mod:`~tactcad.kernel.joints`), hidden-line
projection (:mod:`~tactcad.kernel.hlr`), STEP and BREP files
(:mod:`~tactcad.kernel.step_writer`, :mod:`~tactcad.kernel.brep`), measurements of
solids (:mod:`~tactcad.kernel.inspect`) and the build123d part objects of the
Python API (:mod:`~tactcad.kernel.objects`). Solids, locations and compounds
pass through the layers above as values they hand back here; no module
outside this package imports the kernel (``tests/kernel/test_kernel_wall.py``).

Importing this package is free; each module loads the kernel (2-4 s) when it
is imported, so a command that needs no geometry never imports one.
"""

import importlib
import importlib.util
import sys
from types import ModuleType
from typing import Any

#: Libraries build123d imports as it loads but tactcad never calls into: sympy (0.2-0.4 s
#: of the kernel's 1.5-2 s import) serves one curve object's tangent construction only.
#: Each is imported on its first use instead (:func:`defer_import`).
DEFERRED_IMPORTS = ("sympy",)


class _Deferred(ModuleType):
    """Stands in ``sys.modules`` for a module not imported yet; the first attribute
    it lacks imports the real module (which then replaces it) and is read from it.

    Unlike :class:`importlib.util.LazyLoader`'s module, it survives an ``import``
    statement unloaded (that statement reads ``__spec__``, here a plain attribute)."""

    def __getattr__(self, attr: str) -> Any:
        name = self.__name__
        if sys.modules.get(name) is self:
            del sys.modules[name]
        return getattr(importlib.import_module(name), attr)


def defer_import(name: str) -> None:
    """Put a stand-in for the top-level module ``name`` in ``sys.modules`` that imports
    the module on its first use (an attribute read, a submodule import); its ``__file__``
    is the module's own, read without importing it.

    Nothing happens when the module is already imported or not installed.

    Args:
        name: a top-level module's import name (``"sympy"``).
    """
    if name in sys.modules or "." in name:
        return
    spec = importlib.util.find_spec(name)
    if spec is None:
        return
    stand_in = _Deferred(name)
    stand_in.__spec__ = spec  # for find_spec; an import statement reads its _initializing
    # where it lives is no use of it: a scan of every module's file (hypothesis's pytest
    # plugin reads each one's __file__ as it collects) leaves it unloaded
    stand_in.__file__ = spec.origin
    sys.modules[name] = stand_in


for _name in DEFERRED_IMPORTS:
    defer_import(_name)
