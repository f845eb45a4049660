"""The ``[tolerances]`` section of a design file: one table for the drawings and the study.

The element drawings print these tolerances on the features they govern and
``tactcad tolerance`` draws its Monte Carlo from the same values, so a shop
that works to the drawing delivers parts the study has covered. Every key is
optional; a key the file leaves out takes the default below, each with its
reason (the capability of the process that makes the feature).

Keys (symmetric +/- tolerances; units in the names):

* ``web_thickness_mm``: the flexure web (default ``element.web_tolerance_mm``,
  where the design file has carried it; the two may not disagree);
* ``notch_radius_mm``: the notch radius;
* ``arm_length_mm``: the tip position relative to the notch centre (the lever);
* ``sheet_thickness_mm``: the sheet the elements are cut from;
* ``contact_face_mm``: the contact face width;
* ``tip_height_mm``: the contact face's height above the base's clamped edge (the
  datum every element of the array shares), so twice it is the worst mismatch of two
  tips' heights: the K_obj budget's coplanarity term reads it, and with
  ``requirements.kobj_accuracy_rel`` states the tolerance it needs;
* ``youngs_modulus_rel``: the material's modulus, relative;
* ``general``: the ISO 2768-1 tolerance class for every other dimension
  (``f`` fine, ``m`` medium, ``c`` coarse, ``v`` very coarse).

Units: mm; the modulus tolerance is relative.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from tactcad.vocabulary.schema import (Problems, ResolvedSection, Section, choice, fmt, number,
                                       section_with_defaults)

#: ISO 2768-1 tolerance classes.
GENERAL_CLASSES = {"f": "fine", "m": "medium", "c": "coarse", "v": "very coarse"}

#: Default value and reason of each key (``web_thickness_mm`` defaults to the element's
#: ``web_tolerance_mm``).
DEFAULTS: dict[str, tuple[Any, str]] = {
    "notch_radius_mm": (0.01, "finishing-pass contour accuracy of fine wire EDM (+/-0.01 mm "
                              "is usual after one or two skim cuts); the notch is cut in the "
                              "same pass as the web"),
    "arm_length_mm": (0.02, "the lever runs between two wire-cut features, notch centre and "
                            "tip, each placed to the contour accuracy of wire EDM"),
    "sheet_thickness_mm": (0.05, "rolled sheet of 3 mm is bought to about +/-0.05 mm (EN 485-4 "
                                 "class for aluminium sheet; ground plate is finer); the "
                                 "elements are cut through it, so it is the element width"),
    "contact_face_mm": (0.02, "the contact face width is a wire-cut contour, to its accuracy"),
    "tip_height_mm": (0.02, "the contact face and the base's clamped edge are wire-cut "
                            "contours, each placed to the contour accuracy of wire EDM"),
    "youngs_modulus_rel": (0.02, "heat-to-heat scatter of wrought alloys; handbook moduli are "
                                 "typical values, not minima"),
    "general": ("f", "ISO 2768-f: the parts are wire-cut or milled to fine-class accuracy "
                     "without extra cost"),
}
KEYS = ("web_thickness_mm", *DEFAULTS)
#: Web tolerance when neither [tolerances] nor [element] gives one.
WEB_DEFAULT_MM = 0.02
WEB_DEFAULT_REASON = ("wire EDM holds a thin web to about +/-0.02 mm with skim cuts; the web "
                      "sets K with about its 2.5th power")


class TolerancesSection(Section):
    """``[tolerances]``: every key optional (defaults in :data:`DEFAULTS`)."""

    web_thickness_mm: number(0.0, 0.25, why="+/- web thickness (etching holds 0.225 on 1.5 mm)") = None
    notch_radius_mm: number(0.0, 0.5, why="+/- notch radius") = None
    arm_length_mm: number(0.0, 0.5, why="+/- tip position from the notch centre") = None
    sheet_thickness_mm: number(0.0, 0.5, why="+/- sheet thickness") = None
    contact_face_mm: number(0.0, 0.5, why="+/- contact face width") = None
    tip_height_mm: number(0.0, 0.5, why="+/- contact face height above the base's clamped "
                                        "edge (tip coplanarity)") = None
    youngs_modulus_rel: number(0.0, 0.2, unit="", why="+/- relative Young's modulus") = None
    general: choice(tuple(GENERAL_CLASSES), "ISO 2768-1 tolerance class") = None


def thinnest_web_mm(d: Any) -> float:
    """The thinnest web of a validated design model (mm): ``[element] web_thickness_mm``, or
    where a comb gives each element's (``[comb] web_thicknesses_mm``), the least of those."""
    shared = d.element.web_thickness_mm
    return shared if shared is not None else min(d.comb.web_thicknesses_mm)


