"""How a part comes to be: the typed process every part carries into its BOM
row, title block and manifest, and from which the shop data (raw stock, blank
allowances, surface finish: :mod:`tactcad.catalogue.shop`) follows."""

from __future__ import annotations

from enum import Enum


class Method(Enum):
    """How a part comes to be: the typed half of its :class:`Process`; the raw
    stock, the blank allowances and the surface finish follow from it
    (:mod:`tactcad.catalogue.shop`)."""

    SHEET = "cut from sheet"          # wire EDM or laser: sheet blank
    PLATE = "milled from plate"       # sawn plate blank, faced both sides
    BAR = "cut from bar stock"        # sawn and faced rectangular bar
    ROUND_BAR = "turned from round bar"
    CAST = "cast"                     # moulded to size
    BOUGHT = "bought"                 # a catalogue part: no stock


class Process(str):
    """A part's process as the BOM, title block and manifest print it (the
    text), typed by its :class:`Method` (``.method``), which is what the shop
    data reads: ``Process("milling from plate", Method.PLATE)``."""

    method: Method

    def __new__(cls, text: str, method: Method) -> "Process":
        if not isinstance(method, Method):
            raise TypeError(f"Process {text!r}: method must be a Method, not {method!r}")
        obj = super().__new__(cls, text)
        obj.method = method
        return obj

    def __getnewargs__(self) -> tuple[str, Method]:  # pickles with its method
        return (str(self), self.method)
