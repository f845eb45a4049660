"""The public Python API (``tactcad.load`` -> ``Project``), the build123d part
classes, and the documentation's Python examples (docs/how-to/python.md, the FreeCAD
script of docs/how-to/freecad.md), run as they stand."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import tactcad
from tactcad import cli
from tactcad.errors import DesignError, DesignErrors

ROOT = Path(__file__).resolve().parents[2]
#: The design the documentation's example loads (its one path, replaced by this absolute one).
EXAMPLE_DESIGN = ROOT / "hardware" / "macro_array" / "macro_array.toml"
DOCS_EXAMPLE_DESIGN = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
DOCS_DESIGN_LINE = 'DESIGN = "fingertip/fingertip.toml"'


def docs_block(page: str, index: int = 0) -> str:
    """The ``index``-th python block of the documentation page ``page`` (under docs/)."""
    text = (ROOT / "docs" / page).read_text(encoding="utf-8")
    return re.findall(r"```python\n(.*?)```", text, re.S)[index]


# --- import costs nothing -------------------------------------------------------------------
def test_import_tactcad_and_the_api_load_no_cad_kernel():
    code = ("import sys, tactcad, tactcad.api; p = tactcad.load(); "
            "print(sorted(m for m in ('OCP', 'build123d', 'cadquery', 'skfem', 'gmsh') "
            "if m in sys.modules)); print(type(p).__name__, p.name)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert out.stdout.splitlines() == ["[]", "Project macro_array"]
    assert out.stderr == ""  # no warning, no print on import


def test_public_names_are_reachable_from_the_package():
    assert set(tactcad.__all__) >= {"load", "Project", "FlexureElement", "FlexureArray", "show"}
    assert tactcad.load is tactcad.api.load and tactcad.Project is tactcad.api.Project
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        tactcad.nope  # noqa: B018


# --- load validates as the CLI does ---------------------------------------------------------
def test_load_refuses_what_the_cli_refuses_with_the_same_message(capsys):
    with pytest.raises(DesignErrors) as caught:
        tactcad.load(set={"element.web_thickness_mm": 1.55, "element.nope_mm": 1})
    fields = [e.field for e in caught.value.errors]
    assert "element.web_thickness_mm" in fields and len(fields) == 2
    code = cli.main(["stiffness", "--element", "1", "--set", "element.web_thickness_mm=1.55",
                     "--set", "element.nope_mm=1", "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    # the same refusals; each names where its value came from: set=, or the --set typed
    assert [e.file for e in caught.value.errors] == ["set", "set"]
    typed = {"element.web_thickness_mm": "--set element.web_thickness_mm=1.55",
             "element.nope_mm": "--set element.nope_mm=1"}
    assert code == 2 and error["message"] == str(caught.value.sourced(typed))


@pytest.mark.parametrize("bad", [{"nodot": 1}, {"": 1}, {3: 1}, [("element.x", 1)]])
def test_load_refuses_a_set_that_is_no_dotted_mapping(bad):
    with pytest.raises(DesignError, match="set"):
        tactcad.load(set=bad)


def test_load_refuses_a_missing_file_naming_it(tmp_path):
    with pytest.raises(DesignError, match="nothere.toml"):
        tactcad.load(tmp_path / "nothere.toml")


def test_set_and_with_values_change_the_plan():
    base = tactcad.load()
    thick = tactcad.load(set={"element.web_thickness_mm": 0.3})
    assert base.element(8).geometry.web_thickness_mm == 0.25
    assert thick.element(8).geometry.web_thickness_mm == 0.3
    assert thick.design_hash != base.design_hash
    again = base.with_values({"element.web_thickness_mm": 0.3})
    assert again.design_hash == thick.design_hash
    with pytest.raises(DesignError, match="element"):
        base.element(11)


# --- parts, assembly, element -----------------------------------------------------------------
def test_parts_are_built_on_first_access_and_once():
    from tactcad.solids.build import BUILD_COUNTS

    project = tactcad.load()
    assert "element_a4mm" in project.parts and "cart" in project.parts
    assert len(project.parts) == len(list(project.parts))
    before = BUILD_COUNTS["spacer"]
    first = project.parts["spacer"]
    assert project.parts["spacer"] is first and BUILD_COUNTS["spacer"] == before + 1
    assert first.volume == pytest.approx(project._specs["spacer"].expected_volume_mm3, rel=1e-6)
    with pytest.raises(KeyError, match="not a part of design macro_array"):
        project.parts["flange"]


def test_assembly_is_a_labelled_compound_of_the_scene():
    from tactcad.catalogue.array_catalogue import array_instances

    project = tactcad.load()
    asm = project.assembly("array")
    labels = [c.label for c in asm.children]
    assert asm.label == "array"
    assert {i.name for i in array_instances(project.plan)} <= set(labels)
    assert len(asm.solids()) == len(labels)
    total = sum(project.parts[i.part].volume for i in array_instances(project.plan))
    assert asm.volume == pytest.approx(total, rel=1e-6)


def test_assembly_refuses_an_unknown_scene():
    from tactcad.errors import SceneError

    with pytest.raises(SceneError, match="calibration-rig"):
        tactcad.load().assembly("nope")


def test_element_stiffness_and_strength_are_the_ladders():
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.element_strength import plan_strength
    from tactcad.studies.verification import rated_full_scale_force
    from tactcad.paper.paper_load import paper_load_of

    project = tactcad.load()
    e = project.element(8)
    k = e.stiffness()
    ref = estimate("closed-form", e.geometry, project.plan.material, element=8)
    assert k.stiffness_N_per_mm == pytest.approx(ref.stiffness_N_per_mm, rel=1e-12)
    assert k.element == 8 and e.part_name == "element_a4mm"
    s = e.strength()
    assert s == [r for r in plan_strength(project.plan, rated_full_scale_force(project.plan),
                                          reference_load=paper_load_of(project.plan))
                 if r.element == 8][0]
    assert s.full_scale_force_N == project.verify("closed-form").requirements["full_scale_force_N"]
    thick = project.with_values({"element.web_thickness_mm": 0.3}).element(8).stiffness()
    assert thick.stiffness_N_per_mm > 1.5 * k.stiffness_N_per_mm  # K ~ t^2.5
    assert e.solid.volume == pytest.approx(project.parts["element_a4mm"].volume)
    assert [x.number for x in project.elements] == list(range(1, 11))


# --- build123d part classes -----------------------------------------------------------------
def test_flexure_element_defaults_are_the_default_designs_element():
    import build123d as bd

    e = tactcad.FlexureElement()
    plan = tactcad.load().plan
    assert isinstance(e, bd.BasePartObject)
    assert e.geometry == plan.element(1).geometry
    assert e.volume == pytest.approx(tactcad.load().parts["element_a4mm"].volume, rel=1e-9)


def test_flexure_element_builds_inside_buildpart():
    import build123d as bd

    with bd.BuildPart() as jaw:
        bd.Box(30, 20, 8, align=(bd.Align.CENTER, bd.Align.CENTER, bd.Align.MAX))
        element = tactcad.FlexureElement(arm_length_mm=5, web_thickness_mm=0.3,
                                         rotation=(90, 0, 0),
                                         align=(bd.Align.CENTER, bd.Align.MIN, bd.Align.CENTER))
    assert element.geometry.arm_length_mm == 5 and element.geometry.web_thickness_mm == 0.3
    assert len(jaw.part.solids()) == 1
    assert jaw.part.volume == pytest.approx(30 * 20 * 8 + element.volume, rel=1e-6)
    box = jaw.part.bounding_box()
    assert box.max.Z == pytest.approx(element.geometry.base_height_mm + 1.5, abs=1e-6)  # 11.5 mm


def test_flexure_element_subtracts_in_buildpart():
    import build123d as bd

    with bd.BuildPart() as block:
        bd.Box(40, 20, 10)
        tactcad.FlexureElement(align=bd.Align.CENTER, mode=bd.Mode.SUBTRACT)  # inside the box
    assert block.part.volume == pytest.approx(40 * 20 * 10 - tactcad.FlexureElement().volume,
                                              rel=1e-6)


def test_flexure_element_refuses_with_the_design_files_message():
    with pytest.raises(DesignErrors) as by_class:
        tactcad.FlexureElement(web_thickness_mm=1.55)
    with pytest.raises(DesignErrors) as by_file:
        tactcad.load(set={"element.web_thickness_mm": 1.55})
    same = ("field", "value", "allowed", "why")
    assert [getattr(by_class.value.errors[0], a) for a in same] == \
        [getattr(by_file.value.errors[0], a) for a in same]
    with pytest.raises(DesignErrors) as arm:
        tactcad.FlexureElement(arm_length_mm=25)
    assert len(arm.value.errors) == 1  # once, not once per element of the array
    assert arm.value.field == "arms.lengths_mm[1]" and "2 <= value <= 20 mm" in str(arm.value)
    with pytest.raises(DesignErrors, match="web_thickness_mm = 'x'"):
        tactcad.FlexureElement(web_thickness_mm="x")


def test_flexure_array_is_the_designs_array():
    from tactcad.catalogue.array_catalogue import array_instances

    a = tactcad.FlexureArray(pitch_mm=4.5)
    assert a.plan.pitch_mm == 4.5
    assert len(a.solids()) == len(array_instances(a.plan)) == 38  # 28 parts + 10 gauges
    with pytest.raises(DesignErrors, match="arms.lengths_mm"):
        tactcad.FlexureArray(arm_lengths_mm=[4, 5])


def test_show_is_optional():
    try:
        import ocp_vscode  # noqa: F401
    except ImportError:
        assert tactcad.show(tactcad.FlexureElement()) is False
    else:  # pragma: no cover - only where the viewer is installed
        pytest.skip("ocp_vscode installed: show() would open the viewer")


# --- docs: "Use tactcad from Python" runs as written --------------------------------------
@pytest.mark.slow  # a whole chain through the command line or an export
def test_docs_python_example_runs(tmp_path):
    code = docs_block("how-to/python.md")
    assert DOCS_DESIGN_LINE in code  # the one path the example names
    code = code.replace(DOCS_DESIGN_LINE, f"DESIGN = {str(DOCS_EXAMPLE_DESIGN)!r}")
    script = tmp_path / "example.py"
    script.write_text(code, encoding="utf-8")
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path,
                         capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""  # no raw warning reaches the user
    lines = out.stdout.splitlines()
    project = tactcad.load(DOCS_EXAMPLE_DESIGN, set={"element.web_thickness_mm": 0.2})
    element = project.element(2)
    name = element.part_name
    assert lines[0] == f"{name} web 0.2 mm"
    # the element stands on the 30 x 20 x 8 mm jaw: one solid of both volumes
    jaw = re.fullmatch(r"jaw: 1 solid, (\d+) mm\^3", lines[1])
    assert jaw and int(jaw[1]) == pytest.approx(30 * 20 * 8 + element.solid.volume, abs=1)
    assert lines[2].startswith(f"K = {element.stiffness().stiffness_N_per_mm:.2f} N/mm")
    assert lines[-1] == f"['step/{name}.step', 'manifest.json']"
    step = tmp_path / "exports-web0p2" / "step" / f"{name}.step"
    assert step.read_bytes().startswith(b"ISO-10303-21;")


@pytest.mark.slow
def test_docs_freecad_script_runs_in_freecadcmd(freecad, tmp_path):
    project = tactcad.load()
    result = project.export(tmp_path / "exports", only="step", cache=False)
    array = next(f for f in result.files if f["path"] == "step/array.step")
    code = docs_block("how-to/freecad.md")
    line = 'STEP = "exports/step/array.step"'
    assert line in code
    script = tmp_path / "review.py"
    script.write_text(code.replace(line, f"STEP = {str(tmp_path / 'exports/step/array.step')!r}"),
                      encoding="utf-8")
    out = subprocess.run([freecad, str(script)], cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    found = re.search(r"^(\d+) solids; parts: (.*)$", out.stdout, re.M)
    assert found, out.stdout[-2000:]
    assert int(found.group(1)) == array["solids"] == 38  # with the 10 gauges
    from tactcad.catalogue.array_catalogue import array_parts

    assert found.group(2).split(", ") == sorted(array_parts(project.plan))
    assert (tmp_path / "array-review.FCStd").stat().st_size > 1000


# --- plain results, element numbers, keyword names ------------------------------------------
def test_an_api_result_holds_plain_python_that_json_takes():
    import numpy as np

    from tactcad.api import plain

    raw = {"dofs": np.int32(7), "passed": np.True_, "k": np.float64(1.5),
           "beams": np.array([1, 2], dtype=np.int32), "rows": (np.int64(3), [np.float32(0.5)]),
           np.int64(4): "key", "text": "a"}
    out = plain(raw)
    assert json.loads(json.dumps(out)) == {"dofs": 7, "passed": True, "k": 1.5, "beams": [1, 2],
                                           "rows": [3, [0.5]], "4": "key", "text": "a"}
    assert type(out["dofs"]) is int and out["passed"] is True and type(out["k"]) is float
    assert isinstance(out["rows"], list)  # as the command's JSON writes a tuple


def test_a_check_result_holds_a_bool_whatever_computed_its_verdict():
    import numpy as np

    from tactcad.checks.check_result import CheckResult

    result = CheckResult("c", "s", np.True_, undecided=np.False_)
    assert result.passed is True and result.undecided is False
    assert json.dumps({"passed": result.passed}) == '{"passed": true}'


@pytest.mark.parametrize("number", [True, 2.0, "2", 0, 11, None])
def test_an_element_is_asked_by_an_integer_in_the_designs_range(number):
    project = tactcad.load(EXAMPLE_DESIGN)
    with pytest.raises(DesignError) as err:
        project.element(number)
    assert err.value.field == "number" and err.value.value == number
    assert "an integer 1 ... 10" in str(err.value)


def test_an_element_number_of_numpy_integer_type_is_taken():
    import numpy as np

    assert tactcad.load(EXAMPLE_DESIGN).element(np.int64(3)).number == 3


def test_an_api_refusal_names_the_keyword_argument_not_the_commands_option(tmp_path):
    project = tactcad.load(EXAMPLE_DESIGN)
    with pytest.raises(DesignError) as err:
        project.export(tmp_path / "x", only="dxff")
    assert err.value.field == "only" and "--only" not in str(err.value)


def test_a_command_keeps_its_option_names_and_the_api_after_it_its_keywords(tmp_path, capsys):
    # the command runs the API's method: its refusal names --out, as the command's help does
    from tactcad.cli import main

    blocker = tmp_path / "file"
    blocker.write_text("not a folder", encoding="utf-8")
    assert main(["check", "--design", str(EXAMPLE_DESIGN), "--out", str(blocker / "x"),
                 "--json"]) == 2
    assert json.loads(capsys.readouterr().out)["error"]["message"].startswith("--out ")
    project = tactcad.load(EXAMPLE_DESIGN)
    with pytest.raises(DesignError) as err:
        project.export(tmp_path / "y", only="dxff")
    assert err.value.field == "only"


def test_option_names_in_a_refusals_words_become_keyword_arguments():
    from tactcad.api import with_keyword_names
    from tactcad.errors import ExportPathError

    exc = DesignError("--force-N", 9.0, "0 ... 2 N", "paste --force-N 1.5 or --angle-deg 4",
                      alternatives=[{"option": "--slab-thickness-mm 2", "words": "thinner"}])
    named = with_keyword_names(exc, ["force_N", "angle_deg", "slab_thickness_mm"])
    assert named.field == "force_N" and named.why == "paste force_N=1.5 or angle_deg=4"
    assert named.alternatives == [{"option": "slab_thickness_mm=2", "words": "thinner"}]
    both = with_keyword_names(DesignErrors([exc, DesignError("--kobj", -1, "> 0 N/mm")]),
                              ["force_N", "kobj"])
    assert [e.field for e in both.errors] == ["force_N", "kobj"]
    path = with_keyword_names(ExportPathError("--out a/b.toml: a file"), ["out"])
    assert type(path) is ExportPathError and str(path) == "out=a/b.toml: a file"
    other = DesignError("--design", "x", "a file")  # no keyword of the call: left as it is
    assert with_keyword_names(other, ["out"]) is other


def test_check_refuses_an_out_no_export_can_be_written_to_before_solving(tmp_path, monkeypatch):
    """A check whose --out cannot take an export is refused before its requirements are
    decided (a cold store's fem3d decision took 90 s before the refusal)."""
    import tactcad.checks.groups as groups
    from tactcad.errors import ExportPathError

    ran: list[str] = []
    monkeypatch.setattr(groups, "run_groups", lambda *args, **kwargs: ran.append("groups"))
    blocker = tmp_path / "file"
    blocker.write_text("not a folder", encoding="utf-8")
    with pytest.raises(ExportPathError):
        tactcad.load(EXAMPLE_DESIGN).check(out=blocker / "x", cache=False)
    assert ran == []


@pytest.mark.parametrize("cache, why", [("a_file", "it is an existing file"),
                                        ("a_file/sub", "is not a folder"),
                                        (3, "True, False, None or a path")])
def test_an_unusable_cache_is_refused_naming_the_argument_before_any_work(tmp_path, cache, why):
    (tmp_path / "a_file").write_text("x", encoding="utf-8")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        project = tactcad.load(EXAMPLE_DESIGN)
        for call in (lambda: project.export(out="out", cache=cache),
                     lambda: project.check(out="out", cache=cache)):
            with pytest.raises(DesignError) as err:
                call()
            assert err.value.field == "cache" and why in str(err.value)
    finally:
        os.chdir(cwd)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"]  # nothing written


def test_the_apis_refusals_name_its_own_parameters_and_every_value_it_takes():
    # verify(model="nope") listed the ladder's levels without its own default, auto; grasp
    # named the command's --coupling and --profile for its keyword arguments
    from tactcad.mechanics.ladder import models

    project = tactcad.load(EXAMPLE_DESIGN)
    with pytest.raises(ValueError) as refused:
        project.verify(model="nope")
    assert str(refused.value) == f"model = 'nope': allowed {', '.join(('auto', *models()))}"
    for keyword in ("coupling", "profile"):
        with pytest.raises(DesignError) as refused:
            project.grasp(**{keyword: "nope"})
        assert refused.value.field == keyword, refused.value
