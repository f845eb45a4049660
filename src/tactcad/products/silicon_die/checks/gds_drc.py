"""The die's masks read back with KLayout's own layout engine (``klayout.db``, headless):
every rule of :func:`tactcad.products.silicon_die.vocabulary.soi_process.soi_rules` (widths, spaces,
enclosures) and the read-back of the outlines the mechanics assumed (the beams left in the
device layer over the handle's cavities equal the plan's beams, each row over its own
cavity, the hard stop the plan sized; each beam's two root corners filleted at the plan's
radius, every vertex of the drawn arcs on the mask's outline; the implant equals each beam's resistor and its
reference, the references off the window; each contact on its resistor and under its
metal), as :class:`tactcad.checks.check_result.CheckResult` rows.

KLayout's region checks are edge-based (Euclidian metric): ``width_check(d)`` flags a
part of a shape narrower than d, ``space_check(d)`` two edges of different or the same
shape closer than d, ``enclosing_check(other, d)`` an edge of ``other`` within d inside
this region's edge. The GDS database unit (1 nm) is the checks' unit.
"""

from __future__ import annotations

from pathlib import Path

from tactcad.checks.check_result import CheckResult
from tactcad.products.silicon_die.vocabulary.soi_process import MASK_BY_NAME, soi_rules

#: How many violation markers a failed check quotes (um coordinates).
MARKERS_QUOTED = 3


def _regions(path: Path):
    """(layout, top cell, mask name -> merged region) of a die GDS.

    Raises:
        ValueError: the file is no GDS KLayout can read (cut short, another format), or
            holds other than one top cell; the message names the file.
        OSError: the file cannot be opened.
    """
    import klayout.db as kdb

    if not Path(path).is_file():
        raise FileNotFoundError(2, "no such file", str(path))
    layout = kdb.Layout()
    try:
        layout.read(str(path))
    except RuntimeError as exc:  # KLayout says a bad file as a RuntimeError
        raise ValueError(f"{Path(path).name}: unreadable GDS ({exc})") from None
    tops = layout.top_cells()
    if len(tops) != 1:
        raise ValueError(f"{path.name}: one top cell (the die) expected, found "
                         f"{len(tops)}")
    top = tops[0]
    regions = {}
    for name, mask in MASK_BY_NAME.items():
        index = layout.find_layer(mask.gds_layer, mask.datatype)
        region = kdb.Region() if index is None else kdb.Region(top.begin_shapes_rec(index))
        regions[name] = region.merged()
    return layout, top, regions


def mask_regions(path: Path) -> dict:
    """Mask name -> its merged region (KLayout) in the die GDS at ``path``."""
    return _regions(path)[2]


def _where(edge_pairs, dbu: float) -> str:
    """The first violation markers, as um coordinates."""
    out = []
    for ep in list(edge_pairs.each())[:MARKERS_QUOTED]:
        box = ep.bbox()
        out.append(f"({box.center().x * dbu:.1f}, {box.center().y * dbu:.1f}) um")
    return ", ".join(out)


def rule_results(path: Path, plan) -> list[CheckResult]:
    """Each rule of the die's process checked on the GDS at ``path``."""
    layout, _, regions = _regions(path)
    dbu = layout.dbu
    out = []
    for rule in soi_rules(plan.stack):
        d = int(round(rule.value_um / dbu))
        region = regions[rule.layer]
        if rule.kind == "width":
            bad = region.width_check(d)
        elif rule.kind == "space":
            bad = region.space_check(d)
        else:
            bad = regions[rule.inside].enclosing_check(region, d)
            outside = region - regions[rule.inside]
            if not outside.is_empty():
                out.append(CheckResult("gds_drc", rule.name, False,
                                       f"{outside.count()} {rule.layer} shapes outside "
                                       f"{rule.inside}"))
                continue
        n = bad.count()
        words = (f"{rule.kind} >= {rule.value_um:.3g} um ({rule.source})" if n == 0 else
                 f"{n} places below {rule.value_um:.3g} um, at {_where(bad, dbu)} "
                 f"({rule.source})")
        out.append(CheckResult("gds_drc", rule.name, n == 0, words))
    return out