def check_tolerances(d: Any, p: Problems) -> None:
    """Cross-field rules: one web tolerance, and tolerances smaller than what they tolerance."""
    e = d.element
    tol = getattr(d, "tolerances", None)
    if tol is not None and tol.web_thickness_mm is not None and e.web_tolerance_mm is not None \
            and abs(tol.web_thickness_mm - e.web_tolerance_mm) > 1e-12:
        p.add("tolerances.web_thickness_mm", tol.web_thickness_mm,
              f"{fmt(e.web_tolerance_mm)} mm (element.web_tolerance_mm) or leave one of them out",
              "one web tolerance for the drawing and the study")
    web = thinnest_web_mm(d)
    bounded = [("element.web_tolerance_mm", e.web_tolerance_mm, web, "thinnest web")]
    if tol is not None:
        bounded += [("tolerances.web_thickness_mm", tol.web_thickness_mm, web, "thinnest web"),
                    ("tolerances.notch_radius_mm", tol.notch_radius_mm, e.notch_radius_mm,
                     "notch radius")]
    for field, v, nominal, what in bounded:
        if v is not None and v > nominal / 2:
            p.add(field, v, f"<= {fmt(nominal / 2)} mm (half the {what})",
                  "a larger tolerance lets the feature vanish in the tolerance study's draw")


@dataclass(frozen=True)
class DesignTolerances(ResolvedSection):
    """A design's resolved tolerances (mm; modulus relative) with each one's
    source (``sources``: "design file" or the default's reason)."""

    web_thickness_mm: float
    notch_radius_mm: float
    arm_length_mm: float
    sheet_thickness_mm: float
    contact_face_mm: float
    tip_height_mm: float
    youngs_modulus_rel: float
    general: str

    @property
    def general_text(self) -> str:
        """``ISO 2768-f`` etc."""
        return f"ISO 2768-{self.general}"


def tolerances_of(raw: Mapping[str, Any]) -> DesignTolerances:
    """The resolved tolerances of a design's raw tables (validated before)."""
    element = raw.get("element", {}) if isinstance(raw, Mapping) else {}
    web = ((element["web_tolerance_mm"], "design file (element.web_tolerance_mm)")
           if element.get("web_tolerance_mm") is not None else (WEB_DEFAULT_MM, WEB_DEFAULT_REASON))
    values, sources = section_with_defaults(raw, "tolerances",
                                            {"web_thickness_mm": web, **DEFAULTS})
    return DesignTolerances(sources=tuple(sorted(sources.items())),
                            **{k: (values[k] if k == "general" else float(values[k]))
                               for k in KEYS})


#: ISO 2768-1:1989 table 1, permissible deviations for linear dimensions (+/- mm) by class:
#: (upper end of the nominal size range in mm, deviation); class v has none below 3 mm.
ISO_2768_LINEAR_MM: dict[str, tuple[tuple[float, float | None], ...]] = {
    "f": ((3, 0.05), (6, 0.05), (30, 0.1), (120, 0.15), (400, 0.2), (1000, 0.3), (2000, 0.5)),
    "m": ((3, 0.1), (6, 0.1), (30, 0.2), (120, 0.3), (400, 0.5), (1000, 0.8), (2000, 1.2),
          (4000, 2.0)),
    "c": ((3, 0.2), (6, 0.3), (30, 0.5), (120, 0.8), (400, 1.2), (1000, 2.0), (2000, 3.0),
          (4000, 4.0)),
    "v": ((3, None), (6, 0.5), (30, 1.0), (120, 1.5), (400, 2.5), (1000, 4.0), (2000, 6.0),
          (4000, 8.0)),
}


def general_linear_tolerance_mm(size_mm: float, general: str) -> float:
    """The +/- deviation (mm) ISO 2768-1 allows a linear dimension of ``size_mm`` (mm) in
    tolerance class ``general`` (``f``, ``m``, ``c``, ``v``); a size below the table's
    first range takes that range's, one beyond its last takes the last (the standard stops
    at 4000 mm; class v starts at 0.5 mm deviation).

    Raises:
        KeyError: ``general`` is not a class of :data:`GENERAL_CLASSES`.
    """
    rows = ISO_2768_LINEAR_MM[general]
    defined = [(top, dev) for top, dev in rows if dev is not None]
    return next((dev for top, dev in defined if size_mm <= top), defined[-1][1])
