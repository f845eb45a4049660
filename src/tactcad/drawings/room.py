"""What a text covers on a sheet, and how much of it another item takes: the
one notion of overlap that places labels (:class:`tactcad.drawings.sheet.Sheet`)
and checks the written sheets (:mod:`tactcad.checks.sheet_overlap`).

All in paper mm, y down. A text covers a box (left, top, right, bottom); a
stroke is a polyline with a half width (the ink on each side of its centre
line): it takes the length of its segments inside a text's box grown by that
half width; two texts take the smaller side of their boxes' common part.
"""

from __future__ import annotations

import math

import numpy as np

Box = tuple[float, float, float, float]    # left, top, right, bottom (paper mm, y down)
Point = tuple[float, float]


def box_overlap(a: Box, b: Box) -> float:
    """The smaller side (mm) of the common part of two boxes; <= 0 when they do not meet."""
    return min(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1]))


def grown(box: Box, by: float) -> Box:
    """``box`` grown by ``by`` mm on every side."""
    return (box[0] - by, box[1] - by, box[2] + by, box[3] + by)


def length_in_box(p: Point, q: Point, box: Box) -> float:
    """Length (mm) of the segment ``p``-``q`` inside ``box`` (Liang-Barsky clipping)."""
    x0, y0, x1, y1 = box
    dx, dy = q[0] - p[0], q[1] - p[1]
    t0, t1 = 0.0, 1.0
    for edge_p, edge_q in ((-dx, p[0] - x0), (dx, x1 - p[0]), (-dy, p[1] - y0), (dy, y1 - p[1])):
        if abs(edge_p) < 1e-15:
            if edge_q < 0:
                return 0.0
            continue
        t = edge_q / edge_p
        if edge_p < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 >= t1:
            return 0.0
    return (t1 - t0) * math.hypot(dx, dy)


def lengths_in_boxes(p: np.ndarray, q: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """:func:`length_in_box` of many segments at once: ``p``, ``q`` (n, 2) their
    ends, ``boxes`` (n, 4) the box each is clipped to; returns (n,) mm."""
    d = q - p
    t0, t1 = np.zeros(len(p)), np.ones(len(p))
    outside = np.zeros(len(p), dtype=bool)
    edges = ((-d[:, 0], p[:, 0] - boxes[:, 0]), (d[:, 0], boxes[:, 2] - p[:, 0]),
             (-d[:, 1], p[:, 1] - boxes[:, 1]), (d[:, 1], boxes[:, 3] - p[:, 1]))
    for edge_p, edge_q in edges:
        parallel = np.abs(edge_p) < 1e-15
        outside |= parallel & (edge_q < 0)
        t = edge_q / np.where(parallel, 1.0, edge_p)
        t0 = np.where(~parallel & (edge_p < 0), np.maximum(t0, t), t0)
        t1 = np.where(~parallel & (edge_p > 0), np.minimum(t1, t), t1)
    return np.where(outside | (t0 >= t1), 0.0, (t1 - t0) * np.hypot(d[:, 0], d[:, 1]))


class Segments:
    """A sheet's strokes as segments, growing as strokes are added: each
    segment's ends, half width and owning stroke, with the extent of each, so
    that a box is clipped only against the segments that can reach it."""

    def __init__(self) -> None:
        self._parts: list[np.ndarray] = []    # (n, 6) blocks: x0 y0 x1 y1 half owner
        self._all = np.zeros((0, 6))
        self.count = 0                        # strokes added

    def add(self, points: list[Point], half: float) -> None:
        """One stroke: the polyline ``points`` with ink ``half`` mm either side of it."""
        pts = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(pts) >= 2:
            block = np.empty((len(pts) - 1, 6))
            block[:, 0:2], block[:, 2:4] = pts[:-1], pts[1:]
            block[:, 4], block[:, 5] = half, self.count
            self._parts.append(block)
        self.count += 1

    def _array(self) -> np.ndarray:
        if self._parts:
            self._all = np.concatenate([self._all, *self._parts])
            self._parts = []
        return self._all

    def ink_in(self, box: Box) -> np.ndarray:
        """Length (mm) of each stroke inside ``box`` grown by the stroke's half
        width, as an array over the strokes added so far."""
        a = self._array()
        x0, y0, x1, y1 = box
        h = a[:, 4]
        near = ((np.minimum(a[:, 0], a[:, 2]) - h <= x1) & (np.maximum(a[:, 0], a[:, 2]) + h >= x0)
                & (np.minimum(a[:, 1], a[:, 3]) - h <= y1) & (np.maximum(a[:, 1], a[:, 3]) + h >= y0))
        out = np.zeros(self.count)
        if near.any():
            s = a[near]
            boxes = np.stack([x0 - s[:, 4], y0 - s[:, 4], x1 + s[:, 4], y1 + s[:, 4]], axis=1)
            np.add.at(out, s[:, 5].astype(int), lengths_in_boxes(s[:, 0:2], s[:, 2:4], boxes))
        return out
