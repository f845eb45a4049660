"""Pictures for people: a shaded render of the array and PNG pages of the drawings.

* :func:`render_assembly_png`: every placed solid tessellated (OpenCascade
  mesher through build123d), transformed to the assembly frame and drawn by
  an orthographic z-buffer (numpy), flat shaded with a fixed directional
  light (Lambert term + ambient) in the catalogue's part colours, with dark
  outlines at part boundaries and creases; PNG written by Pillow.
* :func:`pdf_page_png`: one PDF page rasterised by PDFium (pypdfium2).

Both write PNG without time stamps or tool versions, so the same input gives
the same bytes with the same library versions.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from tactcad.assembly.placement import location, matrix
from tactcad.parts.mesh import tessellate

LIGHT = np.array([0.35, 0.8, 0.6])  # towards the light, assembly frame
NO_TRIANGLE = np.iinfo(np.int64).max  # z-buffer's triangle index where none is drawn


def pdf_page_png(pdf: str | Path, page: int, target: str | Path, dpi: int = 150) -> None:
    """Rasterise page ``page`` (0-based) of ``pdf`` to a PNG at ``dpi``.

    Raises:
        IndexError: no such page.
    """
    import pypdfium2 as pdfium

    doc = pdfium.PdfDocument(str(pdf))
    try:
        if not 0 <= page < len(doc):
            raise IndexError(f"page {page} of {len(doc)}")
        bitmap = doc[page].render(scale=dpi / 72.0)
        image = bitmap.to_pil().convert("RGB")
        image.save(target, format="PNG", optimize=False)
    finally:
        doc.close()


def mesh_instances(solids: Mapping[str, object], instances: Sequence, tolerance: float = 0.02,
                   angular_tolerance: float = 0.2):
    """Triangles of every instance in the assembly frame.

    Args:
        solids: build123d solids by part name (part frame, mm).
        instances: :class:`tactcad.catalogue.array.Instance` objects.

    Returns:
        (triangles (n, 3, 3) in mm, part index per triangle, instance index
        per triangle, part names).
    """
    names = sorted({i.part for i in instances})
    local = {}
    for name in names:
        v, t = tessellate(solids[name], tolerance, angular_tolerance)
        local[name] = v[t]
    all_tris, owner, inst_ids = [], [], []
    for k, inst in enumerate(instances):
        m = matrix(location(inst.placement))
        t = local[inst.part]
        moved = t @ m[:3, :3].T + m[:3, 3]
        all_tris.append(moved)
        owner.append(np.full(len(t), names.index(inst.part)))
        inst_ids.append(np.full(len(t), k))
    return np.concatenate(all_tris), np.concatenate(owner), np.concatenate(inst_ids), names


def _camera(elev_deg: float, azim_deg: float) -> np.ndarray:
    """Rows: screen right, screen up, towards the viewer (assembly frame, y up)."""
    el, az = np.radians(elev_deg), np.radians(azim_deg)
    towards = np.array([np.cos(el) * np.sin(az), np.sin(el), np.cos(el) * np.cos(az)])
    right = np.cross([0.0, 1.0, 0.0], towards)
    right /= np.linalg.norm(right)
    up = np.cross(towards, right)
    return np.array([right, up, towards])


def rasterise(tris: np.ndarray, size_px: tuple[int, int], cam: np.ndarray,
              margin: float = 0.06, chunk: int = 4_000_000) -> np.ndarray:
    """Orthographic z-buffer of triangles, vectorised by scan-line spans.

    Each triangle covers the pixels whose centres lie inside it (top-left
    half-open rule along rows); the nearest fragment wins, ties going to the
    earlier triangle, so the result does not depend on anything but the input.

    Args:
        tris: (n, 3, 3) vertices (mm, assembly frame).
        size_px: (width, height) of the raster.
        cam: camera rows from :func:`_camera`.
        chunk: fragments processed at once (bounds memory).

    Returns:
        (h, w) index of the nearest triangle per pixel, -1 for background.
    """
    w, h = size_px
    p = tris @ cam.T  # screen x, y, depth (larger = nearer)
    lo = p[:, :, :2].reshape(-1, 2).min(axis=0)
    hi = p[:, :, :2].reshape(-1, 2).max(axis=0)
    span = hi - lo
    k = min(w * (1 - 2 * margin) / span[0], h * (1 - 2 * margin) / span[1])
    off = np.array([w, h]) / 2 - k * (lo + hi) / 2
    X = p[:, :, 0] * k + off[0]
    Y = h - (p[:, :, 1] * k + off[1])
    Z = p[:, :, 2]
    # depth plane z = a x + b y + c per triangle
    e1 = np.stack([X[:, 1] - X[:, 0], Y[:, 1] - Y[:, 0], Z[:, 1] - Z[:, 0]], axis=1)
    e2 = np.stack([X[:, 2] - X[:, 0], Y[:, 2] - Y[:, 0], Z[:, 2] - Z[:, 0]], axis=1)
    n = np.cross(e1, e2)
    ok = np.abs(n[:, 2]) > 1e-12
    a = np.where(ok, -n[:, 0] / np.where(ok, n[:, 2], 1), 0.0)
    b = np.where(ok, -n[:, 1] / np.where(ok, n[:, 2], 1), 0.0)
    c = Z[:, 0] - a * X[:, 0] - b * Y[:, 0]
    r0 = np.clip(np.ceil(Y.min(axis=1) - 0.5), 0, h).astype(np.int64)
    r1 = np.clip(np.floor(Y.max(axis=1) - 0.5), -1, h - 1).astype(np.int64)
    nrows = np.where(ok, np.maximum(r1 - r0 + 1, 0), 0)
    best_z = np.full(h * w, -np.inf)
    best_t = np.full(h * w, NO_TRIANGLE, dtype=np.int64)
    tri_ids = np.nonzero(nrows)[0]
    # per-triangle work is bounded by its rows x width; group triangles into chunks
    width_est = np.ceil(X.max(axis=1) - X.min(axis=1)) + 1
    cost = nrows * width_est
    bounds = np.searchsorted(np.cumsum(cost[tri_ids]), np.arange(chunk, cost.sum() + chunk, chunk))
    start = 0
    for stop in list(bounds) + [len(tri_ids)]:
        ids = tri_ids[start:stop]
        start = stop
        if len(ids) == 0:
            continue
        t = np.repeat(ids, nrows[ids])
        first = np.repeat(np.cumsum(nrows[ids]) - nrows[ids], nrows[ids])
        row = r0[t] + (np.arange(len(t)) - first)
        yc = row + 0.5
        xs = []
        for i, j in ((0, 1), (1, 2), (2, 0)):
            ya, yb, xa, xb = Y[t, i], Y[t, j], X[t, i], X[t, j]
            cross = ((ya <= yc) & (yc < yb)) | ((yb <= yc) & (yc < ya))
            dy = np.where(yb != ya, yb - ya, 1.0)
            xs.append(np.where(cross, xa + (yc - ya) * (xb - xa) / dy, np.nan))
        xs = np.stack(xs, axis=1)
        valid = np.isfinite(xs).sum(axis=1) >= 2
        xl = np.where(valid, np.nanmin(np.where(valid[:, None], xs, 0), axis=1), 0)
        xr = np.where(valid, np.nanmax(np.where(valid[:, None], xs, 0), axis=1), 0)
        c0 = np.clip(np.ceil(xl - 0.5), 0, w).astype(np.int64)
        c1 = np.clip(np.ceil(xr - 0.5), 0, w).astype(np.int64)
        cnt = np.where(valid, np.maximum(c1 - c0, 0), 0)
        ft = np.repeat(t, cnt)
        frow = np.repeat(row, cnt)
        ffirst = np.repeat(np.cumsum(cnt) - cnt, cnt)
        fcol = np.repeat(c0, cnt) + (np.arange(len(ft)) - ffirst)
        fz = a[ft] * (fcol + 0.5) + b[ft] * (frow + 0.5) + c[ft]
        pix = frow * w + fcol
        # nearest depth per pixel; where this chunk brought a nearer one, the
        # earlier winner is void; then the first triangle at that depth wins
        before = best_z[pix]
        np.maximum.at(best_z, pix, fz)
        nearest = best_z[pix]
        best_t[pix[nearest > before]] = NO_TRIANGLE
        win = fz == nearest
        np.minimum.at(best_t, pix[win], ft[win])
    return np.where(best_t == NO_TRIANGLE, -1, best_t).reshape(h, w)


def box_filter(px: np.ndarray, k: int) -> np.ndarray:
    """Exact integer k x k box filter (mean rounded half up) of an (h k, w k, 3)
    uint8 image -> (h, w, 3) uint8: one strided slice per sub-pixel offset,
    several times faster than a reduction over a 5-D view; 16 bits hold
    255 k^2 up to k = 16."""
    n = k * k
    wide = np.uint16 if n <= 256 else np.uint32
    q = sum(px[i::k, j::k].astype(wide) for i in range(k) for j in range(k))
    return ((q + n // 2) // n).astype(np.uint8)


def render_assembly_png(solids: Mapping[str, object], instances: Sequence,
                        colors: Mapping[str, tuple[float, float, float]], target: str | Path,
                        title: str = "", size_px: tuple[int, int] = (1600, 1000),
                        elev: float = 28.0, azim: float = -58.0, supersample: int = 2) -> int:
    """Render placed solids to a PNG; returns the number of triangles drawn.

    Orthographic z-buffer render (see :func:`rasterise`) from elevation
    ``elev`` and azimuth ``azim`` (degrees, y up), Lambert shading with a fixed
    light, dark outlines where the visible surface changes part or turns by
    more than 25 degrees, ``supersample`` x ``supersample`` anti-aliasing.
    """
    from PIL import Image, ImageDraw, ImageFont

    tris, owner_part, inst_id, names = mesh_instances(solids, instances)
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    nl = np.linalg.norm(normals, axis=1)
    cam = _camera(elev, azim)
    # closed solids, outward triangles: only those facing the viewer can be seen
    keep = (nl > 1e-12) & ((normals @ cam[2]) > 0)
    tris, owner_part, inst_id, normals = tris[keep], owner_part[keep], inst_id[keep], normals[keep]
    normals = normals / nl[keep][:, None]
    w, h = size_px[0] * supersample, size_px[1] * supersample
    tri = rasterise(tris, (w, h), cam)
    light = LIGHT / np.linalg.norm(LIGHT)
    shade = 0.38 + 0.62 * np.clip(normals @ light, 0.0, 1.0)
    base = np.array([colors[n] for n in names])[owner_part]
    tri_rgb = np.clip(base * shade[:, None], 0.0, 1.0)
    fg = tri >= 0
    # outlines: a neighbouring pixel on another instance, or across a crease
    inst_px = np.where(fg, inst_id[np.maximum(tri, 0)], -1)
    cos_crease = np.cos(np.radians(25.0))
    edge = np.zeros((h, w), dtype=bool)
    for dy, dx in ((0, 1), (1, 0), (1, 1)):
        ta, tb = tri[: h - dy, : w - dx], tri[dy:, dx:]
        ia, ib = inst_px[: h - dy, : w - dx], inst_px[dy:, dx:]
        e = ia != ib
        cand = (~e) & (ta != tb) & (ta >= 0)
        ya, xa = np.nonzero(cand)
        na, nb = normals[ta[ya, xa]], normals[tb[ya, xa]]
        crease = (na * nb).sum(-1) < cos_crease
        e[ya[crease], xa[crease]] = True
        edge[: h - dy, : w - dx] |= e
    # 8-bit colour of every triangle and of the background (last row), plain
    # and darkened as an outline, looked up per pixel
    rgb = np.vstack([tri_rgb, np.ones((1, 3))]).astype(np.float32)
    table = np.stack([np.round(rgb * np.float32(255)),
                      np.round(rgb * np.float32(0.25) * np.float32(255))], axis=1).astype(np.uint8)
    px = table[np.where(fg, tri, len(tri_rgb)), edge.astype(np.intp)]
    pil = Image.fromarray(box_filter(px, supersample), "RGB")
    if title:
        import matplotlib

        font_path = Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"
        font = ImageFont.truetype(str(font_path), 22)
        ImageDraw.Draw(pil).text((24, 18), title, fill=(0, 0, 0), font=font)
    pil.save(target, format="PNG", optimize=False)
    return int(keep.sum())
