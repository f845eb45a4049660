"""An export folder holds one whole set of files: the old one or the new one,
whatever happens (a kill at any moment, Ctrl-C, a refused folder, an OS
error); files an earlier design wrote and this one does not are removed,
files tactcad never wrote are kept."""

from __future__ import annotations

import hashlib
import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import ctrl_c_at_its_default, run_cli, warm_store_copy, with_default_companions
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.store import Store

# one worker for the module: its ``warm`` store is filled once, not once per worker
pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("export-set")]


def tactcad(*args: str, cwd: Path | None = None) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "tactcad.cli", *args], cwd=cwd,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=ctrl_c_at_its_default)


def run(*args: str) -> subprocess.CompletedProcess:
    return run_cli(*args)


def small_design(tmp: Path) -> Path:
    """The default design with 4 columns: fewer elements, spacers, other files."""
    text = DEFAULT_DESIGN.read_text(encoding="utf-8")
    text = text.replace("columns = 5", "columns = 4")
    text = text.replace("lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0, 5.0, 7.0]",
                        "lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0]")
    path = tmp / "small.toml"
    path.write_text(text, encoding="utf-8")
    return with_default_companions(path)


def whole_set(out: Path) -> tuple[str, set[str]]:
    """(design sha256, paths) of the set in ``out``, after proving that every
    file its manifest lists is there with its sha256 and no other file of a
    tactcad set is."""
    man = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    listed = {f["path"]: f["sha256"] for f in man["files"]}
    for rel, sha in listed.items():
        assert hashlib.sha256((out / rel).read_bytes()).hexdigest() == sha, rel
    present = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()}
    assert present - set(listed) <= {"manifest.json", "my_notes.txt"}, present - set(listed)
    return man["design"]["sha256"], set(listed)


@pytest.fixture(scope="module")
def warm(tmp_path_factory, default_store) -> Path:
    """A store with both designs' jobs in it, so exports in the tests take seconds."""
    tmp = tmp_path_factory.mktemp("warm")
    store = warm_store_copy(default_store, tmp / "store")
    assert run("export", "--cache", str(store), "--out", str(tmp / "first"),
               "--design", str(small_design(tmp))).returncode == 0
    return store


def test_a_smaller_design_removes_the_old_files_and_keeps_foreign_ones(tmp_path, warm):
    out = tmp_path / "out"
    assert run("export", "--cache", str(warm), "--out", str(out)).returncode == 0
    (out / "my_notes.txt").write_text("keep me")
    big_hash, big = whole_set(out)
    small = small_design(tmp_path)
    assert run("export", "--design", str(small), "--cache", str(warm), "--out",
               str(out)).returncode == 0
    small_hash, files = whole_set(out)
    assert small_hash != big_hash
    gone = big - files
    assert "dxf/spacer_qty8.dxf" in gone and not (out / "dxf/spacer_qty8.dxf").exists()
    assert (out / "my_notes.txt").read_text() == "keep me"
    assert not list(tmp_path.glob(".out.staging-*"))


def test_a_kill_at_any_moment_leaves_one_whole_set(tmp_path, warm):
    """SIGKILL at moments spread over a whole export's time, measured here
    (from the warm store, so most of it is fetching, writing and swapping in
    the set, not making jobs); the two designs in turn, so each kill lands on
    a set that a finished run would replace."""
    out = tmp_path / "out"
    small = small_design(tmp_path)
    designs = [str(small), str(DEFAULT_DESIGN)]
    start = time.perf_counter()
    whole = tactcad("export", "--cache", str(warm), "--out", str(out))
    assert whole.wait(timeout=600) == 0
    seconds = time.perf_counter() - start
    for k, share in enumerate((0.2, 0.5, 0.65, 0.75, 0.85, 0.92, 1.0, 1.1)):
        proc = tactcad("export", "--design", designs[k % 2], "--cache", str(warm), "--out",
                       str(out))
        try:
            proc.wait(timeout=share * seconds)  # a run that ends sooner is not waited for
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGKILL)
            proc.wait()
        whole_set(out)  # the old set or the new one, whole
    assert run("export", "--cache", str(warm), "--out", str(out)).returncode == 0
    whole_set(out)
    assert not list(tmp_path.glob(".out.staging-*"))  # the next run cleared the leftovers


def test_ctrl_c_is_one_line_and_keeps_the_old_set(tmp_path, warm):
    out = tmp_path / "out"
    assert run("export", "--cache", str(warm), "--out", str(out)).returncode == 0
    before = whole_set(out)
    proc = tactcad("export", "--no-cache", "--out", str(out))
    for line in proc.stderr:  # the run is under way: jobs are being made
        if line.startswith("["):
            break
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    if proc.returncode == 0:
        pytest.skip("the export finished before the interrupt")
    assert proc.returncode == 130 and "Traceback" not in err
    assert err.strip().splitlines()[-1].startswith("tactcad: interrupted")  # after the progress
    assert whole_set(out) == before


