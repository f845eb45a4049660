"""The offline review page: its text (fast) and the page in headless Chromium (slow)."""

from __future__ import annotations

import json
import re
import time
from types import SimpleNamespace

import pytest

from tactcad.export.review_assets import MODULES, ReviewAssetsError, _rewrite, import_map
from tactcad.checks.review_results import checks_script, write_checks_script
from tactcad.export.review_page import REVIEW_PAGE, bom_table, page_html, review_contents


def _contents(name="demo", sha="ab" * 32, **extra):
    facts = {"design": {"name": name, "source": "d.toml", "sha256": sha}, "tactcad_version": "0",
             "cad_stack": {}, "units": "mm", "files": [{"path": "x"}], **extra}
    return review_contents(facts, [("drawings/a.svg", "a", "<svg/>")], {"s": b"glb"},
                           "\ufeffitem,part\n1,a\n", [], "A", "2026-01-01", "0.187.0")


def _data(**kw):
    return _contents(**kw).data


def test_page_text_carries_design_hash_and_no_network():
    html = page_html(_contents(), '{"imports": {}}')
    assert '<meta name="tactcad-design-sha256" content="' + "ab" * 32 + '">' in html
    assert not re.search(r"""(src|href)\s*=\s*["']https?:""", html)


def test_hostile_design_name_stays_data():
    """A name holding markup or a template token neither breaks the page nor is replaced."""
    name = "</script><script>alert(1)</script>@@SCENES@@"
    html = page_html(_contents(name=name), '{"imports": {}}')
    assert "<script>alert(1)" not in html
    blob = re.search(r'id="review-data">(.*?)</script>', html, re.S).group(1)
    assert json.loads(blob)["manifest"]["design"]["name"] == name
    assert "files" not in json.loads(blob)["manifest"]


def test_the_page_carries_every_sheet_and_scene_with_its_sha256():
    import base64
    import hashlib

    sheets = [("drawings/a.svg", "a", "<svg>é</svg>"), ("drawings/b.svg", "b", "<svg>é</svg>"),
              ("drawings/c.svg", "c", "<svg/>")]
    contents = review_contents({"design": {"name": "d", "sha256": "ab" * 32}}, sheets,
                               {"t": b"glb-t", "s": b"glb-s"}, "", [], "A", "d", "0")
    digest = {p: hashlib.sha256(svg.encode()).hexdigest() for p, _, svg in sheets}
    assert [s["sha256"] for s in contents.data["sheets"]] == list(digest.values())
    assert len(contents.sheets) == 2  # two sheets of the same bytes: one copy
    assert contents.data["scenes"] == ["t", "s"]
    assert contents.data["scene_sha256"]["s"] == hashlib.sha256(b"glb-s").hexdigest()
    html = page_html(contents, '{"imports": {}}')
    blob = json.loads(re.search(r'id="review-data">(.*?)</script>', html, re.S).group(1))
    assert [base64.b64decode(s["svg_base64"]).decode() for s in blob["sheets"]] == \
        [svg for _, _, svg in sheets]
    scenes = json.loads(re.search(r'id="review-scenes">(.*?)</script>', html, re.S).group(1))
    assert base64.b64decode(scenes["s"]) == b"glb-s"


def test_verification_is_passed_on_when_the_manifest_has_it():
    assert "verification" not in _data()["manifest"]
    assert _data(verification=[{"requirement": "K"}])["manifest"]["verification"]


def test_bom_table_reads_the_csv_with_its_bom():
    t = bom_table("\ufeffitem,part\n1,élément\n")
    assert t == {"columns": ["item", "part"], "rows": [{"item": "1", "part": "élément"}]}
    assert bom_table("") == {"columns": [], "rows": []}


def test_checks_script_counts_and_is_written_only_beside_a_page(tmp_path):
    r = [SimpleNamespace(check="c", subject="s", passed=True, detail=""),
         SimpleNamespace(check="c", subject="</script>", passed=False, detail="bad")]
    text = checks_script("ff", [("parts", r)])
    doc = json.loads(text.removeprefix("window.TACTCAD_CHECKS = ").rstrip(";\n"))
    assert (doc["passed"], doc["failed"], doc["design_sha256"]) == (1, 1, "ff")
    assert "</script>" not in text
    assert write_checks_script(tmp_path, "ff", [("parts", r)]) is None
    (tmp_path / "review").mkdir()
    (tmp_path / REVIEW_PAGE).write_text("x")
    assert write_checks_script(tmp_path, "ff", [("parts", r)]).read_text() == text


