"""A calibration data file read and fitted with one set of refusals.

``tactcad calibrate --data`` and ``tactcad budget --calibration`` both read a file through
:func:`read_calibration`, so a file one refuses the other refuses too, in the same words.
Beyond what :func:`~tactcad.mechanics.measured_io.read_measured` refuses (a cell, a column,
an encoding), the readings of each element must be fittable (paper eq. 4-5):

* the Z travel, the force and the bridge signal each change over the readings (a column
  that reads the same at every step is a channel not connected or not mapped);
* the force gauge's own deflection F/K_s stays within the Z travel z, so that the
  element's deflection z - F/K_s is positive and the fitted K > 0; where it is not, the
  refusal says which reading, and which of the likely causes the readings point to: z
  written in mm, force in mN, the gauge stiffness ``k_sensor_N_per_mm``, one outlier;
* the signal follows the deflection (a K_v distinct from zero).

Units: Z travel in um, deflection in mm, force in N, stiffness in N/mm, signal in V.
"""

from __future__ import annotations

from typing import Mapping, NamedTuple, Sequence

import numpy as np

from tactcad.mechanics.calibration import (K_SENSOR_N_PER_MM, Calibration, CalibrationData,
                                           CalibrationError, fit_calibration)
from tactcad.mechanics.measured_io import ReadInfo, TooFewReadings, WorkbookError, read_measured

#: A reading's element deflection below -this share of the element's largest Z travel is
#: negative beyond what the force gauge's noise explains at Z = 0.
NEGATIVE_DEFLECTION_SHARE = 0.05
#: Ratio of a unit slip (mm for um, mN for N).
UNIT_RATIO = 1e3
#: An element whose largest force (or travel) is this many times the other elements' has
#: its column in another unit.
UNIT_SLIP_RATIO = 30.0
#: Under this Z travel (um) a whole calibration run is not a travel in um.
SMALLEST_TRAVEL_UM = 1.0
#: K_v within this many standard errors of zero: the signal does not follow the deflection.
SIGNAL_T_MIN = 3.0


class CalibrationFile(NamedTuple):
    """A calibration data file, read and fitted.

    Attributes:
        data: element -> its readings, in the file's order.
        fits: element -> its fit (paper eq. 4-5), K > 0 for every element.
        info: how the file was read.
    """

    data: dict[int, CalibrationData]
    fits: dict[int, Calibration]
    info: ReadInfo


def read_calibration(path, option: str = "--data", encoding: str | None = None,
                     mapping: Mapping[str, str] | None = None,
                     default_k_sensor: float = K_SENSOR_N_PER_MM,
                     element_numbers: Sequence[int] | None = None) -> CalibrationFile:
    """Read a calibration data file and fit every element's K, K_v and V0.

    Args:
        path: the CSV, LVM or TDMS file.
        option: the option that named the file (``--data``, ``--calibration``): the
            refused field where the refusal is of the file as a whole.
        encoding, mapping: as :func:`~tactcad.mechanics.measured_io.read_measured`.
        default_k_sensor: the force gauge's stiffness K_s (N/mm) where the file states none.
        element_numbers: the design's element numbers; None accepts any.

    Returns:
        :class:`CalibrationFile`.

    Raises:
        CalibrationError: the file cannot be read, names an element the design does not
            have, or an element's readings cannot be fitted (see the module doc); the
            message names the file, the element, the line where one is the cause and what
            to change; ``field``, ``value`` and ``allowed`` are always set.
    """
    try:
        data, info = read_measured(path, encoding, mapping, default_k_sensor=default_k_sensor)
    except TooFewReadings as exc:  # an element the design has not is the first thing wrong
        if element_numbers is not None:
            _check_element_numbers(exc.places, str(path), element_numbers, option)
        raise _of_option(exc, option, str(path)) from None
    except CalibrationError as exc:
        raise _of_option(exc, option, str(path)) from None
    if element_numbers is not None:
        _check_elements(data, info, element_numbers, option)
    fits = {e: _fit_element(e, d, info) for e, d in data.items()}
    bad = [e for e, fit in fits.items() if fit is None or not fit.K_N_per_mm > 0]
    if bad:
        good = [d for e, d in data.items() if e not in bad]
        raise travel_refusal(bad[0], data[bad[0]], info, good)
    return CalibrationFile(data, fits, info)


def _of_option(exc: CalibrationError, option: str, path: str) -> CalibrationError:
    """``exc`` with the option and the file as its field and value where it names no column."""
    if isinstance(exc, WorkbookError):  # the file as a whole: the option heads the message
        return CalibrationError(f"{option} = {exc}", option, path, exc.allowed)
    if exc.field is not None:
        return exc
    message = str(exc)
    allowed = exc.allowed or (message.split(": allowed ", 1)[1] if ": allowed " in message
                              else "a calibration file tactcad reads (CSV, LVM or TDMS)")
    return CalibrationError(message, option, path, allowed)


