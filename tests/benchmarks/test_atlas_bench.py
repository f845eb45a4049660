"""``tactcad bench atlas``: how it judges agreement with ``design``, how it draws the records
it checks, and (slow) the command's figures on a small die atlas."""

from __future__ import annotations

import json

import pytest
from conftest import run_cli

from tactcad.benchmarks.atlas_bench import disagreement, drawn_records


def record(point: int, feasible: bool, field: str = "--full-scale-force",
           limit: str = "strength") -> dict:
    return {"point": point, "product": "mems-die", "material": "silicon",
            "feasible": feasible, "design_field": "" if feasible else field,
            "binding_limit": "" if feasible else limit, "command": f"tactcad design --p {point}"}


def refusal(field: str, limit: str | None) -> dict:
    error = {"field": field, "message": "refused"}
    return {"error": error if limit is None else {**error, "limit": limit}}


def test_a_feasible_record_agrees_only_when_design_writes_it():
    assert disagreement(record(0, True), 0, {"design": "x.toml"}) == ""
    assert "refused" in disagreement(record(0, True), 2, refusal("--columns", "sheet"))


def test_a_refused_record_agrees_only_with_the_same_option_and_limit_code():
    r = record(1, False)
    assert disagreement(r, 2, refusal("--full-scale-force", "strength")) == ""
    assert "--columns" in disagreement(r, 2, refusal("--columns", "strength"))
    assert "stop" in disagreement(r, 2, refusal("--full-scale-force", "stop"))
    assert "limit" in disagreement(r, 2, refusal("--full-scale-force", None))
    assert disagreement(r, 0, {"design": "x.toml"}) == "design wrote it"
    # an option the atlas did not seek is not compared; the limit still is
    unsought = {**r, "design_field": ""}
    assert disagreement(unsought, 2, refusal("--columns", "strength")) == ""


def test_the_draw_takes_both_kinds_and_repeats_with_its_seed():
    records = [record(i, i % 4 == 0) for i in range(40)]
    drawn = drawn_records(records, 6, seed=3)
    assert len(drawn) == 6 and len({r["point"] for r in drawn}) == 6
    assert sum(r["feasible"] for r in drawn) == 3
    assert drawn == drawn_records(records, 6, seed=3)
    # fewer feasible than half: the rest refused
    assert sum(r["feasible"] for r in drawn_records(records[:5], 4, seed=0)) == 2
    assert drawn_records(records, 0, seed=0) == []


@pytest.mark.slow  # two local Dask clusters and a design process (about a minute)
def test_bench_atlas_prints_the_rate_the_scaling_and_the_agreement():
    r = run_cli("bench", "atlas", "--jaw", "5", "--points", "4", "--agree", "1", "--batch",
                "1", "--quiet", "--json")
    assert r.returncode == 0, r.stderr
    f = json.loads(r.stdout)
    assert f["records"] == 4 and f["points_per_s"] > 0 and f["scaling"] > 0
    assert f["same_records"] is True
    assert len(f["two_workers_cpu_s"]) == 2 and f["one_worker_cpu_s"] > 0
    assert f["cpu_scaling"] == pytest.approx(f["one_worker_cpu_s"] / max(f["two_workers_cpu_s"]))
    assert f["agreement"]["checked"] == 1 and f["agreement"]["rate"] == 1.0


@pytest.mark.parametrize("argv, needle", [
    (["--points", "1"], "--points"),
    (["--agree", "-1"], "--agree"),
    (["--material", "unobtainium"], "--material"),
])
def test_bad_bench_atlas_options_are_refused_naming_them(argv, needle):
    done = run_cli("bench", "atlas", *argv)
    assert done.returncode == 2 and needle in done.stderr and "Traceback" not in done.stderr


def test_the_bench_batches_points_as_the_atlas_command_would(monkeypatch):
    """Without --batch, each timed run cuts its points as `tactcad atlas` does for that many
    workers: one or two points a task for a comb's handful, so the last tasks even out."""
    import contextlib

    from tactcad.benchmarks import atlas_bench
    from tactcad.studies import design_atlas, sweeps

    class Client:
        def run(self, fn, *args):
            return {"w1": 0.0}

    asked = []
    monkeypatch.setattr(sweeps, "dask_client",
                        lambda address, workers: contextlib.nullcontext(Client()))
    monkeypatch.setattr(design_atlas, "run_atlas",
                        lambda atlas, points, client, batch: (asked.append(batch), ([], True))[1])
    points = [{"point": i} for i in range(64)]
    for workers in (1, 2):
        atlas_bench.timed_atlas(None, points, workers, None, warm=points[:1])
        atlas_bench.timed_atlas(None, points, workers, 8, warm=points[:1])
    assert asked == [design_atlas.auto_batch(64, 1), 8, design_atlas.auto_batch(64, 2), 8]
    assert asked[0] == 2 and asked[2] == 1