def test_import_map_inlines_every_module_without_relative_imports():
    doc = json.loads(import_map())
    assert set(doc["imports"]) == set(MODULES)
    assert all(u.startswith("data:text/javascript;base64,") for u in doc["imports"].values())


def test_an_import_outside_the_map_is_refused():
    with pytest.raises(ReviewAssetsError, match="update MODULES"):
        _rewrite("import { x } from './nowhere.js';", "build/three.module.js")
    assert _rewrite("import { a } from './three.core.js';", "build/three.module.js") == \
        "import { a } from 'three/core';"


def test_the_page_carries_the_build_steps_of_its_scenes():
    """The book's steps ride in the page's data for the scenes it carries (a
    step drawn in a scene the page lacks is left out)."""
    book = [{"key": "a", "scene": "array", "explode": {"e1": [0, 0, 1]}},
            {"key": "b", "scene": "not-exported"}]
    contents = review_contents({"design": {"name": "x", "sha256": "0" * 64}}, [],
                               {"array": b"glb"}, "", [], "A", "-", "r0", book)
    assert [s["key"] for s in contents.data["book"]] == ["a"]
    assert review_contents({}, [], {}, "", [], "A", "-", "r0").data["book"] == []


# --- in Chromium ---------------------------------------------------------------------------
@pytest.mark.slow
def test_a_build_step_lights_its_parts_and_the_slider_explodes_them(exported, browser):
    """From file://: the Build step list holds every step of steps.json; choosing
    the stack step lights its parts in the array, and the slider at its end
    moves each of them by its explosion vector (the gauges bonded before with
    them); a rig's step switches the 3D view to its scene."""
    from tactcad.checks.review_browser import wait_first_frame
    from tactcad.export.instructions import BOOK_DATA

    out, _ = exported
    steps = json.loads((out / BOOK_DATA).read_text())
    stack = next(s for s in steps if s["key"] == "array-stack")
    rig = next(s for s in steps if s["key"].startswith("rig-") and s["explode"])
    moved = sorted(stack["explode"])
    assert any(n.startswith("gauge_") for n in moved)  # carried by their elements
    with browser() as page:
        page.goto((out / REVIEW_PAGE).resolve().as_uri())
        wait_first_frame(page)
        options = page.eval_on_selector_all("#step-select option", "os => os.map(o => o.value)")
        assert options == [""] + [s["key"] for s in steps]
        page.select_option("#step-select", "array-stack")
        page.wait_for_function("window.__review.step() === 'array-stack'")
        lit = set(page.evaluate("window.__review.lit()"))
        assert {n for n in moved if not n.startswith("gauge_")} <= lit
        # the gauges (bonded in step 1) grey, the bolts (torqued in the next step) not shown yet
        roles = page.evaluate("window.__review.stepRoles()")
        shown = set(page.evaluate("window.__review.visible()"))
        bolts = [n for n in roles if n.startswith("bolt_")]
        assert bolts and all(roles[n] == "later" and n not in shown for n in bolts)
        assert all(roles[n] == "earlier" and n in shown for n in roles if n.startswith("gauge_"))
        assert {n for n, r in roles.items() if r == "new"} == lit
        before = page.evaluate(f"window.__review.positions({json.dumps(moved)})")
        pixels = page.locator("#view canvas").screenshot()
        page.locator("#explode").fill("100")
        page.wait_for_function(f"window.__review.positions(['{moved[0]}'])['{moved[0]}'][2]"
                               f" !== {before[moved[0]][2]}")
        after = page.evaluate(f"window.__review.positions({json.dumps(moved)})")
        for name in moved:
            assert after[name] == pytest.approx(
                [b + d for b, d in zip(before[name], stack["explode"][name])], abs=1e-6)
        assert page.locator("#view canvas").screenshot() != pixels
        page.select_option("#step-select", rig["key"])
        page.wait_for_function(f"window.__review.scene === {json.dumps(rig['scene'])}")
        page.select_option("#step-select", "")  # no step: every part as the model has it
        assert set(page.evaluate("window.__review.visible()")) == \
            set(page.evaluate("window.__review.instances"))
        assert page.errors == []