def _check_elements(data: Mapping[int, CalibrationData], info: ReadInfo,
                    numbers: Sequence[int], option: str) -> None:
    _check_element_numbers({e: info.places.get(e, ("line ?",)) for e in data}, info.path,
                           numbers, option)


def _check_element_numbers(places: Mapping[int, Sequence[str]], path: str,
                           numbers: Sequence[int], option: str) -> None:
    """Refuse the first element of ``places`` (element -> where its readings are) that is
    none of the design's ``numbers``."""
    known = sorted(set(numbers))
    span = (f"{known[0]} ... {known[-1]}" if known == list(range(known[0], known[-1] + 1))
            else ", ".join(map(str, known)))
    for element, where in places.items():
        if element not in known:
            place = (where or ("line ?",))[0]
            allowed = f"element numbers of the design, {span}"
            raise CalibrationError(f"{option} = {path}: {place}, column element = "
                                   f"{element}: element {element} is not in the design: "
                                   f"allowed {allowed}", "element", element, allowed)


def _fit_element(element: int, d: CalibrationData, info: ReadInfo) -> Calibration | None:
    """The element's fit, or None where the gauge's deflection leaves it no positive one."""
    at = f"{info.path}: element {element}"
    for column, values, unit, what in (
            ("z_um", d.z_travel_um, "um", "the Z axis stood at"),
            ("force_N", d.force_N, "N", "the force gauge read"),
            ("signal_V", d.signal_V, "V", "the bridge read")):
        if np.ptp(values) == 0:  # a channel not connected, or another column's
            allowed = (f"{column} that changes over the Z steps (is its channel connected, "
                       "and is it the column read?)")
            raise CalibrationError(
                f"{at}: column {column}: {column.split('_')[0]} constant: {what} "
                f"{values[0]:g} {unit} at every step: allowed {allowed}", column,
                f"{values[0]:g} {unit} at all {values.size} readings", allowed)
    try:
        fit = fit_calibration(d.z_travel_um, d.force_N, d.signal_V, d.k_sensor_N_per_mm)
    except CalibrationError:  # every reading at one deflection: the gauge took all the travel
        return None
    if not fit.K_N_per_mm > 0:
        return None
    if abs(fit.K_v_V_per_mm) <= SIGNAL_T_MIN * fit.stderr_K_v_V_per_mm:
        allowed = (f"a signal that follows the deflection (|K_v| > {SIGNAL_T_MIN:g} standard "
                   "errors): is the bridge powered and its channel the signal_V column?")
        raise CalibrationError(
            f"{at}: column signal_V: K_v = {fit.K_v_V_per_mm:.3g} +- "
            f"{fit.stderr_K_v_V_per_mm:.2g} V/mm, no slope above the noise: allowed {allowed}",
            "signal_V", f"K_v = {fit.K_v_V_per_mm:.3g} V/mm", allowed)
    return fit


def _negative(d: CalibrationData, keep: np.ndarray | None = None) -> np.ndarray:
    """Readings whose element deflection z - F/K_s is negative beyond the gauge's noise."""
    z_mm, force = 1e-3 * d.z_travel_um, d.force_N
    if keep is not None:
        z_mm, force = z_mm[keep], force[keep]
    deflection = z_mm - force / d.k_sensor_N_per_mm
    return deflection < -NEGATIVE_DEFLECTION_SHARE * max(float(z_mm.max()), 0.0)


def _fits_positive(z_um, force_N, d: CalibrationData) -> bool:
    """True when readings (z, F) with ``d``'s signal and gauge give K > 0 and no reading
    with a negative deflection."""
    trial = CalibrationData(z_um, force_N, d.signal_V, d.k_sensor_N_per_mm)
    try:
        fit = fit_calibration(z_um, force_N, d.signal_V, d.k_sensor_N_per_mm)
    except CalibrationError:
        return False
    return bool(fit.K_N_per_mm > 0 and not _negative(trial).any())


def _outlier(d: CalibrationData) -> int | None:
    """The one reading whose removal leaves a fit with K > 0 and no negative deflection:
    the one whose gauge deflection most exceeds its travel; None when no single reading."""
    if d.force_N.size < 4:
        return None
    deflection = 1e-3 * d.z_travel_um - d.force_N / d.k_sensor_N_per_mm
    worst = int(np.argmin(deflection))
    keep = np.arange(d.force_N.size) != worst
    try:
        fit = fit_calibration(d.z_travel_um[keep], d.force_N[keep], d.signal_V[keep],
                              d.k_sensor_N_per_mm)
    except CalibrationError:
        return None
    return worst if fit.K_N_per_mm > 0 and not _negative(d, keep).any() else None


