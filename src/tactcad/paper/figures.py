"""Plots of the virtual experiments (matplotlib, Agg backend; PNG files).

* :func:`plot_ratio_map`: a Fig. 7-like plot, R against K_m/K_obj, one line
  per K_r/K_m, with optional measured points (paper Table 2).
* :func:`plot_ratio_vs_load`: a Fig. 6-like plot, R of each element against
  the grasping force (N) for one sample.
"""

from __future__ import annotations

from pathlib import Path


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


#: Line styles of the series that share a colour (one K_r/K_m), in turn: the elements of
#: one design ratio differ only by where they sit in the array (the sample's coupling).
SHARED_COLOUR_STYLES = ("-", "--", ":", "-.", "-o", "--s", ":^", "-.v")


def plot_ratio_map(series: list[dict], path: str | Path, title: str,
                   measured: list[dict] | None = None) -> Path:
    """Write R against K_m/K_obj, one line per element, to a PNG file.

    Args:
        series: records {"label", "K_r_over_K_m", "K_m_over_K_obj": [...], "R": [...]}
            and optional "style" (matplotlib line style); series with equal K_r/K_m
            (2 decimals) share a colour, and those without a style of their own take
            the next of :data:`SHARED_COLOUR_STYLES` within it, so each stays told
            apart in the legend.
        path: output PNG path; parent directories are created.
        title: plot title.
        measured: optional records of the same form drawn as markers in the
            colour of the series with the same K_r/K_m (rounded to 2 decimals).

    Returns:
        The written path.
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.8), dpi=120)
    colours: dict[float, str] = {}
    unstyled: dict[float, int] = {}  # series of one K_r/K_m drawn without a style of their own
    for s in sorted(series, key=lambda s: s["K_r_over_K_m"]):
        order = sorted(range(len(s["R"])), key=lambda i: s["K_m_over_K_obj"][i])
        key = round(s["K_r_over_K_m"], 2)
        style = s.get("style")
        if style is None:
            style = SHARED_COLOUR_STYLES[unstyled.get(key, 0) % len(SHARED_COLOUR_STYLES)]
            unstyled[key] = unstyled.get(key, 0) + 1
        (line,) = ax.plot([s["K_m_over_K_obj"][i] for i in order], [s["R"][i] for i in order],
                          style, label=s["label"], color=colours.get(key))
        colours.setdefault(key, line.get_color())
    for m in measured or []:
        ax.plot(m["K_m_over_K_obj"], m["R"], "o", ms=4,
                color=colours.get(round(m["K_r_over_K_m"], 2), "k"),
                label=m.get("label"))
    return _finish(plt, fig, ax, "K_m / K_obj", "R = (Δ − δ_m)/(Δ − δ_r)", title, path)


def plot_ratio_vs_load(loads_N, ratios: dict[str, list[float]], path: str | Path, title: str) -> Path:
    """Write R of each element against the grasping force (N) to a PNG file (Fig. 6-like)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 4.0), dpi=120)
    for label, r in ratios.items():
        ax.plot(loads_N, r, "o-", ms=3, label=label)
    return _finish(plt, fig, ax, "grasping force W (N)", "R", title, path)


def place_legend(ax):
    """The legend beside the axes, right of them, so it never covers a curve however many
    elements are drawn (one column up to 12 entries, then two).

    Args:
        ax: the axes, its lines labelled.

    Returns:
        The legend.
    """
    entries = len(ax.get_legend_handles_labels()[1])
    return ax.legend(fontsize=7, ncol=1 if entries <= 12 else 2, loc="upper left",
                     bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)


def _finish(plt, fig, ax, xlabel: str, ylabel: str, title: str, path) -> Path:
    """Label, grid and legend the axes, write the PNG (creating its folder), close the figure."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    place_legend(ax)
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, bbox_inches="tight")  # the legend beside the axes is part of the picture
    plt.close(fig)
    return out


#: Markers cycled with the colours, so elements stay apart past the colour table's length.
MARKERS = ("o", "s", "^", "D", "v")


def distinct_styles(n: int) -> list[tuple[tuple[float, ...], str]]:
    """``n`` (colour RGBA, marker) pairs, no two alike: matplotlib's 20-colour table
    ``tab20`` (its darker shades first), each pass over it with the next marker of
    :data:`MARKERS` (a 2 x 8 array's 16 elements: 16 colours)."""
    import matplotlib

    table = matplotlib.colormaps["tab20"].colors
    colours = list(table[0::2]) + list(table[1::2])
    return [(tuple(colours[i % len(colours)]), MARKERS[(i // len(colours)) % len(MARKERS)])
            for i in range(n)]


def plot_calibration(readings: list[dict], path: str | Path, title: str) -> Path:
    """Write force and signal against element deflection for each element (Fig. 4-like) to a PNG.

    Args:
        readings: records {"element", "deflection_um": [...], "force_N": [...], "signal_V": [...]}.
        path: output PNG path; parent directories are created.
        title: figure title.
    """
    plt = _pyplot()
    fig, (ax_f, ax_v) = plt.subplots(1, 2, figsize=(10.0, 4.0), dpi=120)
    for r, (colour, marker) in zip(readings, distinct_styles(len(readings))):
        for ax, key in ((ax_f, "force_N"), (ax_v, "signal_V")):
            ax.plot(r["deflection_um"], r[key], marker, ms=3, color=colour,
                    label=f"element {r['element']}")
    ax_v.set_xlabel("element deflection Δ (um)")
    ax_v.set_ylabel("signal V (V)")
    ax_v.grid(True, alpha=0.3)
    return _finish(plt, fig, ax_f, "element deflection Δ (um)", "force F (N)", title, path)
