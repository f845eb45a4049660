"""The other ways in: calibration data files and command-line option values,
drawn at random; each must be read or refused by name, never a traceback.

Usage (``make fuzz`` runs it after the design fuzz)::

    python scripts/fuzz_inputs.py --data 1000 --options 300 [--seed 0] [--quiet]

* **data files**: the example readings in every format tactcad reads (CSV
  with comma, semicolon or tab, decimal point or comma, in UTF-8, UTF-8 with
  a byte order mark, UTF-16, Windows-1252 or Latin-1, with or without the
  right ``--encoding``; LVM; TDMS), then damaged: characters or random bytes
  put in, lines cut, doubled or dropped, cells emptied or made NaN, the file
  cut short; now and then a huge file (many MB of readings, or beyond the
  size limit). Each goes through the reader and the fit that ``calibrate
  --data`` runs. An undamaged file must give the example's K (to 1e-9 N/mm);
* **options**: command lines drawn from the argument parser (every command,
  every option, by introspection), parsed and checked; for the commands that
  finish in seconds also run to the end. Exit 0/1/2/3 with at most one error
  line and no Python warning is right; anything else counts as a traceback.

Prints one line per kind: tried, read/accepted, refused, tracebacks.
"""

from __future__ import annotations

import argparse
import codecs
import contextlib
import io
import os
import random
import signal
import sys
import tempfile
import time
import traceback
import warnings
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
HW = REPO / "hardware" / "macro_array"
sys.path.insert(0, str(REPO / "tests"))  # the command-line strategies the tests use

from tactcad.paper import calibration_audit as ca  # noqa: E402
from tactcad.mechanics.calibration import CalibrationError  # noqa: E402
from tactcad.mechanics.measured_io import MAX_BYTES, parse_mapping, read_measured  # noqa: E402

DAQ_MAP = parse_mapping(["force_N=Dev1/ai0,signal_V=Dev1/ai1"])
ENCODINGS = ("utf-8", "utf-8-sig", "utf-16", "cp1252", "latin-1")


def example_rows() -> tuple[list[str], list[list[str]]]:
    lines = [ln for ln in (HW / "calibration_example.csv").read_text(encoding="utf-8").splitlines()
             if ln and not ln.startswith("#")]
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def csv_bytes(rng: random.Random, header, rows, repeat: int = 1) -> tuple[bytes, str | None, bool]:
    """A CSV in a drawn dialect; its bytes, the --encoding to give and whether that is right."""
    sep = rng.choice([",", ";", "\t"])
    decimal = "." if sep == "," else rng.choice([".", ","])
    comment = rng.choice(["# readings", "# Z in µm, force in N", "# k_sensor_N_per_mm = 57.04"])
    if decimal == ",":
        comment = comment.replace("57.04", "57,04")
    body = [sep.join(header)] + [sep.join(c.replace(".", decimal) for c in r) for r in rows] * repeat
    text = "\n".join([comment] + body) + rng.choice(["\n", "\r\n", ""])
    enc = rng.choice(ENCODINGS)
    raw = text.encode(enc)
    given = None if enc.startswith("utf") else rng.choice([enc, None, "utf-8", "no-such"])
    return raw, given, given in (enc, None) and (enc.startswith("utf") or "µ" not in text)


def damage(rng: random.Random, raw: bytes) -> bytes:
    """One to three random damages."""
    for _ in range(rng.randint(1, 3)):
        kind = rng.randrange(8)
        at = rng.randrange(len(raw) + 1)
        lines = raw.split(b"\n")
        i = rng.randrange(len(lines))
        if kind == 0:
            raw = raw[:at] + bytes(rng.randrange(256) for _ in range(rng.randint(1, 8))) + raw[at:]
        elif kind == 1:
            raw = raw[:at]
        elif kind == 2:
            raw = raw[:at] + raw[at + rng.randint(1, 20):]
        elif kind == 3:
            lines.insert(i, lines[i])
            raw = b"\n".join(lines)
        elif kind == 4:
            del lines[i]
            raw = b"\n".join(lines)
        elif kind == 5:
            raw = raw[:at] + rng.choice([b"nan", b"inf", b"-1e999", b"", b";;", b",", b"\t",
                                         b"\x00", b"\xff\xfe", b"\r"]) + raw[at:]
        elif kind == 6:
            raw = raw.replace(rng.choice([b"0", b"1", b"5", b"."]), rng.choice([b"", b"x", b"-"]), 3)
        else:
            raw = raw[:at] + bytes([raw[at] ^ (1 << rng.randrange(8))]) + raw[at + 1:] \
                if at < len(raw) else raw
    return raw