def _unit_slips(d: CalibrationData, good: Sequence[CalibrationData]) -> list[str]:
    """The unit slips (z in mm, force in mN) that would give this element a positive
    deflection, in words; the other elements' scale decides between the two."""
    z_max, f_max = float(d.z_travel_um.max()), float(np.abs(d.force_N).max())
    z_fix = _fits_positive(d.z_travel_um * UNIT_RATIO, d.force_N, d)
    f_fix = _fits_positive(d.z_travel_um, d.force_N / UNIT_RATIO, d)
    z_words = (f"z_um written in mm (the largest travel is {z_max:.4g} um; in um it would be "
               f"{z_max * UNIT_RATIO:.4g})")
    f_words = (f"force_N written in mN (the largest force is {f_max:.4g} N; in N it would be "
               f"{f_max / UNIT_RATIO:.4g})")
    if good:
        z_others = float(np.median([g.z_travel_um.max() for g in good]))
        f_others = float(np.median([np.abs(g.force_N).max() for g in good]))
        if f_fix and f_max > UNIT_SLIP_RATIO * f_others:
            return [f_words + f", {f_max / f_others:.0f} x the other elements'"]
        if z_fix and z_max * UNIT_SLIP_RATIO < z_others:
            return [z_words + f", 1/{z_others / z_max:.0f} of the other elements'"]
    elif z_fix and z_max < SMALLEST_TRAVEL_UM:
        return [z_words]
    return [w for w, fix in ((z_words, z_fix), (f_words, f_fix)) if fix]


def travel_refusal(element: int, d: CalibrationData, info: ReadInfo,
                   good: Sequence[CalibrationData] = ()) -> CalibrationError:
    """The refusal of an element whose readings give no positive K: the force gauge's own
    deflection F/K_s exceeds the Z travel, so the element's deflection z - F/K_s comes out
    negative; with the reading where it does most and the likely causes.

    Args:
        element: the element number. d: its readings. info: how the file was read (its
            path and the places of the readings).
        good: the readings of the file's elements that fit, to tell a unit slip of one
            element from the others' scale.

    Returns:
        The :class:`CalibrationError` to raise (field ``force_N``, or ``z_um`` where the
        travel's unit is the cause).
    """
    k_s = d.k_sensor_N_per_mm
    taken_um = 1e3 * d.force_N / k_s
    deflection_um = d.z_travel_um - taken_um
    worst = int(np.argmin(deflection_um))
    places = info.places.get(element, ())
    place = places[worst] if worst < len(places) else f"reading {worst + 1}"
    try:
        fit = fit_calibration(d.z_travel_um, d.force_N, d.signal_V, k_s)
        fitted = f"fitted K = {fit.K_N_per_mm:.4g} N/mm"
    except CalibrationError:
        fitted = "no K can be fitted (every reading at one deflection)"
    count = int(np.count_nonzero(_negative(d)))
    if not count:  # every deflection positive: the force itself falls as Z rises
        allowed = "> 0 (force must rise with Z travel)"
        return CalibrationError(
            f"{info.path}: element {element}: {fitted}: allowed {allowed}; force_N goes from "
            f"{d.force_N[int(np.argmin(d.z_travel_um))]:g} N at the least travel to "
            f"{d.force_N[int(np.argmax(d.z_travel_um))]:g} N at the most: is the gauge read "
            "with compression negative? Then negate force_N", "force_N", fitted, allowed)
    outlier = _outlier(d)
    if outlier is not None:
        at = places[outlier] if outlier < len(places) else f"reading {outlier + 1}"
        causes = [f"an outlier at {at}: force_N = {d.force_N[outlier]:g} N at z_um = "
                  f"{d.z_travel_um[outlier]:g} (remove or re-take that reading)"]
    else:
        moved = d.z_travel_um > 0
        # K_s >= F/z at every reading keeps each deflection z - F/K_s >= 0
        need = float(np.max(d.force_N[moved] / (1e-3 * d.z_travel_um[moved])))
        causes = _unit_slips(d, good) + [
            f"the force gauge's stiffness k_sensor_N_per_mm = {k_s:g} N/mm too low (these "
            f"readings need more than {need:.4g} N/mm; set it in the file's "
            "'# k_sensor_N_per_mm = ...' line or the rigs' force_gauge.stiffness_N_per_mm)"]
    field = "z_um" if causes[0].startswith("z_um") else "force_N"
    allowed = "F/K_s <= z at every reading (a positive element deflection z - F/K_s)"
    return CalibrationError(
        f"{info.path}: element {element}: {fitted}: the force gauge's own deflection F/K_s "
        f"exceeds the Z travel at {count} of {d.force_N.size} readings (at {place}: "
        f"force_N = {d.force_N[worst]:g} N, F/K_s = {taken_um[worst]:.4g} um > z_um = "
        f"{d.z_travel_um[worst]:.4g} um, K_s = {k_s:g} N/mm): the gauge's compliance takes "
        f"more than the travel, so the element's deflection comes out negative: allowed "
        f"{allowed}; likely {'; or '.join(causes)}", field,
        f"{place}: {field} = {(d.z_travel_um if field == 'z_um' else d.force_N)[worst]:g}",
        allowed)