@pytest.mark.slow
def test_page_offline_in_chromium(exported, browser):
    """From file:// with the network off: a drawn 3D view, the instance names in the
    part tree, every drawing sheet, the BOM and the design's sha256."""
    from tactcad.checks.review_browser import canvas_is_blank, wait_first_frame

    out, result = exported
    man = json.loads((out / "manifest.json").read_text())
    sheets = [f["path"] for f in man["files"] if f["kind"] in ("drawing-svg", "drawing-assembly")]
    with browser() as page:
        page.goto((out / REVIEW_PAGE).resolve().as_uri())
        wait_first_frame(page)
        assert page.errors == []
        assert not canvas_is_blank(page)
        tree = page.locator("#tree .instance").all_inner_texts()
        names = {t.strip() for t in tree}
        assert {f"element_{k}" for k in range(1, 11)} | {"clamp_plate_front"} <= names
        shown = page.eval_on_selector_all(".sheet", "cs => cs.map(c => c.dataset.sheet)")
        assert shown == sheets
        assert page.eval_on_selector_all(".sheet img", "is => is.every(i => i.naturalWidth > 0)")
        assert page.locator("#bom-table tr").count() > 1
        assert man["design"]["sha256"] in page.locator("#provenance-body").inner_text()
        # hide one instance and highlight another: the tree and the view follow
        page.locator('#tree label[data-instance="element_1"] input').uncheck()
        assert page.evaluate("window.__review.instances.includes('element_1')")
        page.locator("#clip-axis").select_option("x")
        assert not canvas_is_blank(page)


@pytest.mark.slow
def test_page_served_by_any_web_server_shows_what_it_carries(exported, browser):
    """Served over http by a plain file server (no ``tactcad watch`` behind it): the
    page shows its own scene and sheets, asks for ``/state`` once and, finding no
    watch, never polls or reads ``/data``."""
    import functools
    import http.server
    import threading

    from tactcad.checks.review_browser import canvas_is_blank, wait_first_frame

    out, _ = exported
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(out))
    handler.log_message = lambda *a: None
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True).start()
    try:
        with browser(offline=False) as page:
            asked = []
            page.on("request", lambda r: asked.append(r.url))
            page.goto(f"http://127.0.0.1:{server.server_address[1]}/{REVIEW_PAGE}")
            wait_first_frame(page)
            page.wait_for_timeout(1000)  # five polling periods
            assert page.errors == [] and not canvas_is_blank(page)
            assert page.eval_on_selector_all(".sheet img", "is => is.every(i => i.naturalWidth > 0)")
            assert sum(u.endswith("/state") for u in asked) == 1
            assert not any(u.endswith("/data") or "/scene/" in u or "/sheet/" in u for u in asked)
            assert page.locator("#status").inner_text() == ""
    finally:
        server.shutdown()
        server.server_close()


@pytest.mark.slow
def test_a_page_whose_watch_stopped_asks_less_and_less_often(exported, browser):
    """Served by a watch that then stops answering: the page says so and asks
    /state less and less often (200 ms doubling up to 5 s), not five times a second."""
    import http.server
    import threading

    from tactcad.checks.review_browser import wait_first_frame

    out, _ = exported
    page_bytes = (out / REVIEW_PAGE).read_bytes()
    asked = []

    class Gone(http.server.BaseHTTPRequestHandler):
        def do_GET(self):  # noqa: N802
            path = self.path.split("?")[0]
            if path == "/state":
                asked.append(time.monotonic())
                if len(asked) > 2:  # the watch stopped after two answers
                    self.send_error(503)
                    return
                body, kind = b'{"seq": 1, "sha256": "", "refusal": null, "status": "current"}', \
                    "application/json"
            elif path == "/":
                body, kind = page_bytes, "text/html; charset=utf-8"
            else:
                self.send_error(404)
                return
            self.send_response(200)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *a):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Gone)
    threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True).start()
    try:
        with browser(offline=False) as page:
            page.goto(f"http://127.0.0.1:{server.server_address[1]}/")
            wait_first_frame(page)
            page.wait_for_function("document.getElementById('status').textContent"
                                   " === 'watch: not reachable'", timeout=10000)
            start = len(asked)
            page.wait_for_timeout(3000)
            assert len(asked) - start <= 5, len(asked) - start  # 200 ms apart would be 15
            gaps = [b - a for a, b in zip(asked[2:], asked[3:])]
            assert gaps == sorted(gaps) and gaps[-1] > 0.7
            assert page.errors == []
    finally:
        server.shutdown()
        server.server_close()


