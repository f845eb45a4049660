"""How a part comes to be: the typed process every part carries into its BOM
row, title block and manifest, and from which the shop data (raw stock, blank
allowances, surface finish: :mod:`tactcad.catalogue.shop`) follows; a cut
process also carries the fatigue surface factor of the surface it leaves
(:class:`SurfaceFatigue`), which the strength model applies at the notch root."""

from __future__ import annotations

from dataclasses import dataclass
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


@dataclass(frozen=True)
class SurfaceFatigue:
    """The fatigue surface factor of the surface a process leaves (Marin's k_a:
    the fatigue strength of the part's surface over that of the polished
    specimen the library's data come from).

    k_a = min(ceiling, a S_u^b) (Marin's form, S_u in MPa), so a harder alloy
    loses more to the same surface.

    Attributes:
        surface: the surface in words.
        marin_a_MPa, marin_b: Marin's coefficients for the surface class (S_u in MPa).
        ceiling: the largest factor taken whatever S_u (<= 1).
        reason: why these values, with the sources.
    """

    surface: str
    marin_a_MPa: float
    marin_b: float
    ceiling: float
    reason: str

    def factor(self, ultimate_MPa: float) -> float:
        """k_a of this surface on an alloy of ultimate strength ``ultimate_MPa`` (MPa, > 0).

        Raises:
            ValueError: a non-positive ultimate strength.
        """
        if not ultimate_MPa > 0:
            raise ValueError(f"ultimate strength must be > 0 MPa; got {ultimate_MPa!r}")
        return min(self.ceiling, self.marin_a_MPa * ultimate_MPa ** self.marin_b)


#: A finished (skim-cut) wire-EDM surface: the notch root of every element.
WIRE_EDM_SURFACE = SurfaceFatigue(
    surface="wire EDM with finishing skim cuts (recast layer at the notch root)",
    marin_a_MPa=4.51, marin_b=-0.265, ceiling=0.9,
    reason=("Marin's factor of a machined surface, k_a = 4.51 S_u^-0.265 (Shigley's Mechanical "
            "Engineering Design, 9th ed., Table 6-2, after Noll and Lipson 1946), as the "
            "surface class a finished wire-EDM cut matches: trim-pass wire EDM of titanium "
            "alloys fatigues like flank milling (Antar et al., Procedia CIRP 2013, "
            "Ti-6Al-2Sn-4Zr-6Mo: no significant difference at the 5 % level) and like grinding "
            "(Klocke et al., Procedia Eng. 19, 2011, Ti-6Al-4V); a main cut without skims "
            "leaves a thicker recast layer that lowers it further (Mower, Int. J. Fatigue 64, "
            "2014, Ti-6Al-4V), so the drawing's skim cuts (Ra 0.8 at the web) are part of the "
            "assumption. Marin's fit comes from steels and gives ~1 for a soft aluminium "
            "alloy, yet its recast layer still carries microcracks: the factor is capped at "
            "0.9 for every alloy (a judgement, not a measurement). 6061-T6: 0.90, 7075-T6: "
            "0.84, Ti-6Al-4V: 0.73, CuBe C17200: 0.70, 17-4 PH H900: 0.67."))


class Process(str):
    """A part's process as the BOM, title block and manifest print it (the
    text), typed by its :class:`Method` (``.method``), which is what the shop
    data reads: ``Process("milling from plate", Method.PLATE)``; ``.surface``
    is the fatigue surface factor of the cut surface (:class:`SurfaceFatigue`,
    None when the process does not state one)."""

    method: Method
    surface: SurfaceFatigue | None

    def __new__(cls, text: str, method: Method,
                surface: SurfaceFatigue | None = None) -> "Process":
        if not isinstance(method, Method):
            raise TypeError(f"Process {text!r}: method must be a Method, not {method!r}")
        obj = super().__new__(cls, text)
        obj.method = method
        obj.surface = surface
        return obj

    def __getnewargs__(self) -> tuple[str, Method, SurfaceFatigue | None]:  # pickles whole
        return (str(self), self.method, self.surface)


#: How every sensing element is made; its surface factor is the one strength
#: applies at the notch root (a polished or etched process would carry its own).
ELEMENT_PROCESS = Process("wire EDM from sheet", Method.SHEET, WIRE_EDM_SURFACE)