def draw_data_file(rng: random.Random, folder: Path, k: int, header, rows):
    """(path, encoding, mapping, expect_same_K)."""
    pick = rng.random()
    if pick < 0.01:  # beyond the size limit: a sparse file, refused before it is read
        path = folder / f"huge{k}.csv"
        with open(path, "wb") as fh:
            fh.write(b"element,run,z_um,force_N,signal_V\n")
            fh.truncate(MAX_BYTES + 1)
        return path, None, None, False
    if pick < 0.03:  # a huge file within the limit: many copies of the readings
        raw, enc, right = csv_bytes(rng, header, rows, repeat=rng.randint(300, 3000))
        path = folder / f"big{k}.csv"
    elif pick < 0.15:
        path = folder / f"f{k}.lvm"
        raw, enc, right = (HW / "calibration_example.lvm").read_bytes(), None, True
    elif pick < 0.25:
        path = folder / f"f{k}.tdms"
        raw, enc, right = (HW / "calibration_example.tdms").read_bytes(), None, True
    else:
        raw, enc, right = csv_bytes(rng, header, rows)
        path = folder / f"f{k}.csv"
    damaged = rng.random() < 0.7
    if damaged:
        raw = damage(rng, raw)
    path.write_bytes(raw)
    mapping = DAQ_MAP if path.suffix in (".lvm", ".tdms") else None
    return path, enc, mapping, right and not damaged and not path.name.startswith("big")


def fuzz_data(n: int, seed: int, quiet: bool) -> dict:
    header, rows = example_rows()
    reference = {e: c.K_N_per_mm for e, c in
                 ca.fit_all(read_measured(HW / "calibration_example.csv")[0]).items()}
    counts = {"tried": 0, "read": 0, "refused": 0, "tracebacks": 0, "wrong K": 0, "warned": 0,
              "through the command": 0}
    with tempfile.TemporaryDirectory(prefix="tactcad-fuzz-data-") as tmp:
        for k in range(n):
            rng = random.Random(seed * 1_000_003 + k)
            path, enc, mapping, same = draw_data_file(rng, Path(tmp), k, header, rows)
            counts["tried"] += 1
            if k % 25 == 0:  # now and then the whole command, as a user runs it
                argv = ["calibrate", "--data", str(path)] + (["--encoding", enc] if enc else []) \
                    + (["--map", "force_N=Dev1/ai0,signal_V=Dev1/ai1"] if mapping else [])
                result, _, err = run_cli(argv, 120)
                counts["through the command"] += 1
                if verdict(result, err) == "traceback":
                    counts["tracebacks"] += 1
                    if not quiet:
                        print(f"data #{k}: {argv} -> {result!r}\n{err[-2000:]}")
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    data, _ = read_measured(path, enc, mapping)
                    fits = ca.fit_all(data)
                counts["warned"] += bool(caught)
                counts["read"] += 1
                if same and any(abs(fits[e].K_N_per_mm - K) > 1e-9 for e, K in reference.items()):
                    counts["wrong K"] += 1
                    if not quiet:
                        print(f"data #{k}: {path.name}: K differs from the example's")
            except CalibrationError:
                counts["refused"] += 1
            except Exception:  # noqa: BLE001 - exactly what this fuzz looks for
                counts["tracebacks"] += 1
                if not quiet:
                    print(f"data #{k}: {path.name} ({enc}):\n{traceback.format_exc()}")
            path.unlink()
    return counts


class _TimeUp(BaseException):
    pass


