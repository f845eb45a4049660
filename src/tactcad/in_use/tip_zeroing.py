"""The tips' heights read on a rigid flat, and the reading corrected for them.

A tip standing proud of its neighbours meets the tissue first: its element deflects more
at the same travel, which the deflection ratio R cannot tell from a softer object. On the
macro array a 1 um mismatch moves K_obj by about 5 %, while a drawing holds a tip's height
to +/-0.02 mm. The remedy is a zeroing run: a rigid flat (a gauge block's face, flatter
than the tips' mismatch) is pressed onto every tip in a few steps. Under a rigid flat the
element deflections are set by displacement, not force, so at each step every element
in contact deflects by the flat's travel plus its own tip's height above the others,
whatever its stiffness: e_i = Δ_s + h_i. The differences e_i - mean_j e_j are the heights
about the array's mean tip, one estimate per step; their mean over the steps is the
height, their scatter its uncertainty, with the flat's flatness added.

Those heights then go into the coupled inversion (:func:`tactcad.in_use.tissue_coupling.
offset_object_stiffness`), which needs the reference element's force at the reading: the
offset is a length, so its effect on R falls as the elements deflect further.

Assumptions: the flat is held parallel to the clamp's datum by the rig's guide (its tilt
adds a plane to the heights and is not separable from a tilt of the tips); every element
named is in contact at a step whose deflections all exceed ``contact_mm``.

Units: mm (readings in um in the data file), N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from tactcad.errors import TactcadError

#: Flatness of the rigid flat the units are zeroed on (mm): a gauge block's measuring face,
#: ISO 3650 grade 1 (0.15 um up to 150 mm), larger than any face the tips span.
ZEROING_FLAT_FLATNESS_MM = 0.15e-3
#: Steps in contact a zeroing run needs: two give a scatter, hence an uncertainty.
MIN_CONTACT_STEPS = 2


class ZeroingError(TactcadError, ValueError):
    """A zeroing run that gives no tip heights (named with what it lacks)."""


@dataclass(frozen=True)
class TipHeights:
    """Each tip's height about the array's mean tip, read on a rigid flat.

    Attributes:
        heights_mm: element -> height (mm, + proud: towards the tissue).
        sigma_mm: element -> its standard uncertainty (mm): the scatter over the steps
            over sqrt(steps) and the flat's flatness, in quadrature.
        steps_used: the steps in which every element was in contact.
        steps_skipped: the steps left out (an element at or below ``contact_mm``).
        flatness_mm: the flat's flatness taken into the uncertainty (mm).
    """

    heights_mm: Mapping[int, float]
    sigma_mm: Mapping[int, float]
    steps_used: tuple[int, ...]
    steps_skipped: tuple[int, ...]
    flatness_mm: float

    def mismatch_mm(self, unit: tuple[int, int]) -> tuple[float, float]:
        """(measuring tip's height - reference tip's height, its uncertainty) (mm) of a
        (measuring, reference) unit; the two tips' scatters taken independent."""
        m, r = unit
        return (self.heights_mm[m] - self.heights_mm[r],
                math.hypot(self.sigma_mm[m], self.sigma_mm[r]))

    def as_json(self) -> dict:
        return {"heights_um": {str(e): 1e3 * h for e, h in self.heights_mm.items()},
                "sigma_um": {str(e): 1e3 * s for e, s in self.sigma_mm.items()},
                "steps_used": list(self.steps_used), "steps_skipped": list(self.steps_skipped),
                "flatness_um": 1e3 * self.flatness_mm}