@pytest.mark.slow
def test_check_results_join_the_page(exported, browser, plan):
    from types import SimpleNamespace as R

    from tactcad.checks.review_browser import wait_first_frame

    out, _ = exported
    write_checks_script(out, plan.design_hash, [("parts", [R(
        check="volume", subject="spacer", passed=False, detail="off by 3 %")])])
    try:
        with browser() as page:
            page.goto((out / REVIEW_PAGE).resolve().as_uri())
            wait_first_frame(page)
            text = page.locator("#checks-body").inner_text()
            assert "1 failed" in text and "off by 3 %" in text
    finally:
        (out / "review/checks.js").unlink()


@pytest.mark.slow
def test_an_undecided_requirement_shows_as_undecided_not_pass(exported, browser, plan):
    from tactcad.checks.check_result import CheckResult
    from tactcad.checks.review_browser import wait_first_frame

    out, _ = exported
    write_checks_script(out, plan.design_hash, [("requirements", [
        CheckResult("requirement", "footprint_mm", True, "undecided: margin +0.0 %",
                    undecided=True),
        CheckResult("requirement", "kr_over_km", True, "pass: margin +2.2 %")])])
    try:
        with browser() as page:
            page.goto((out / REVIEW_PAGE).resolve().as_uri())
            wait_first_frame(page)
            rows = page.locator("#checks-body tr").all_inner_texts()
            text = page.locator("#checks-body").inner_text()
            assert "1 passed, 1 undecided, 0 failed" in text
            footprint = next(r for r in rows if "footprint_mm" in r)
            assert footprint.split("\t")[0] == "UNDECIDED"
    finally:
        (out / "review/checks.js").unlink()


@pytest.mark.slow
def test_a_requirement_reported_not_judged_shows_as_info_in_the_checks(exported, browser, plan):
    """A requirement the lab never stated: INFO in the checks tab, counted apart from the
    passed (it showed PASS and counted among them)."""
    from tactcad.checks.check_result import CheckResult
    from tactcad.checks.review_browser import wait_first_frame

    out, _ = exported
    write_checks_script(out, plan.design_hash, [("requirements", [
        CheckResult("requirement", "k_tolerance_rel", True,
                    "info: not stated, not judged: predicted 0.1285", info=True),
        CheckResult("requirement", "kr_over_km", True, "pass: margin +2.2 %")])])
    try:
        with browser() as page:
            page.goto((out / REVIEW_PAGE).resolve().as_uri())
            wait_first_frame(page)
            rows = page.locator("#checks-body tr").all_inner_texts()
            text = page.locator("#checks-body").inner_text()
            assert "1 passed, 0 failed, 1 info" in text
            band = next(r for r in rows if "k_tolerance_rel" in r)
            assert band.split("\t")[0] == "INFO"
    finally:
        (out / "review/checks.js").unlink()


def test_requirements_of_the_manifest_show_as_the_verification_matrix():
    record = {"values": {"full_scale_force_N": 0.1},
              "closed_form_matrix": [{"requirement": "full_scale_force_N", "target": 0.1,
                                      "predicted": 0.12, "pass": True, "binding_words": "w",
                                      "limits": [{"limit": "yield", "force_N": 0.3}]},
                                     {"requirement": "kr_over_km", "target": 10,
                                      "predicted": 9.9, "pass": False}]}
    view = _data(requirements=record)["manifest"]["verification"]
    rows, limits, values, unmet = view.values()
    # read as the CLI prints it, failures first
    assert [r["requirement"] for r in rows] == ["kr_over_km", "full_scale_force_N"]
    assert list(rows[0]) == ["requirement", "verdict", "target", "predicted", "margin", "binds",
                             "model"]
    assert rows[0]["verdict"] == "FAIL" and rows[1]["binds"] == "w"
    assert limits == [{"limit": "yield", "force_N": 0.3}] and values == {"full_scale_force_N": 0.1}
    assert unmet == ["kr_over_km"]  # the page's red banner


def test_a_requirement_reported_not_judged_shows_as_info_not_pass():
    # a K band the lab did not state is the design's own figure: verify prints INFO
    record = {"values": {}, "closed_form_matrix": [
        {"requirement": "k_tolerance_rel", "target": None, "predicted": 0.5, "pass": True,
         "verdict": "pass", "informational": True},
        {"requirement": "kr_over_km", "target": 10, "predicted": 10.1, "pass": True}]}
    rows = next(iter(_data(requirements=record)["manifest"]["verification"].values()))
    assert {r["requirement"]: r["verdict"] for r in rows} == {"k_tolerance_rel": "INFO",
                                                              "kr_over_km": "PASS"}