def run_cli(argv: list[str], timeout_s: int) -> tuple[object, str, str]:
    """``tactcad.cli.main(argv)`` in this process: (exit code, or "timeout",
    or the exception that escaped; stdout; stderr)."""
    from tactcad import cli

    out, err = io.StringIO(), io.StringIO()

    def time_up(*_):
        raise _TimeUp

    old = signal.signal(signal.SIGALRM, time_up)
    signal.alarm(timeout_s)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            result: object = cli.main(argv)
    except _TimeUp:
        result = "timeout"
    except BaseException as exc:  # noqa: BLE001 - a traceback the user would see
        result = exc
        err.write(traceback.format_exc())
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    return result, out.getvalue(), err.getvalue()


def verdict(result: object, err: str) -> str:
    """``accepted``, ``refused``, ``timeout`` or ``traceback``."""
    if result == "timeout":
        return "timeout"
    if not isinstance(result, int) or result not in (0, 1, 2, 3) or "Traceback" in err:
        return "traceback"
    lines = err.splitlines()
    if sum(": error: " in ln for ln in lines) > 1 or any(
            "Warning: " in ln and not ln.startswith("tactcad: warning:") for ln in lines):
        return "traceback"  # more than one error line, or a warning in Python's format
    return "accepted" if result in (0, 1) else "refused"


def fuzz_options(n: int, seed: int, quiet: bool, timeout_s: int) -> dict:
    from hypothesis import HealthCheck, Phase, given, settings

    from cli_strategies import LONG, command_lines
    from tactcad import cli
    from tactcad.errors import TactcadError

    counts = {"tried": 0, "accepted": 0, "refused": 0, "timeout": 0, "tracebacks": 0}
    here = os.getcwd()

    @settings(max_examples=n, deadline=None, database=None, derandomize=False,
              phases=[Phase.generate], suppress_health_check=list(HealthCheck))
    @given(command_lines())
    def one(argv):
        counts["tried"] += 1
        try:
            cli.parse_checked(argv)
        except TactcadError:
            counts["refused"] += 1
            return
        except BaseException:  # noqa: BLE001
            counts["tracebacks"] += 1
            if not quiet:
                print(f"options {argv}:\n{traceback.format_exc()}")
            return
        if tuple(a for a in argv[:2] if not a.startswith("-")) in LONG or argv[0] in \
                {c[0] for c in LONG}:
            counts["accepted"] += 1  # checked; the run itself takes minutes
            return
        with tempfile.TemporaryDirectory(prefix="tactcad-fuzz-cli-") as tmp:
            os.chdir(tmp)
            try:
                result, _, err = run_cli(argv, timeout_s)
            finally:
                os.chdir(here)
        v = verdict(result, err)
        counts["tracebacks" if v == "traceback" else v] += 1
        if v == "traceback" and not quiet:
            print(f"options {argv} -> {result!r}:\n{err[-2000:]}")

    import hypothesis

    hypothesis.seed(seed)(one)()
    return counts


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=int, default=1000, help="data files to draw (default 1000)")
    ap.add_argument("--options", type=int, default=300, help="command lines to draw (default 300)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--timeout", type=int, default=60, help="seconds per command line run")
    ap.add_argument("--quiet", action="store_true", help="summary only")
    args = ap.parse_args(argv)
    os.environ.setdefault("TACTCAD_WORKERS", "0")
    t0 = time.perf_counter()
    data = fuzz_data(args.data, args.seed, args.quiet)
    t1 = time.perf_counter()
    print(f"fuzz data files: {data['tried']} tried ({data['through the command']} also through "
          f"`tactcad calibrate`), {data['read']} read ({data['warned']} with a warning), "
          f"{data['refused']} refused by name, {data['wrong K']} read with a wrong K, "
          f"{data['tracebacks']} tracebacks ({t1 - t0:.0f} s)", flush=True)
    opts = fuzz_options(args.options, args.seed, args.quiet, args.timeout)
    print(f"fuzz options: {opts['tried']} command lines tried, {opts['accepted']} accepted, "
          f"{opts['refused']} refused by name, {opts['timeout']} ran past {args.timeout} s, "
          f"{opts['tracebacks']} tracebacks ({time.perf_counter() - t1:.0f} s)")
    return 0 if not (data["tracebacks"] or data["wrong K"] or opts["tracebacks"]) else 1


if __name__ == "__main__":
    sys.exit(main())