@pytest.mark.parametrize("target", ["/", "/usr", "FILE", "FOREIGN", "."])
def test_refused_out_folders_write_nothing(tmp_path, target):
    (tmp_path / "FILE").write_text("x")
    (tmp_path / "FOREIGN").mkdir()
    (tmp_path / "FOREIGN" / "thesis.tex").write_text("x")
    before = sorted(p.name for p in tmp_path.rglob("*"))
    out = target if target.startswith("/") else str(tmp_path / target) if target != "." else "."
    proc = run_cli("export", "--out", out, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.startswith("tactcad: error: --out") and "Traceback" not in proc.stderr
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


@pytest.mark.parametrize("argv", [
    ("export", "--out", "/usr/tactcad-test-exp"), ("export", "--out", "/etc/tactcad-test-exp"),
    ("check", "--out", "/usr/tactcad-test-exp"),
    ("diff", "OLD", "NEW", "--out", "/usr/tactcad-test-exp"),
    ("sweep", "grid", "--out", "/usr/tactcad-test-exp"),
    ("die", "--jaw", "5", "--kr-over-km", "6", "--kobj-range", "1", "8", "--full-scale-force",
     "0.008", "--out", "/usr/tactcad-test-exp")])
def test_every_out_folder_below_a_system_folder_is_refused_by_the_one_rule(tmp_path, argv):
    from tactcad.atomic import SYSTEM_RULE

    (tmp_path / "OLD").mkdir()
    (tmp_path / "NEW").mkdir()
    for name in ("OLD", "NEW"):
        (tmp_path / name / "manifest.json").write_text('{"files": []}')
    out = argv[-1]
    proc = run_cli(*argv, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr == f"tactcad: error: --out = '{out}': allowed a folder {SYSTEM_RULE}\n"
    assert not Path(out).exists()


def test_the_system_folder_rule_refuses_the_trees_and_allows_users_folders(tmp_path):
    from tactcad.atomic import in_system_folder

    assert all(in_system_folder(p) for p in ("/", "/etc", "/usr/x", "/etc/a/b", "/var", "/home"))
    assert not any(in_system_folder(p) for p in ("/tmp/x", "/home/x", "/var/tmp/x", tmp_path))


def test_export_help_says_which_out_folders_are_refused(capsys):
    from tactcad.cli import main

    with pytest.raises(SystemExit):
        main(["export", "--help"])
    assert "anything below /bin, /boot, /dev, /etc" in " ".join(capsys.readouterr().out.split())


def test_an_out_folder_under_a_file_is_one_line_naming_out_and_the_path(tmp_path):
    (tmp_path / "plain_file").write_text("x")
    proc = run("export", "--no-cache", "--out", str(tmp_path / "plain_file" / "out"))
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert proc.stderr.startswith("tactcad: error: --out ")
    assert "plain_file" in proc.stderr and "is a file, not a folder" in proc.stderr


@pytest.mark.parametrize("command", [("export",), ("check",)])
def test_an_out_folder_that_cannot_be_made_is_refused_in_words_before_any_work(
        tmp_path, monkeypatch, command):
    """A folder the file system will not make (as /proc takes none): one line naming --out,
    the path and the reason, no traceback, nothing written beside it."""
    import errno
    import tempfile

    parent = tmp_path / "refuses"
    parent.mkdir()
    made = tempfile.mkdtemp

    def mkdtemp(suffix=None, prefix=None, dir=None):  # the folder takes no new folder
        if dir is not None and Path(dir) == parent:
            raise OSError(errno.EROFS, "Read-only file system", str(dir))
        return made(suffix, prefix, dir)

    monkeypatch.setattr(tempfile, "mkdtemp", mkdtemp)
    out = parent / "x"
    proc = run_cli(*command, "--out", str(out), cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    last = proc.stderr.strip().splitlines()[-1]
    assert last.startswith("tactcad: error: --out ") and str(out) in last, proc.stderr
    assert "read-only file system" in last and "Traceback" not in proc.stderr
    assert list(parent.iterdir()) == []


def test_the_store_is_best_effort(tmp_path):
    """A store that cannot be written costs time, never the export."""
    (tmp_path / "not_a_dir").write_text("x")
    store = Store(tmp_path / "not_a_dir" / "store")
    assert store.memo("k" * 64, lambda: 42) == 42
    store.keep("k" * 64, tmp_path, [])
    assert store.fetch("k" * 64, tmp_path) is None


def test_an_incremental_export_writes_the_bytes_of_a_cold_one(tmp_path, warm, arm_changed_cold):
    """One arm changed, exported over a store that holds the old design's jobs
    (most files come from the store, a few are rebuilt), gives the very files
    of the same design exported cold."""
    changed, cold = arm_changed_cold
    proc = run("export", "--design", str(changed), "--cache", str(warm), "--out",
               str(tmp_path / "incremental"), "--json")
    assert proc.returncode == 0, proc.stderr
    summary = json.loads(proc.stdout)
    assert 0 < summary["jobs_run"] < summary["jobs_reused"]
    inc = tmp_path / "incremental"
    files = sorted(p.relative_to(cold).as_posix() for p in cold.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(inc).as_posix() for p in inc.rglob("*") if p.is_file())
    for rel in files:
        assert (inc / rel).read_bytes() == (cold / rel).read_bytes(), rel


def test_an_output_path_cannot_leave_the_export_folder(tmp_path):
    from tactcad.errors import ExportPathError
    from tactcad.export.run import _inside

    (tmp_path / "out").mkdir()
    assert _inside(tmp_path / "out", "scenes/a.step") == (tmp_path / "out/scenes/a.step").resolve()
    for bad in ("../escaped.step", "scenes/../../x", "/etc/passwd"):
        with pytest.raises(ExportPathError, match="would leave"):
            _inside(tmp_path / "out", bad)


@pytest.mark.parametrize("argv", [
    ("die", "--kr-over-km", "10", "--kobj-range", "0.5", "5", "--full-scale-force", "0.009",
     "--jaw", "5"),
    ("atlas", "--jaw", "10", "--points", "2"),
    ("diff", "OLD", "OLD"),
    ("sweep", "montecarlo", "--samples", "2"),
])
def test_other_commands_refuse_an_out_folder_that_cannot_be_made_in_words(tmp_path, argv):
    """Each command that writes into --out DIR: a folder under a file is refused on one line
    naming --out, the path and why, with no traceback and nothing made."""
    from tactcad.atomic import unmakeable_folder

    (tmp_path / "plain_file").write_text("x")
    out = tmp_path / "plain_file" / "out"
    design = Path(__file__).resolve().parents[2] / "hardware" / "macro_array" / "macro_array.toml"
    argv = [str(design) if a == "OLD" else a for a in argv]
    before = sorted(p.name for p in tmp_path.rglob("*"))
    proc = run_cli(*argv, "--out", str(out), "--json", cwd=tmp_path)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    err = json.loads(proc.stdout)["error"]
    assert err["field"] == "--out" and err["value"] == str(out)
    assert unmakeable_folder(out) in err["message"]
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


def test_unmakeable_folder_says_why_and_leaves_nothing(tmp_path):
    from tactcad.atomic import unmakeable_folder

    (tmp_path / "f").write_text("x")
    assert unmakeable_folder(tmp_path / "new" / "deeper") is None
    assert unmakeable_folder(tmp_path / "f" / "x") == f"{tmp_path / 'f'} is a file, not a folder"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f"]


def test_a_second_export_to_a_folder_being_written_is_refused_and_the_lock_goes(tmp_path):
    """Two exports to one --out at once: the second removed the first's staging folder
    (".../review/wirecut.FCStd: No such file or directory", exit 3)."""
    from tactcad.atomic import writing_lock

    out = tmp_path / "exports"
    with writing_lock(out) as lock:  # as a run writing it holds it
        assert lock.parent == tmp_path and lock.name == ".exports.lock"
        proc = run_cli("export", "--no-cache", "--out", out, cwd=tmp_path)
        assert proc.returncode == 2, proc.stderr
        assert proc.stderr == (f"tactcad: error: --out {out}: another tactcad run is writing "
                               "this folder now; wait for it to end, or name another folder\n")
        assert not out.exists() and [p.name for p in tmp_path.iterdir()] == [".exports.lock"]
    assert list(tmp_path.iterdir()) == []  # no lock file left beside it, none in it


def test_a_killed_run_leaves_the_folder_unlocked(tmp_path):
    from tactcad.atomic import writing_lock
    from tactcad.errors import ExportPathError

    out = tmp_path / "exports"
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys, time; from pathlib import Path; "
         "from tactcad.atomic import writing_lock\n"
         f"with writing_lock(Path({str(out)!r})):\n print('held', flush=True); time.sleep(60)"],
        stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        with pytest.raises(ExportPathError, match="another tactcad run is writing"):
            with writing_lock(out):
                pass
    finally:
        holder.kill()
        holder.wait()
    with writing_lock(out):  # the killed holder's lock freed with its process
        pass
    assert list(tmp_path.iterdir()) == []
