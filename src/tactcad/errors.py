"""Errors that a user can act on: each names the field, the value and the allowed range."""

from __future__ import annotations


class TactcadError(Exception):
    """Base of all errors tactcad reports to a user (CLI exit code 2)."""


class DesignError(TactcadError, ValueError):
    """A design file value is missing, unknown or outside its allowed range.

    Attributes:
        field: dotted key in the design file, e.g. ``element.web_thickness_mm``.
        value: the offending value (``None`` when the key is missing).
        allowed: human-readable allowed range or set, with units.
    """

    def __init__(self, field: str, value: object, allowed: str, why: str = ""):
        self.field = field
        self.value = value
        self.allowed = allowed
        self.why = why
        text = f"{field} = {value!r}: allowed {allowed}"
        if why:
            text += f" ({why})"
        super().__init__(text)


class SceneError(TactcadError):
    """An unknown scene or group, a bad scenes file, or a rig that cannot be
    assembled (a slide would leave its range)."""


class ExportPathError(TactcadError):
    """An export folder tactcad will not write: a system folder, a file, or a
    folder of other files."""


class CheckFailure(TactcadError):
    """A geometry, export or manufacturability check failed."""
