"""Write the readings of hardware/macro_array/calibration_example.csv in the other formats
tactcad reads, so every example holds the same numbers:

* ``calibration_example_excel.csv``: Excel's "CSV UTF-8" (byte order mark, CRLF);
* ``calibration_example_semicolon.csv``: Excel in most of Europe: semicolons,
  decimal commas, Windows-1252 (read with ``--encoding cp1252``);
* ``calibration_example.lvm``: LabVIEW's "Write To Measurement File" text
  format, one segment, the rig's channels ``element``, ``run``, ``z_um`` and
  the DAQ's ``Dev1/ai0`` (force, N) and ``Dev1/ai1`` (bridge signal, V);
* ``calibration_example.tdms``: the same channels in TDMS, groups ``rig`` and
  ``Dev1`` (written with npTDMS).

The LVM and TDMS examples need ``--map force_N=Dev1/ai0,signal_V=Dev1/ai1``.

Usage: ``python scripts/make_calibration_examples.py [hardware/macro_array]``
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
COLUMNS = ("element", "run", "z_um", "force_N", "signal_V")
DAQ = {"force_N": "ai0", "signal_V": "ai1"}  # DAQ channels of the two analogue readings
MAP = "force_N=Dev1/ai0,signal_V=Dev1/ai1"


def read_example(path: Path) -> tuple[list[str], float, list[dict[str, str]]]:
    """Comments (without '# '), the force sensor stiffness and the rows as text."""
    comments, k_sensor, body = [], 57.04, []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            text = line.lstrip("#").strip()
            if text.startswith("k_sensor_N_per_mm"):
                k_sensor = float(text.split("=")[1])
            else:
                comments.append(text)
        elif line.strip():
            body.append(line)
    rows = list(csv.DictReader(body))
    return comments, k_sensor, rows


def write_excel(out: Path, comments, k_sensor, rows) -> None:
    lines = [f"# {c}" for c in comments] + [f"# k_sensor_N_per_mm = {k_sensor:g}", ",".join(COLUMNS)]
    lines += [",".join(r[c] for c in COLUMNS) for r in rows]
    out.write_bytes(b"\xef\xbb\xbf" + "\r\n".join(lines).encode("utf-8") + b"\r\n")


def write_semicolon(out: Path, comments, k_sensor, rows) -> None:
    lines = [f"# {c}" for c in comments] + [
        "# Saved as Excel does in most of Europe: semicolons, decimal commas, Windows-1252 "
        "(Z in µm).", f"# k_sensor_N_per_mm = {k_sensor:g}".replace(".", ","), ";".join(COLUMNS)]
    lines += [";".join(r[c].replace(".", ",") for c in COLUMNS) for r in rows]
    out.write_bytes("\r\n".join(lines).encode("cp1252") + b"\r\n")


def write_lvm(out: Path, comments, k_sensor, rows) -> None:
    names = ["element", "run", "z_um", f"Dev1/{DAQ['force_N']}", f"Dev1/{DAQ['signal_V']}"]
    n = len(names)
    tabs = lambda *cells: "\t".join(str(c) for c in cells)  # noqa: E731
    head = [tabs("LabVIEW Measurement", ""), tabs("Writer_Version", 2), tabs("Reader_Version", 2),
            tabs("Separator", "Tab"), tabs("Decimal_Separator", "."), tabs("Multi_Headings", "No"),
            tabs("X_Columns", "One"), tabs("Time_Pref", "Relative"), tabs("Operator", "tactcad"),
            tabs("Description", " ".join(comments)), tabs("Date", "2026/01/01"),
            tabs("Time", "00:00:00"), tabs("k_sensor_N_per_mm", f"{k_sensor:g}"),
            tabs("***End_of_Header***", ""), "",
            tabs("Channels", *[n] + [""] * (n - 1)), tabs("Samples", *[len(rows)] * n),
            tabs("Date", *["2026/01/01"] * n), tabs("Time", *["00:00:00"] * n),
            tabs("Y_Unit_Label", "", "", "um", "N", "V"), tabs("X_Dimension", *["Time"] * n),
            tabs("X0", *["0.0000000000000000E+0"] * n), tabs("Delta_X", *["1.000000"] * n),
            tabs("***End_of_Header***", *[""] * n), tabs("X_Value", *names, "Comment")]
    data = [tabs(f"{i:.6f}", *(r[c] for c in COLUMNS)) for i, r in enumerate(rows)]
    out.write_text("\r\n".join(head + data) + "\r\n", encoding="utf-8", newline="")


def write_tdms(out: Path, comments, k_sensor, rows) -> None:
    import numpy as np
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    col = {c: np.array([float(r[c]) for r in rows]) for c in COLUMNS}
    root = RootObject(properties={"description": " ".join(comments),
                                  "k_sensor_N_per_mm": float(k_sensor)})
    channels = [ChannelObject("rig", "element", col["element"].astype(np.int32)),
                ChannelObject("rig", "run", col["run"].astype(np.int32)),
                ChannelObject("rig", "z_um", col["z_um"], properties={"unit_string": "um"}),
                ChannelObject("Dev1", DAQ["force_N"], col["force_N"], properties={"unit_string": "N"}),
                ChannelObject("Dev1", DAQ["signal_V"], col["signal_V"],
                              properties={"unit_string": "V"})]
    with TdmsWriter(out) as writer:
        writer.write_segment([root, GroupObject("rig"), GroupObject("Dev1"), *channels])


def main(argv: list[str]) -> int:
    folder = Path(argv[0]) if argv else REPO / "hardware" / "macro_array"
    source = read_example(REPO / "hardware" / "macro_array" / "calibration_example.csv")
    write_excel(folder / "calibration_example_excel.csv", *source)
    write_semicolon(folder / "calibration_example_semicolon.csv", *source)
    write_lvm(folder / "calibration_example.lvm", *source)
    write_tdms(folder / "calibration_example.tdms", *source)
    print(f"wrote 4 examples to {folder} ({len(source[2])} readings each); LVM and TDMS: --map {MAP}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
