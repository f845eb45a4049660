"""``tactcad atlas``: the table, figure and summary written, a second run reusing the kept
table, clean refusals, and the same table on an existing Dask cluster as on a local one."""

from __future__ import annotations

import json
import math
import os
import re
import shlex
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import run_cli

import tactcad

#: The 5 mm jaw holds the die alone (the comb stands too tall): cheap points.
DIE_ATLAS = ["atlas", "--jaw", "5", "--points", "6", "--force-range", "0.001", "0.05",
             "--workers", "1", "--quiet"]


def table(path: Path) -> list[dict]:
    """The Parquet table's rows, NaN (a figure a refused point has not) read as None so that
    two tables compare equal cell by cell."""
    import math

    import pyarrow.parquet as pq

    return [{k: None if isinstance(v, float) and math.isnan(v) else v for k, v in r.items()}
            for r in pq.read_table(path).to_pylist()]


@pytest.mark.slow  # a local Dask cluster started (about 25 s)
def test_an_atlas_is_written_and_its_second_run_reuses_the_kept_table(tmp_path):
    out, cache = tmp_path / "out", tmp_path / "cache"
    r = run_cli(*DIE_ATLAS, "--out", out, "--cache", cache, "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    s = json.loads(r.stdout)
    rows = table(out / "atlas.parquet")
    assert len(rows) == 6 and {r["product"] for r in rows} == {"mems-die"}
    assert s["reused"] is False and s["points_per_s"] > 0
    feasible = [r for r in rows if r["feasible"]]
    assert feasible and len(s["front"]) >= 1
    assert all(f["command"].startswith("tactcad design --jaw 5 --construction mems-die")
               for f in s["front"])
    # every front point is feasible, and no feasible point beats it in force, span and
    # resolution at once
    for f in s["front"]:
        assert any(r["point"] == f["point"] and r["feasible"] for r in rows)
    assert (out / "atlas_front.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert list(cache.rglob("*.parquet"))
    again = run_cli(*DIE_ATLAS, "--out", out, "--cache", cache, "--json")
    assert json.loads(again.stdout)["reused"] is True
    assert table(out / "atlas.parquet") == rows


def allowed_text(r) -> str:
    """The allowed range a refusal states (after "allowed ")."""
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    return r.stderr.split("allowed ", 1)[1].split(" (see ", 1)[0].strip()


@pytest.mark.parametrize("command, option, outside, inside_parser_range", [
    ("atlas", "--force-range", ["0", "0"], ["2000", "5000"]),
    ("atlas", "--kobj-span", ["0", "1"], ["0.5", "2"]),
    ("tolerance", "--samples", ["0"], ["1"]),
])
def test_an_option_states_one_range(command, option, outside, inside_parser_range):
    extra = ["--jaw", "5"] if command == "atlas" else []
    first = allowed_text(run_cli(command, *extra, option, *outside))
    second = allowed_text(run_cli(command, *extra, option, *inside_parser_range))
    assert first == second


@pytest.mark.parametrize("argv, field", [
    (["--jaw", "7"], "--jaw"),
    (["--jaw", "5", "--force-range", "2", "1"], "--force-range"),
    (["--jaw", "5", "--columns-range", "1", "3"], "--columns-range"),
    (["--jaw", "5", "--out", "/etc/atlas"], "--out"),
    # each point's targets are design's: refused before any task, not inside every task
    (["--jaw", "5", "--kobj-span", "1", "1"], "--kobj-span"),
    (["--jaw", "5", "--kr-over-km-range", "1.000001", "2"], "--kr-over-km-range"),
    (["--jaw", "5", "--kobj-centre", "1e4", "1e4"], "--kobj-centre"),
])
def test_bad_atlas_options_are_refused_without_a_traceback(tmp_path, argv, field):
    r = run_cli("atlas", "--out", tmp_path / "out", *argv, "--json")
    assert r.returncode != 0
    error = json.loads(r.stdout)["error"]
    assert error["field"] == field and "Traceback" not in r.stdout + r.stderr
    assert "Compute Failed" not in r.stderr and not (tmp_path / "out").exists()


EXAMPLES = Path(tactcad.__file__).parent / "examples"


def die_project_with_jaw_file(tmp_path: Path) -> Path:
    """The 5 mm die example copied to ``tmp_path/p5`` with its jaw as a file beside it
    (``jaw.toml``, the 5 mm class's table): the design file's path."""
    import shutil

    from tactcad.partlib.grasper_jaw import class_jaw_file_table

    folder = tmp_path / "p5"
    shutil.copytree(EXAMPLES / "grasper_jaw_5mm_mems", folder)
    (folder / "jaw.toml").write_text("[grasper_jaw]\n" + "".join(
        f"{k} = {json.dumps(v)}\n" for k, v in class_jaw_file_table("5").items()),
        encoding="utf-8")
    design = folder / "grasper_jaw_5mm_mems.toml"
    text = design.read_text(encoding="utf-8")
    design.write_text(re.sub(r'(?m)^jaw = "5"', 'jaw = "jaw.toml"', text), encoding="utf-8")
    return design


@pytest.mark.parametrize("project, why", [
    ("macro_array/macro_array.toml", "names no grasper jaw"),
    ("no_such_design.toml", "no such file"),
    ("macro_array", "names no grasper jaw"),  # a project folder: its one design file
])
def test_a_project_without_a_jaw_is_refused_naming_the_option(tmp_path, project, why):
    r = run_cli("atlas", "--project", EXAMPLES / project, "--json")
    assert r.returncode != 0
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--project" and why in error["message"]
    assert "Traceback" not in r.stdout + r.stderr


def test_a_metal_projects_jaw_is_its_class_or_the_labs_table_it_states(tmp_path):
    # the comb example describes its trocar class's own jaw: read as a jaw file, every key of a
    # lab's jaw was "not given" and no comb project had an atlas
    from tactcad.commands.atlas import PROJECT_ATLAS_FOLDER, project_jaw

    comb = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
    assert project_jaw(str(comb)) == ("10", str(comb.parent / PROJECT_ATLAS_FOLDER))
    lab = tmp_path / "lab.toml"
    lab.write_text(comb.read_text(encoding="utf-8").replace("length_mm = 34.0",
                                                           "length_mm = 36.0"), encoding="utf-8")
    assert "length_mm = 36.0" in lab.read_text(encoding="utf-8")
    assert project_jaw(str(lab))[0] == str(lab)  # a lab's own jaw: the table it states


def test_a_jaw_and_a_project_together_are_refused(tmp_path):
    r = run_cli("atlas", "--jaw", "5", "--project", EXAMPLES / "macro_array" / "macro_array.toml")
    assert r.returncode == 2 and "not allowed with" in r.stderr


@pytest.mark.slow  # a die judged at two points
def test_a_projects_atlas_is_its_jaws_and_lands_in_its_folder_for_the_review_page(tmp_path):
    import shutil

    from tactcad.export.atlas_view import atlas_view

    folder = tmp_path / "p5"
    shutil.copytree(EXAMPLES / "grasper_jaw_5mm_mems", folder)
    design = folder / "grasper_jaw_5mm_mems.toml"
    r = run_cli("atlas", "--project", design, "--points", "2", "--force-range", "0.002",
                "0.02", "--workers", "1", "--no-cache", "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    summary = json.loads(r.stdout)
    assert summary["jaw"] == "5"  # the die file's jaw
    assert Path(summary["files"]["table"]).parent == folder / "atlas"
    view = atlas_view(design)
    assert len(view["points"]) == summary["records"] == 2
    assert all(p["command"].startswith("tactcad design --jaw 5 ") for p in view["points"])


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def started(argv: list[str], env: dict) -> subprocess.Popen:
    return subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


def scheduler_answers(address: str, workers: int, timeout_s: float = 60.0) -> bool:
    from distributed import Client

    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        try:
            with Client(address, timeout="5s") as client:
                if len(client.scheduler_info()["workers"]) >= workers:
                    return True
        except (OSError, TimeoutError):
            pass
        time.sleep(1.0)
    return False


@pytest.mark.slow  # a scheduler and two worker processes started, a local cluster too
def test_an_atlas_through_a_scheduler_address_gives_the_local_runs_table(tmp_path):
    src = str(Path(tactcad.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": src, "OMP_NUM_THREADS": "1"}
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "dask"]
    procs = [started(dask + ["scheduler", "--host", "127.0.0.1", "--port", str(port),
                             "--no-dashboard"], env)]
    try:
        for _ in range(2):
            procs.append(started(dask + ["worker", address, "--nthreads", "1",
                                         "--no-dashboard"], env))
        assert scheduler_answers(address, 2), "the scheduler and its workers did not start"
        remote = run_cli(*DIE_ATLAS, "--scheduler", address, "--no-cache",
                         "--out", tmp_path / "remote")
        assert remote.returncode == 0, remote.stderr
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
    local = run_cli(*DIE_ATLAS, "--no-cache", "--out", tmp_path / "local")
    assert local.returncode == 0, local.stderr
    assert table(tmp_path / "remote" / "atlas.parquet") == \
        table(tmp_path / "local" / "atlas.parquet")
    assert shlex.split(table(tmp_path / "local" / "atlas.parquet")[0]["command"])[:3] == \
        ["tactcad", "design", "--jaw"]


def verdict(point, product, feasible, force, span, res):
    return {"product": product, "material": "m", "point": point, "kr_over_km": 10.0,
            "kobj_lo_N_per_mm": 1.0, "kobj_hi_N_per_mm": span, "full_scale_force_N": force,
            "columns": 4, "feasible": feasible, "binding_limit": "" if feasible else "stop",
            "binding_detail": "", "design_field": "", "kobj_resolution_rel": res,
            "max_force_N": force, "lowest_first_Hz": 1e3, "sheet_mm": 1.0, "layer_um": float("nan"),
            "command": f"tactcad design --point {point}"}


def test_the_summary_counts_each_products_verdicts_and_fronts_its_own_points(tmp_path):
    from tactcad.commands.atlas import atlas_summary, read_table, write_table

    records = [verdict(0, "a", True, 1.0, 10.0, 0.1), verdict(1, "a", True, 0.5, 5.0, 0.2),
               verdict(2, "a", False, 9.0, 90.0, float("nan")),
               verdict(0, "b", True, 0.1, 2.0, 0.3)]
    write_table(tmp_path / "t.parquet", records, {"jaw": "10"})
    back = read_table(tmp_path / "t.parquet")
    assert [r["point"] for r in back] == [0, 1, 2, 0] and back[2]["feasible"] is False
    # readable by whoever reads the folder, as the figure and the summary beside it
    from tactcad.atomic import write_bytes_atomic

    sibling = write_bytes_atomic(tmp_path / "atlas.json", b"{}")
    assert (tmp_path / "t.parquet").stat().st_mode & 0o777 == sibling.stat().st_mode & 0o777
    assert sibling.stat().st_mode & 0o044  # (not private to its writer)
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary left
    (tmp_path / "atlas.json").unlink()
    s = atlas_summary(back, {"jaw": "10", "points": 3, "seed": 0, "ranges": {}, "key": "k"},
                      2.0, False, True, tmp_path)
    per = {g["product"]: g for g in s["products"]}
    assert (per["a"]["points"], per["a"]["feasible"]) == (3, 2)
    assert per["a"]["binding_limits"] == {"stop": 1}
    # a's front: point 0 alone (point 1 worse in all; point 2 refused, however strong);
    # b's only point is its own front, though a's dominates it
    assert [f["point"] for f in per["a"]["front"]] == [0]
    assert [f["point"] for f in per["b"]["front"]] == [0]
    assert s["points_per_s"] == 1.5 and "layer_um" not in per["a"]["front"][0]
    # a's boundary: its feasible forces at spans 5 and 10, the refused 9 N bounding nothing
    assert max(b["largest_feasible_force_N"] for b in per["a"]["boundary"]) == 1.0
    assert [b["largest_feasible_force_N"] for b in per["b"]["boundary"]] == [0.1]
    json.dumps(s, allow_nan=False)  # the summary is JSON as it is written


def test_the_figure_draws_each_products_feasible_boundary(tmp_path):
    from tactcad.commands.atlas import boundary_path, front_figure

    records = [verdict(0, "a", True, 1.0, 10.0, 0.1), verdict(1, "a", True, 0.5, 5.0, 0.2),
               verdict(2, "a", False, 9.0, 90.0, float("nan"))]
    front_figure(records, records[:1], tmp_path / "f.svg", "10")
    text = (tmp_path / "f.svg").read_text(encoding="utf-8")
    assert "feasible boundary, m" in text and "Pareto front" in text
    front_figure(records, records[:1], tmp_path / "f.png", "10")  # the docs' pictures
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert boundary_path([(2.0, 10.0, 0.3), (10.0, 50.0, 0.02)]) == \
        ([0.3, 0.3, 0.02, 0.02], [2.0, 10.0, 10.0, 50.0])


def test_each_drawn_point_carries_its_figures_and_command_for_the_hover(tmp_path):
    """The atlas's SVG: every marker has a <title> (a browser shows it on hover) with its
    targets, its figures or the limit that refused it, and its design command."""
    import re

    from tactcad.commands.atlas import front_figure

    def record(i, feasible, product="monolithic-comb", material="Ti-6Al-4V"):
        return {"product": product, "material": material, "point": i, "kr_over_km": 5.0 + i,
                "kobj_lo_N_per_mm": 0.5, "kobj_hi_N_per_mm": 5.0 + i,
                "full_scale_force_N": 0.1 * (i + 1), "columns": 4, "feasible": feasible,
                "binding_limit": None if feasible else "strength",
                "binding_detail": None if feasible else f"detail {i}",
                "kobj_resolution_rel": 0.001 if feasible else math.nan,
                "max_force_N": 1.0 if feasible else math.nan, "lowest_first_Hz": 900.0,
                "sheet_mm": 1.0, "layer_um": math.nan, "command": f"tactcad design #{i}"}

    records = [record(0, True), record(1, False), record(2, True, "mems-die", "silicon"),
               record(3, False), record(4, True)]
    path = tmp_path / "atlas.svg"
    front_figure(records, [records[0]], path, "5")
    titles = re.findall(r"<title>(.*?)</title>", path.read_text(encoding="utf-8"), re.S)
    assert len(titles) == len(records)
    for r in records:
        (mine,) = [t for t in titles if t.endswith(r["command"])]
        if r["feasible"]:
            assert "designed: K_obj resolution 0.10%" in mine and "f1 900 Hz" in mine
        else:
            assert f"refused (strength): detail {r['point']}" in mine


def test_the_lowest_first_resonance_is_modals_lowest_first_Hz_in_table_and_summary(
        tmp_path, monkeypatch):
    """The atlas named a design's lowest first resonance ``f1_Hz`` where ``tactcad modal
    --json`` names it ``lowest_first_Hz``: the table's column is renamed (schema 2, in its
    metadata and in the store's key, so a table kept before is not taken for this one), a
    table written before is read under the new name, and the summary's front points keep
    the old key beside the new one, listed in ``deprecated_keys``."""
    import pyarrow.parquet as pq

    from tactcad.commands import atlas as atlas_cmd
    from tactcad.studies import atlas_files

    records = [verdict(0, "a", True, 1.0, 10.0, 0.1)]
    atlas_cmd.write_table(tmp_path / "t.parquet", records, {"jaw": "10"})
    table = pq.read_table(tmp_path / "t.parquet")
    assert "lowest_first_Hz" in table.column_names and "f1_Hz" not in table.column_names
    assert json.loads(table.schema.metadata[b"tactcad.atlas"])["schema"] == 2
    old = [{("f1_Hz" if k == "lowest_first_Hz" else k): v for k, v in r.items()}
           for r in records]  # a table of schema 1
    pq.write_table(pa_table(old), tmp_path / "old.parquet")
    [was], [now] = (atlas_cmd.read_table(tmp_path / n) for n in ("old.parquet", "t.parquet"))
    assert list(was) == list(now) and was["lowest_first_Hz"] == now["lowest_first_Hz"] == 1e3
    s = atlas_cmd.atlas_summary(records, {"jaw": "10", "points": 1, "seed": 0, "ranges": {},
                                          "key": "k"}, 1.0, False, True, tmp_path)
    assert s["deprecated_keys"] == {"f1_Hz": "lowest_first_Hz"}
    for point in s["front"] + s["products"][0]["front"]:
        assert point["lowest_first_Hz"] == point["f1_Hz"] == 1e3
    # the store's key of the same atlas moves with the schema
    from types import SimpleNamespace

    from tactcad.partlib.grasper_jaw import jaw_room

    atlas = SimpleNamespace(room=jaw_room("10"), products=(("m", "x"),))
    key = atlas_cmd.atlas_key(atlas, [{"point": 0}])
    monkeypatch.setattr(atlas_files, "ATLAS_SCHEMA", 1)
    assert atlas_cmd.atlas_key(atlas, [{"point": 0}]) != key


def pa_table(rows: list[dict]):
    import pyarrow as pa

    return pa.Table.from_pylist(rows)


def test_without_batch_the_tasks_are_about_32_a_worker_thread_and_at_most_32_points():
    from tactcad.commands.atlas import MAX_AUTO_BATCH, TASKS_PER_WORKER, auto_batch

    assert auto_batch(10_000, 2) == MAX_AUTO_BATCH  # a die atlas: few, full tasks
    assert auto_batch(16, 2) == 1 and auto_batch(1, 0) == 1  # a comb's handful: one a task
    for points in (1, 63, 64, 65, 640, 2047, 2048, 5000, 100_000):
        for threads in (1, 2, 3, 8):
            size = auto_batch(points, threads)
            assert 1 <= size <= MAX_AUTO_BATCH
            tasks = math.ceil(points / size)
            # enough tasks to even out the workers, unless the batches are full or single
            assert tasks >= min(points, threads * TASKS_PER_WORKER) or size == MAX_AUTO_BATCH


def test_without_batch_the_run_takes_the_automatic_size(monkeypatch):
    # the command line as parsed, on a one-thread cluster in this process; the judging
    # itself is the run's (recorded here, not run: the sizes are what is asked)
    import contextlib

    import tactcad.studies.design_atlas as design_atlas
    import tactcad.studies.sweeps as sweeps
    from tactcad.cli import parse_checked
    from tactcad.commands.atlas import auto_batch, judged

    sizes = []

    def recorded(atlas, points, client, batch_size=1, **kwargs):
        sizes.append(batch_size)
        return [], True

    @contextlib.contextmanager
    def threads_here(scheduler, workers):  # one worker thread in this process: no spawn
        from distributed import Client

        with Client(processes=False, n_workers=1, threads_per_worker=1,
                    dashboard_address=None) as client:
            yield client

    monkeypatch.setattr(design_atlas, "run_atlas", recorded)
    monkeypatch.setattr(sweeps, "dask_client", threads_here)
    points = [{}] * 70
    judged(None, points, parse_checked(DIE_ATLAS))
    judged(None, points, parse_checked([*DIE_ATLAS, "--batch", "5"]))
    assert sizes == [auto_batch(70, 1), 5] and sizes[0] == 2


@pytest.fixture
def strangers():
    """Two local services that are not Dask schedulers, on ephemeral ports: one replies a
    few bytes of HTTP and hangs up, one is an HTTP server that waits for a request line."""
    import http.server
    import socketserver
    import threading

    class Junk(socketserver.BaseRequestHandler):
        def handle(self):
            self.request.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")

    servers = [socketserver.ThreadingTCPServer(("127.0.0.1", 0), Junk),
               http.server.ThreadingHTTPServer(("127.0.0.1", 0),
                                               http.server.SimpleHTTPRequestHandler)]
    for server in servers:
        server.daemon_threads = True
        threading.Thread(target=server.serve_forever, daemon=True).start()
    yield [f"tcp://127.0.0.1:{server.server_address[1]}" for server in servers]
    for server in servers:
        server.shutdown()
        server.server_close()


def test_a_service_that_is_not_a_scheduler_is_refused_in_time_naming_the_address(
        strangers, monkeypatch, tmp_path):
    from tactcad.studies import sweeps

    monkeypatch.setattr(sweeps, "SCHEDULER_TIMEOUT_S", 3.0)
    junk, http_server = strangers
    for address, words in ((junk, "not a Dask scheduler"),
                           (http_server, "no Dask scheduler answers")):
        start = time.monotonic()
        r = run_cli("atlas", "--jaw", "5", "--scheduler", address, "--json", cwd=tmp_path)
        assert time.monotonic() - start < 8.0, address
        assert not (tmp_path / "exports").exists()  # refused: no folder left behind
        assert r.returncode == 2, r.stdout + r.stderr
        message = json.loads(r.stdout)["error"]["message"]
        assert message.startswith(f"--scheduler {address}: ") and words in message
        assert "Traceback" not in r.stderr


@pytest.mark.slow  # a die judged at four points, one front point designed
def test_a_projects_front_commands_pasted_where_the_atlas_ran_leave_it_one_design(tmp_path):
    """`atlas --project ojp/ojp.toml` printed `design --jaw ojp.toml ... --out ../ojp_...`,
    which only worked from inside ojp/: pasted where the atlas ran it was refused. The
    printed commands are named from there; the review page's (the table in the project)
    from the project's folder."""
    from tactcad.studies.atlas_files import read_table

    design = die_project_with_jaw_file(tmp_path)
    folder = design.parent
    argv = ["atlas", "--project", "p5/grasper_jaw_5mm_mems.toml", "--points", "4",
            "--force-range", "0.002", "0.02", "--workers", "1", "--no-cache"]
    r = run_cli(*argv, "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    front = json.loads(r.stdout)["front"]
    assert front
    for point in front:
        words = shlex.split(point["command"])
        assert words[words.index("--jaw") + 1] == "p5/jaw.toml"
        out = (tmp_path / words[words.index("--out") + 1]).resolve()
        assert out.parent == tmp_path.resolve(), point["command"]
    text_run = run_cli(*argv, cwd=tmp_path)
    assert front[0]["command"] in text_run.stdout  # the text names the same command
    pasted = shlex.split(front[0]["command"])[1:]  # without the program's name
    assert run_cli(*pasted, cwd=tmp_path).returncode == 0
    assert sorted(p.name for p in folder.glob("*.toml")) == ["grasper_jaw_5mm_mems.toml",
                                                               "jaw.toml"]
    out = (tmp_path / pasted[pasted.index("--out") + 1]).resolve()
    assert (out / f"{out.name}.toml").is_file()  # a project of its own beside this one
    # the review page's table: the same point, pasted in the project's folder
    [kept] = [row["command"] for row in read_table(folder / "atlas" / "atlas.parquet")
              if row["point"] == front[0]["point"] and row["product"] == front[0]["product"]
              and row["material"] == front[0]["material"]]
    words = shlex.split(kept)
    assert words[words.index("--jaw") + 1] == "jaw.toml"
    assert words[words.index("--out") + 1] == "../" + out.name


def test_a_projects_commands_name_its_jaw_file_from_where_they_are_pasted(tmp_path):
    # a lab's jaw is the project's design file, named as --project gave it (from elsewhere)
    from tactcad.commands.atlas import project_records
    from tactcad.studies.design_atlas import design_command

    design = tmp_path / "lab" / "lab.toml"
    design.parent.mkdir()
    design.write_text("", encoding="utf-8")
    given = str(design.relative_to(tmp_path.parent))  # as typed in the folder above
    point = {"point": 3, "kr_over_km": 8, "kobj_lo_N_per_mm": 0.4, "kobj_hi_N_per_mm": 4,
             "full_scale_force_N": 0.06, "columns": 5}
    record = {"command": design_command(given, "monolithic-comb", "17-4PH-H900", point)}
    old_cwd = Path.cwd()
    os.chdir(tmp_path.parent)
    try:
        [here] = project_records([record], given, given)
        [inside] = project_records([record], given, given, design.parent)
    finally:
        os.chdir(old_cwd)
    point_folder = "lab_comb_174ph_3"
    words = shlex.split(here["command"])
    assert words[words.index("--jaw") + 1] == given
    assert words[words.index("--out") + 1] == f"{tmp_path.name}/{point_folder}"
    words = shlex.split(inside["command"])
    assert words[words.index("--jaw") + 1] == "lab.toml"
    assert words[words.index("--out") + 1] == f"../{point_folder}"


#: Where a stop reaches a run: while its cluster starts, after its judging stopped with
#: nothing finished, while its cluster closes, and while its files are written.
STOP_MOMENTS = ("cluster start", "judging", "cluster close", "files written")
ATLAS_FILES = {"atlas.parquet", "atlas_front.svg", "atlas.json"}


@pytest.mark.parametrize("moment", STOP_MOMENTS)
def test_a_stop_at_any_moment_ends_130_in_one_line_with_the_whole_file_set(
        tmp_path, monkeypatch, moment):
    import contextlib
    import signal

    import tactcad.commands.atlas as atlas_cmd
    import tactcad.studies.design_atlas as design_atlas
    import tactcad.studies.sweeps as sweeps

    refused = [verdict(0, "mems-die", False, 0.01, 5.0, float("nan"))]

    class Client:
        def nthreads(self):
            return {"worker": 1}

    @contextlib.contextmanager
    def cluster(scheduler, workers):  # the stop raised where Ctrl-C lands
        if moment == "cluster start":
            raise KeyboardInterrupt
        yield Client()
        if moment == "cluster close":
            raise KeyboardInterrupt

    def judging(atlas, points, client, batch_size=1, **kwargs):
        # run_atlas's own answer to a stop: what finished (nothing), not complete
        return ([], False) if moment == "judging" else (refused, True)

    drawn = atlas_cmd.front_figure

    def drawn_under_a_stop(*args, **kwargs):
        signal.raise_signal(signal.SIGINT)  # Ctrl-C between the table and the figure
        drawn(*args, **kwargs)

    monkeypatch.setattr(sweeps, "dask_client", cluster)
    monkeypatch.setattr(design_atlas, "run_atlas", judging)
    if moment == "files written":
        monkeypatch.setattr(atlas_cmd, "front_figure", drawn_under_a_stop)
    out = tmp_path / "out"
    # Ctrl-C as an interpreter takes it (a test worker of a parallel run ignores SIGINT)
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        r = run_cli(*DIE_ATLAS[:-1], "--no-cache", "--out", out)
    finally:
        signal.signal(signal.SIGINT, handler)
    assert r.returncode == 130, r.stdout + r.stderr
    assert "Traceback" not in r.stdout + r.stderr
    assert {p.name for p in out.iterdir()} == ATLAS_FILES  # every file of the set
    summary = json.loads((out / "atlas.json").read_text(encoding="utf-8"))
    figure = (out / "atlas_front.svg").read_text(encoding="utf-8")
    if moment == "files written":  # judged whole; the stop waited for the last file
        assert summary["complete"] is True and summary["records"] == 1
        assert "interrupted; this run had already written" in r.stderr
        return
    assert summary["complete"] is False
    assert "(stopped: the points that finished are kept)" in r.stdout
    if moment == "cluster close":  # what finished before the stop is kept
        assert summary["records"] == 1 and "no feasible design among the 1" in figure
    else:
        assert summary["records"] == 0 and "no target point was judged" in figure


@pytest.mark.slow  # a local cluster started in a new interpreter (about 10 s)
def test_ctrl_c_during_a_real_atlas_ends_130_without_a_traceback_or_litter(tmp_path):
    import signal

    src = str(Path(tactcad.__file__).resolve().parents[1])
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = {**os.environ, "PYTHONPATH": src, "TMPDIR": str(scratch)}
    out = tmp_path / "out"
    # 2000 die points take over a minute: the stop comes long before their end
    argv = [sys.executable, "-m", "tactcad.cli", "atlas", "--jaw", "5", "--points", "2000",
            "--workers", "1", "--no-cache", "--out", str(out)]
    p = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, cwd=tmp_path,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    err = []
    try:
        for line in p.stderr:  # the first batch done: the cluster is up and judging
            err.append(line)
            if "batches" in line:
                p.send_signal(signal.SIGINT)
                break
        stdout, rest = p.communicate(timeout=60)
    finally:
        p.kill()
    err.append(rest)
    text = stdout + "".join(err)
    assert p.returncode == 130, text
    assert "Traceback" not in text and "distributed." not in text
    assert "(stopped: the points that finished are kept)" in stdout
    assert {f.name for f in out.iterdir()} == ATLAS_FILES
    assert list(scratch.iterdir()) == []  # Dask's scratch space went with its cluster


def test_a_local_cluster_that_does_not_start_is_a_refusal_not_a_traceback(
        monkeypatch, tmp_path, capsys):
    """A user whose Dask workers cannot start (`Nanny failed to start`) got Dask's traceback
    and exit 1 (the code of a failed check): the run refuses, naming the cluster and what
    to paste instead, and leaves no folder."""
    import distributed

    from tactcad import cli

    def refuse(*args, **kwargs):
        raise RuntimeError("Nanny failed to start.")
    monkeypatch.setattr(distributed, "LocalCluster", refuse)
    monkeypatch.chdir(tmp_path)
    code = cli.main(["atlas", "--jaw", "5", "--points", "2", "--no-cache", "--json"])
    out = capsys.readouterr()
    error = json.loads(out.out)["error"]
    assert code in (2, 3) and error["exit_code"] == code
    assert "did not start (RuntimeError: Nanny failed to start.)" in error["message"]
    assert "--scheduler ADDRESS" in error["message"] and "Traceback" not in out.err
    assert not (tmp_path / "exports").exists()


def test_a_stopped_atlas_is_resumed_judging_only_the_points_it_had_not_finished(
        tmp_path, monkeypatch):
    import contextlib

    import tactcad.studies.design_atlas as design_atlas
    import tactcad.studies.sweeps as sweeps

    class Client:
        def nthreads(self):
            return {"worker": 1}

    @contextlib.contextmanager
    def cluster(scheduler, workers):
        yield Client()

    asked: list[list[int]] = []
    stop_after: list[int | None] = [2]  # points a run finishes before its stop (None: all)

    def judging(atlas, points, client, batch_size=1, **kwargs):
        asked.append([p["point"] for p in points])
        n = stop_after[0]
        done = points if n is None else points[:n]
        return ([{**verdict(p["point"], "mems-die", False, 0.01, 5.0, float("nan")),
                  "material": "silicon"} for p in done], n is None)

    monkeypatch.setattr(sweeps, "dask_client", cluster)
    monkeypatch.setattr(design_atlas, "run_atlas", judging)
    out, cache = tmp_path / "out", tmp_path / "cache"
    argv = (*DIE_ATLAS, "--out", out, "--cache", cache, "--json")
    first = run_cli(*argv)
    assert first.returncode == 130 and asked == [[0, 1, 2, 3, 4, 5]]
    assert json.loads(first.stdout)["records"] == 2
    from tactcad.atomic import changed_paths

    part = list(cache.rglob("*.partial.parquet"))
    assert part and str(part[0]) not in changed_paths()  # the store's, not the lab's file
    assert str(out / "atlas.parquet") in changed_paths()
    stop_after[0] = 1  # a second stop, after fewer points than the first finished
    second = run_cli(*argv)
    assert second.returncode == 130 and asked[-1] == [2, 3, 4, 5]
    s = json.loads(second.stdout)
    assert s["resumed_points"] == 2 and s["records"] == 3  # the kept part only grew
    stop_after[0] = None
    third = run_cli(*argv)
    assert third.returncode == 0 and asked[-1] == [3, 4, 5]
    s = json.loads(third.stdout)
    assert s["complete"] is True and s["resumed_points"] == 3
    assert [r["point"] for r in table(out / "atlas.parquet")] == [0, 1, 2, 3, 4, 5]
    assert not list(cache.rglob("*.partial.parquet"))  # the whole table kept, not the part
    fourth = run_cli(*argv)
    assert json.loads(fourth.stdout)["reused"] is True and len(asked) == 3


#: A lab's jaw for an 8 mm shaft (the docs' [grasper_jaw] keys): the comb stands too tall
#: and too wide for its pocket, the die seats.
LAB_JAW_8MM = """[grasper_jaw]
shaft_diameter_mm = 8.0
width_mm = 4.8
length_mm = 20.0
thickness_mm = 3.0
opposing_jaw_mm = 3.0
pin_diameter_mm = 1.5
pin_inset_mm = 1.3
opening_angle_deg = 40.0
pocket_depth_mm = 1.0
"""


@pytest.mark.slow  # a die judged at two points on a local cluster
def test_an_atlas_names_each_product_it_left_out_and_reuses_the_same_jaw_in_another_file(
        tmp_path):
    """The atlas of an 8 mm jaw printed only `mems-die silicon: 10/16 feasible`: the comb
    it left out was named nowhere. And the same jaw in another file was judged again."""
    (tmp_path / "LABJAW.toml").write_text(LAB_JAW_8MM, encoding="utf-8")
    argv = ["atlas", "--points", "2", "--force-range", "0.002", "0.05", "--workers", "1",
            "--quiet", "--cache", tmp_path / "cache"]
    r = run_cli(*argv, "--jaw", "LABJAW.toml", "--out", "a", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    s = json.loads(r.stdout)
    assert [g["product"] for g in s["products"]] == ["mems-die"] and s["reused"] is False
    [left] = s["left_out"]
    assert left["product"] == "monolithic-comb"
    assert left["misfit"].startswith("does not fit: height ") and "thickness_mm" in left["misfit"]
    written = json.loads((tmp_path / "a" / "atlas.json").read_text(encoding="utf-8"))
    assert written["left_out"] == s["left_out"]
    # the same jaw in another file and folder: the kept table read back, its design
    # commands naming the file this run was given
    (tmp_path / "lab").mkdir()
    (tmp_path / "lab" / "copy.toml").write_text(LAB_JAW_8MM, encoding="utf-8")
    again = run_cli(*argv, "--jaw", "lab/copy.toml", "--out", "b", "--json", cwd=tmp_path)
    assert again.returncode == 0, again.stdout + again.stderr
    moved = json.loads(again.stdout)
    assert moved["reused"] is True and moved["key"] == s["key"]
    assert moved["jaw"] == "lab/copy.toml" and moved["left_out"] == s["left_out"]
    rows = table(tmp_path / "b" / "atlas.parquet")
    assert len(rows) == 2
    assert all(shlex.split(r["command"])[shlex.split(r["command"]).index("--jaw") + 1]
               == "lab/copy.toml" for r in rows)
    text = run_cli(*argv, "--jaw", "lab/copy.toml", "--out", "b", cwd=tmp_path)
    assert text.returncode == 0, text.stdout + text.stderr
    assert f"not searched: monolithic-comb: {left['misfit']}" in text.stdout
    assert "LABJAW" not in text.stdout


def test_the_key_of_a_jaw_is_its_content_not_its_files_path(tmp_path, monkeypatch):
    from tactcad.commands.atlas import atlas_key, jaw_atlas
    from tactcad.studies.design_atlas import atlas_targets

    here, far = tmp_path / "LABJAW.toml", tmp_path / "far" / "away" / "jaw.toml"
    far.parent.mkdir(parents=True)
    here.write_text(LAB_JAW_8MM, encoding="utf-8")
    far.write_text(LAB_JAW_8MM, encoding="utf-8")
    thicker = tmp_path / "thicker.toml"
    thicker.write_text(LAB_JAW_8MM.replace("thickness_mm = 3.0", "thickness_mm = 3.2"),
                       encoding="utf-8")
    points = atlas_targets(4)
    monkeypatch.chdir(tmp_path)

    def key(jaw, pts=points):
        return atlas_key(jaw_atlas(jaw, None, (2, 8)), pts)

    assert key("LABJAW.toml") == key(str(here)) == key(str(far)) == key("far/away/jaw.toml")
    assert key("thicker.toml") != key("LABJAW.toml")  # another jaw, another key
    assert key("LABJAW.toml", atlas_targets(4, seed=1)) != key("LABJAW.toml")


def test_a_die_projects_jaw_file_is_named_from_the_working_folder_not_absolute(
        tmp_path, monkeypatch):
    # the summary showed the die's jaw file as an absolute path
    from tactcad.commands.atlas import project_jaw

    design = die_project_with_jaw_file(tmp_path)
    folder = design.parent
    monkeypatch.chdir(tmp_path)
    assert project_jaw("p5/grasper_jaw_5mm_mems.toml")[0] == "p5/jaw.toml"
    assert project_jaw(str(design))[0] == "p5/jaw.toml"
    monkeypatch.chdir(folder)
    assert project_jaw("grasper_jaw_5mm_mems.toml")[0] == "jaw.toml"
