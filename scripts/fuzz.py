"""Random designs end to end: validate -> build every distinct part -> assemble
every scene -> checks. Prints a summary: tried / accepted / passed / failures
by class.

Usage (``make fuzz`` runs 1000 designs)::

    python scripts/fuzz.py -n 1000 [--seed 0] [--full] [--wild 0.2]

* in-domain draws (:func:`tactcad.design.domain.draw_design`) must be accepted
  and pass every check;
* ``--wild`` share of the draws take one field outside its range
  (:func:`tactcad.design.domain.draw_out_of_domain`) and must be refused
  naming that field;
* without ``--full`` the checks are the part checks (valid solid, volume and
  box against the catalogue's estimates), the scenes' interference (meshes,
  OpenCascade confirmation) and geometry sanity (indenter on the tip, tips on
  the sample...); with ``--full`` each design is also exported to a scratch
  folder and ``tactcad check``'s array and scene checks run on the files.
"""

from __future__ import annotations

import argparse
import collections
import random
import sys
import tempfile
import time
import traceback

from tactcad.design.domain import draw_design, draw_out_of_domain
from tactcad.design.project import project_from_data, project_of
from tactcad.design.rig_plan import default_rigs_data
from tactcad.design.scene_specs import DEFAULT_SCENES
from tactcad.vocabulary.schema import Problems, read_toml
from tactcad.errors import DesignError, TactcadError


def check_design(plan, rigs, scenes, *, full: bool = False) -> list[str]:
    """Build, assemble and check one accepted design; the failing checks' lines."""
    from tactcad.assembly.scene_solver import build_scene
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.catalogue.rig_catalogue import rig_parts
    from tactcad.checks.mesh_interference import check_mesh_interference
    from tactcad.checks.scene_sanity import check_scene_sanity
    from tactcad.checks.scene_checks import placed_shapes
    from tactcad.checks.solids import check_solid
    from tactcad.solids.cache import PartCache

    project = project_of(plan, rigs, scenes)
    cache = PartCache(plan)
    failed = []
    specs = {**array_parts(plan), **rig_parts(plan, rigs)}
    for spec in specs.values():
        failed += [r.line() for r in check_solid(spec, cache.solid(spec)) if not r.passed]
    for name in scenes:
        scene, solids = build_scene(project, name, cache)
        placed = placed_shapes(scene, solids)
        rep = check_mesh_interference(
            placed, scene.contacts, {i.name: i.part for i in scene.instances}, solids,
            {i.name: i.location for i in scene.instances}, confirm=True,
            part_meshes={i.part: cache.mesh(scene.specs[i.part]) for i in scene.instances})
        failed += [f"{name}: {r.line()}" for r in rep.results if not r.passed]
        failed += [f"{name}: {r.line()}" for r in
                   check_scene_sanity(scene, {p.name: p.shape for p in placed}) if not r.passed]
    if full:
        from tactcad.checks.array_checks import run_checks
        from tactcad.checks.scene_checks import run_scene_checks
        from tactcad.export.run import export

        with tempfile.TemporaryDirectory() as tmp:
            export(project, tmp, log=lambda s: None, parts=cache)
            results = run_checks(plan, tmp, cache) + run_scene_checks(project, tmp, cache=cache)
        failed += [r.line() for r in results if not r.passed]
    return failed


def failure_class(line: str) -> str:
    """The check's name of a failing check line (the word after ``FAIL``)."""
    words = line.split()
    return words[words.index("FAIL") + 1].rstrip(":") if "FAIL" in words[:-1] else line[:40]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-n", type=int, default=1000, help="designs to try (default 1000)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--wild", type=float, default=0.2,
                    help="share of draws with one field out of its range (default 0.2)")
    ap.add_argument("--full", action="store_true", help="also export and run tactcad check's checks")
    ap.add_argument("--quiet", action="store_true", help="summary only")
    args = ap.parse_args(argv)

    rigs_data, scenes_data = default_rigs_data(), read_toml(DEFAULT_SCENES, "scenes file")
    tried = accepted = passed = refused_right = 0
    classes: collections.Counter = collections.Counter()
    refusals: collections.Counter = collections.Counter()
    t0 = time.perf_counter()
    for k in range(args.n):
        rng = random.Random(args.seed * 1_000_003 + k)
        data = draw_design(rng.uniform, rng.choice, name=f"fuzz{k}")
        wild = None
        if rng.random() < args.wild:
            wild = draw_out_of_domain(rng.uniform, rng.choice)
            field, value = wild
            if field.startswith("arms.lengths_mm["):
                data["arms"]["lengths_mm"][1] = value
            else:
                section, key = field.split(".")
                data[section][key] = value
        tried += 1
        problems = Problems("fuzz.toml")
        try:
            plan, rigs, scenes = project_from_data(data, rigs_data, scenes_data, problems,
                                                   source="fuzz.toml")
        except Exception as exc:  # a traceback where a named error was due
            classes[f"validation crash {type(exc).__name__}"] += 1
            if not args.quiet:
                print(f"#{k}: validation crash\n{traceback.format_exc()}")
            continue
        if wild is not None:
            fields = [e.field for e in problems.errors]
            if wild[0] in fields:
                refused_right += 1
            else:
                classes["out-of-domain not refused by its field"] += 1
                if not args.quiet:
                    print(f"#{k}: {wild} -> {fields or 'accepted'}")
            continue
        if problems:
            for e in problems.errors:
                refusals[f"{e.file}: {e.field.split('[')[0]}"] += 1
            classes["in-domain draw refused"] += 1
            if not args.quiet:
                print(f"#{k}: refused: {problems.errors[0].line()[:300]}")
            continue
        accepted += 1
        try:
            failed = check_design(plan, rigs, scenes, full=args.full)
        except (TactcadError, DesignError) as exc:
            failed = [f"FAIL {type(exc).__name__}_raised: {str(exc)[:300]}"]
        except Exception as exc:  # kernel crash or bug: its own class
            failed = [f"FAIL crash_{type(exc).__name__}: {str(exc)[:300]}"]
        if failed:
            for c in {failure_class(f) for f in failed}:
                classes[c] += 1
            if not args.quiet:
                print(f"#{k}: {len(failed)} failing checks, e.g. {failed[0][:300]}")
        else:
            passed += 1
        if not args.quiet and (k + 1) % 10 == 0:
            print(f"  ... {k + 1} tried, {time.perf_counter() - t0:.0f} s", flush=True)
    wild_n = tried - accepted - sum(v for c, v in classes.items() if c == "in-domain draw refused") \
        - sum(v for c, v in classes.items() if c.startswith("validation crash"))
    tracebacks = sum(v for c, v in classes.items() if c.startswith(("validation crash", "crash_")))
    print(f"fuzz design files: {tried} tried, {accepted} accepted, {passed} passed every check, "
          f"{refused_right} of {wild_n} out-of-domain draws refused naming their field, "
          f"{tracebacks} tracebacks "
          f"({time.perf_counter() - t0:.0f} s, {'export + check' if args.full else 'parts + scenes'})")
    for c, v in classes.most_common():
        print(f"  failures {c}: {v}")
    for c, v in refusals.most_common(10):
        print(f"  refused by {c}: {v}")
    return 0 if not classes else 1


if __name__ == "__main__":
    sys.exit(main())