def outline_results(path: Path, plan) -> list[CheckResult]:
    """The masks against the plan the mechanics used: the device layer left over the
    window (the cavities less the front etch) equals the beams the stiffness assumed, each
    row's beams over its own row's cavity (the stop the plan sized); every post on its
    beam; the die's outline the plan's."""
    import klayout.db as kdb

    from tactcad.products.silicon_die.export.gds_masks import beam_outline

    layout, _, regions = _regions(path)
    dbu = layout.dbu

    def poly(points):
        return kdb.Polygon([kdb.Point(round(x / dbu), round(y / dbu)) for x, y in points])

    beams = kdb.Region([poly(beam_outline(plan, b)) for b in plan.beams]).merged()
    window = (regions["cavity_reference"] + regions["cavity_measuring"]).merged()
    left = (window - regions["device_etch"]).merged()
    diff = left ^ beams
    out = [CheckResult("gds_outline", "beams", diff.is_empty(),
                       f"{len(plan.beams)} beams in the device layer over the window equal "
                       "the plan's" if diff.is_empty() else
                       f"{diff.count()} differences between the beams left over the window "
                       f"and the plan's, area {diff.area() * dbu * dbu:.4g} um^2")]
    from tactcad.products.silicon_die.export.gds_masks import (reference_resistor_outline,
                                                               resistor_outline)

    references = kdb.Region([poly(reference_resistor_outline(plan, b)) for b in plan.beams])
    resistors = kdb.Region([poly(resistor_outline(plan, b)) for b in plan.beams]) + references
    drawn = regions["piezo"] ^ resistors.merged()
    out.append(_rows_over_their_cavities(plan, regions, poly))
    out.append(_fillets_drawn(plan, left, dbu))
    strained = references & window
    out.append(CheckResult("gds_outline", "resistors", drawn.is_empty() and strained.is_empty(),
                           f"{len(plan.beams)} beam resistors at their roots and their "
                           "references on the frame, off the window, as the read-out assumed"
                           if drawn.is_empty() and strained.is_empty() else
                           f"{drawn.count()} implant shapes differ from the plan's; "
                           f"{strained.count()} references reach over the window"))
    stray = regions["tip"] - beams
    out.append(CheckResult("gds_outline", "posts", stray.is_empty() and
                           regions["tip"].count() == len(plan.beams),
                           f"{regions['tip'].count()} posts, each on its beam"))
    box = regions["die"].bbox()
    size = (box.width() * dbu, box.height() * dbu)
    ok = abs(size[0] - plan.die_length_um) < 1e-3 and abs(size[1] - plan.die_width_um) < 1e-3
    out.append(CheckResult("gds_outline", "die", ok,
                           f"{size[0]:g} x {size[1]:g} um (plan {plan.die_length_um:g} x "
                           f"{plan.die_width_um:g})"))
    return out


def gds_checks(path: Path, plan) -> list[CheckResult]:
    """:func:`rule_results` and :func:`outline_results` of the die GDS at ``path``; a file
    that cannot be read is one failed check naming it.

    Args:
        path: the die's GDS file.
        plan: the die's plan (:class:`tactcad.products.silicon_die.design.mems_die.DiePlan`).

    Returns:
        The checks' results (dimensions in um).
    """
    try:
        _regions(path)
    except (OSError, ValueError) as exc:
        return [CheckResult("gds_read", Path(path).name, False, str(exc))]
    return rule_results(path, plan) + outline_results(path, plan)


#: How far a drawn fillet's vertex may lie off its arc (um): the GDS's 1 nm grid, twice.
FILLET_VERTEX_TOLERANCE_UM = 2e-3


def _fillets_drawn(plan, left, dbu: float) -> CheckResult:
    """Each beam's two root fillets in the device layer left over the window (``left``,
    KLayout region): at each root corner, every vertex of the drawn quarter circle
    (:func:`tactcad.products.silicon_die.export.gds_masks.fillet_arc`) is a vertex of the
    mask's outline, on the arc of the plan's radius to the grid; a square corner, or a
    fillet of another radius, fails."""
    from tactcad.products.silicon_die.export.gds_masks import FILLET_SEGMENTS, _local, fillet_arc

    r = plan.root_fillet_um
    vertices = {(p.x, p.y) for poly in left.each() for p in poly.each_point_hull()}
    tol = FILLET_VERTEX_TOLERANCE_UM / dbu
    missing = []
    for beam in plan.beams:
        for side in (-1, +1):
            arc = _local(beam, fillet_arc(r, beam.width_um / 2, side))
            found = sum(1 for x, y in arc if _near(vertices, x / dbu, y / dbu, tol))
            if found < len(arc):
                missing.append(f"beam {beam.number} {'left' if side < 0 else 'right'} "
                               f"({found} of {len(arc)} arc vertices)")
    corners = 2 * len(plan.beams)
    return CheckResult("gds_outline", "fillets", not missing,
                       f"{corners} root corners filleted at r = {r:g} um ({FILLET_SEGMENTS} "
                       "chords a quarter circle) in the device etch's mask"
                       if not missing else
                       f"{len(missing)} of {corners} root corners not filleted at r = {r:g} "
                       f"um: {', '.join(missing[:MARKERS_QUOTED])}")


def _near(vertices, x: float, y: float, tol: float):
    """The integer-grid vertices within ``tol`` of (x, y) (database units)."""
    reach = int(tol) + 1
    ix, iy = round(x), round(y)
    return [(ix + i, iy + j) for i in range(-reach, reach + 1) for j in range(-reach, reach + 1)
            if (ix + i, iy + j) in vertices]


def _rows_over_their_cavities(plan, regions, poly) -> CheckResult:
    """Each row's beams over its own cavity (mask ``cavity_<role>``), none reaching over
    the other row's: the cavity's depth is the row's hard stop."""
    import klayout.db as kdb

    from tactcad.products.silicon_die.export.gds_masks import beam_outline

    astray = []
    for role in ("reference", "measuring"):
        row = kdb.Region([poly(beam_outline(plan, b)) for b in plan.beams if b.role == role])
        if not (row - regions[f"cavity_{role}"]).is_empty():
            astray.append(role)
    depths = ", ".join(f"{role} {d:g} um" for role, d in
                       zip(("reference", "measuring"), plan.cavity_depths_um))
    return CheckResult("gds_outline", "stops", not astray,
                       f"each row's beams over its own cavity ({depths} deep: the rows' hard "
                       "stops)" if not astray else
                       f"the {' and '.join(astray)} beams reach beyond their row's cavity")
