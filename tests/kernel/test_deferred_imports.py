"""The kernel's import leaves the libraries build123d loads but tactcad never
calls into (``DEFERRED_IMPORTS``) unloaded until their first use."""

import subprocess
import sys

PROBE = """
import sys
import tactcad.kernel.shapes as shapes
shapes.box_at_origin(1.0, 1.0, 1.0)
print("loaded before use:", "sympy.core" in sys.modules)
import sympy
print("value:", sympy.Rational(1, 3) * 3)
print("loaded after use:", "sympy.core" in sys.modules, type(sys.modules["sympy"]).__name__)
"""


def test_sympy_loads_on_first_use_only():
    out = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True,
                         check=True).stdout
    assert "loaded before use: False" in out
    assert "value: 1" in out
    assert "loaded after use: True module" in out


def test_a_module_already_imported_is_left_alone():
    probe = ("import sys, sympy\nreal = sys.modules['sympy']\nfrom tactcad.kernel import "
             "defer_import\ndefer_import('sympy')\ndefer_import('no_such_module_here')\n"
             "print(sys.modules['sympy'] is real, 'no_such_module_here' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True).stdout
    assert out.split() == ["True", "False"]


def test_reading_where_a_deferred_module_lives_does_not_import_it(tmp_path, monkeypatch):
    """A scan of every module's ``__file__`` (hypothesis's pytest plugin makes one as it
    collects) reads the stand-in's without importing the module; its first use does."""
    from tactcad.kernel import _Deferred, defer_import

    name = "tactcad_deferred_probe"
    source = tmp_path / f"{name}.py"
    source.write_text("LOADED = True\n", encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, name, raising=False)
    defer_import(name)
    stand_in = sys.modules[name]
    assert isinstance(stand_in, _Deferred)
    assert getattr(stand_in, "__file__", None) == str(source)
    assert sys.modules[name] is stand_in  # still not imported
    assert stand_in.LOADED is True  # the first use imports it
    assert not isinstance(sys.modules[name], _Deferred)
    monkeypatch.delitem(sys.modules, name)
