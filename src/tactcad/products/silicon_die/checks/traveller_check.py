"""The die's traveller read against its masks: a fab can run what it says.

The check reads the traveller as written (its Markdown table: step, mask, kind, stops on) and
the die's GDS, and holds the process to the rules a cleanroom would refuse it by:

* every mask a step uses is drawn in the GDS, and every drawn mask is used by a step;
* no lithography after a step that leaves tall features (the posts) or free beams (the
  release): resist cannot be spun and patterned over them;
* no implant after the metal (the anneal an implant needs melts aluminium);
* every etch names what stops it (a layer, or a time and depth);
* the bond pads are opened after the last film that covers them (else nothing bonds);
* the wafer is diced before the beams are released (the saw's water and the tape break
  free beams).

Units: none (the steps' words).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tactcad.checks.check_result import CheckResult

#: The steps' column names in the traveller's table.
COLUMNS = ("#", "step", "mask", "kind", "what is done", "stops on", "leaves")
#: The outline layer: drawn, used by the dicing step, not a photomask.
OUTLINE = "die"


@dataclass(frozen=True)
class TravellerStep:
    """One row of a written traveller: its number, name, mask (or ""), kinds and stop."""

    number: int
    name: str
    mask: str
    kinds: frozenset[str]
    stop: str


def read_traveller(path: Path) -> list[TravellerStep]:
    """The steps of the traveller at ``path`` (its table's rows, in order).

    Raises:
        ValueError: the file has no step table of the traveller's columns.
    """
    rows, header = [], None
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        if not line.startswith("|"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            if tuple(cells) == COLUMNS:
                header = cells
            continue
        if set(cells[0]) <= {"-"}:
            continue
        cell = dict(zip(header, cells))
        mask = cell["mask"].split(" (")[0]
        kinds = frozenset(k.strip() for k in cell["kind"].split(",") if k.strip() not in ("", "-"))
        rows.append(TravellerStep(int(cell["#"]), cell["step"], "" if mask == "-" else mask,
                                  kinds, "" if cell["stops on"] == "-" else cell["stops on"]))
    if header is None:
        raise ValueError(f"{Path(path).name}: no step table ({' | '.join(COLUMNS)})")
    return rows


def _named(steps) -> str:
    return ", ".join(f"{s.number} ({s.name})" for s in steps)


def traveller_results(steps: list[TravellerStep], drawn: set[str], subject: str
                      ) -> list[CheckResult]:
    """The traveller's steps against the masks ``drawn`` in the GDS (names with shapes).

    Returns:
        One :class:`CheckResult` per rule (module doc), named ``traveller_<rule>``.
    """
    out = []
    used = {s.mask for s in steps if s.mask}
    missing, unused = sorted(used - drawn), sorted(drawn - used)
    out.append(CheckResult("traveller_masks", subject, not missing and not unused,
                           "every mask a step uses is drawn and every drawn mask used"
                           if not missing and not unused else
                           f"used but not drawn: {', '.join(missing) or 'none'}; drawn but "
                           f"used by no step: {', '.join(unused) or 'none'}"))
    blocking = [s for s in steps if s.kinds & {"tall", "release"}]
    late = [s for s in steps if "litho" in s.kinds and blocking
            and s.number > blocking[0].number]
    out.append(CheckResult("traveller_litho_order", subject, not late,
                           "no lithography over tall features or free beams" if not late else
                           f"lithography at step {_named(late)} after step "
                           f"{_named(blocking[:1])}"))
    metal = [s for s in steps if "metal" in s.kinds]
    implants_after = [s for s in steps if "implant" in s.kinds and metal
                      and s.number > metal[0].number]
    out.append(CheckResult("traveller_implants", subject, not implants_after,
                           "every implant and its anneal before the aluminium" if
                           not implants_after else
                           f"implant at step {_named(implants_after)} after the metal "
                           f"(step {_named(metal[:1])})"))
    open_etch = [s for s in steps if "etch" in s.kinds and not s.stop]
    out.append(CheckResult("traveller_etch_stops", subject, not open_etch,
                           "every etch names what stops it" if not open_etch else
                           f"etch without a stop at step {_named(open_etch)}"))
    covers = [s for s in steps if "covers_pads" in s.kinds]
    opens = [s for s in steps if "opens_pads" in s.kinds]
    pads_ok = not covers or any(o.number > covers[-1].number for o in opens)
    out.append(CheckResult("traveller_pads_open", subject, pads_ok,
                           "the bond pads opened after the last film over them" if pads_ok
                           else f"the pads stay covered: step {_named(covers[-1:])} covers "
                                "them and no later step opens them"))
    dice = [s for s in steps if "dice" in s.kinds]
    release = [s for s in steps if "release" in s.kinds]
    diced_ok = bool(dice) and (not release or dice[0].number < release[0].number)
    out.append(CheckResult("traveller_dicing", subject, diced_ok,
                           "diced before the beams are released" if diced_ok else
                           "no dicing step" if not dice else
                           f"dicing (step {_named(dice[:1])}) after the release (step "
                           f"{_named(release[:1])}): the saw's water and the tape reach free "
                           "beams"))
    return out


def drawn_masks(gds_path: Path) -> set[str]:
    """The masks of the die's GDS that hold shapes (names of
    :data:`~tactcad.products.silicon_die.vocabulary.soi_process.MASKS`)."""
    from tactcad.products.silicon_die.checks.gds_drc import mask_regions

    return {name for name, region in mask_regions(gds_path).items() if not region.is_empty()}


def traveller_checks(traveller_path: Path, gds_path: Path) -> list[CheckResult]:
    """The written traveller at ``traveller_path`` read against the GDS at ``gds_path``
    (:func:`traveller_results`); an unreadable traveller is one failed check."""
    try:
        steps = read_traveller(traveller_path)
    except (OSError, ValueError, KeyError) as exc:
        return [CheckResult("traveller_masks", traveller_path.name, False,
                            f"unreadable traveller: {exc}")]
    try:
        drawn = drawn_masks(gds_path)
    except (OSError, ValueError) as exc:
        return [CheckResult("traveller_masks", traveller_path.name, False,
                            f"its masks unreadable: {exc}")]
    return traveller_results(steps, drawn, traveller_path.name)