def tip_heights_on_flat(steps: Mapping[int, Mapping[int, float]], elements: tuple[int, ...],
                        contact_mm: float = 0.0,
                        flatness_mm: float = ZEROING_FLAT_FLATNESS_MM) -> TipHeights:
    """Each tip's height from a rigid flat's steps (see the module doc).

    Args:
        steps: step -> {element: deflection (mm)}, each step reading every element.
        elements: the design's element numbers; each step must read exactly these.
        contact_mm: a step counts where every deflection exceeds it (mm), >= 0.
        flatness_mm: the flat's flatness (mm), >= 0.

    Returns:
        :class:`TipHeights`.

    Raises:
        ZeroingError: a step reads an element the design lacks or misses one (named),
            fewer than :data:`MIN_CONTACT_STEPS` steps with every tip in contact.
    """
    if not (math.isfinite(contact_mm) and contact_mm >= 0):
        raise ZeroingError(f"contact_mm = {contact_mm!r}: allowed >= 0 mm")
    if not (math.isfinite(flatness_mm) and flatness_mm >= 0):
        raise ZeroingError(f"flatness_mm = {flatness_mm!r}: allowed >= 0 mm")
    wanted = set(elements)
    used, skipped, rows = [], [], []
    for step, row in steps.items():
        extra, missing = sorted(set(row) - wanted), sorted(wanted - set(row))
        if extra or missing:
            raise ZeroingError(f"step {step}: elements {sorted(row)}: allowed every element of "
                               f"the design once, {sorted(wanted)} (missing {missing}, not in "
                               f"the design {extra})")
        e = np.array([row[n] for n in elements], float)
        if np.all(e > contact_mm):
            used.append(step)
            rows.append(e - e.mean())
        else:
            skipped.append(step)
    if len(used) < MIN_CONTACT_STEPS:
        shown = ", ".join(str(s) for s in skipped[:5]) + (", ..." if len(skipped) > 5 else "")
        hint = ("; every deflection is at or below 0: are they signed the other way?"
                if all(v <= 0 for row in steps.values() for v in row.values()) else "")
        raise ZeroingError(f"steps with every tip in contact (deflection > "
                           f"{1e3 * contact_mm:g} um) = {len(used)}: allowed >= "
                           f"{MIN_CONTACT_STEPS}; press the flat further ({len(skipped)} steps "
                           f"leave a tip out of contact: {shown}){hint}")
    d = np.array(rows)
    mean = d.mean(axis=0)
    scatter = d.std(axis=0, ddof=1) / math.sqrt(len(used))
    sigma = np.hypot(scatter, flatness_mm)
    return TipHeights({n: float(h) for n, h in zip(elements, mean)},
                      {n: float(s) for n, s in zip(elements, sigma)},
                      tuple(used), tuple(skipped), float(flatness_mm))


def read_tip_heights(path, elements: tuple[int, ...], encoding: str | None = None,
                     contact_um: float = 0.0):
    """(:func:`tip_heights_on_flat` of a zeroing file's steps, how the file was read
    (:class:`tactcad.mechanics.measured_io.ReadInfo`)); a refusal of its steps names the file.

    Raises:
        tactcad.mechanics.calibration.CalibrationError: the file cannot be read (named).
        ZeroingError: as :func:`tip_heights_on_flat`, prefixed by ``path``.
    """
    from tactcad.mechanics.measured_io import read_flat_readings

    steps, info = read_flat_readings(path, encoding)
    try:
        return tip_heights_on_flat(steps, elements, 1e-3 * contact_um), info
    except ZeroingError as exc:
        raise ZeroingError(f"{path}: {exc}") from None


def simulated_flat_steps(heights_mm: Mapping[int, float], travels_mm, noise_mm: float = 0.0,
                         seed: int = 0) -> dict[int, dict[int, float]]:
    """A rigid flat's readings for known tip heights (for tests and dry runs): at each
    travel Δ (mm, measured from the proudest tip's contact) every element deflects by
    max(Δ + h_i - max h, 0), plus Gaussian noise of ``noise_mm`` (one sigma)."""
    rng = np.random.default_rng(seed)
    top = max(heights_mm.values())
    return {s + 1: {n: max(float(t) + h - top, 0.0) + float(rng.normal(0.0, noise_mm))
                    for n, h in heights_mm.items()}
            for s, t in enumerate(np.asarray(travels_mm, float))}
