"""The silicon die as a first-class product: `strength` and `stiffness` answer for it with
the numbers its plan and its verification hold, `tactcad.load` gives its project, `design
--jaw 5 --out DIR` writes a project folder, and its export ends with a review page and a
manifest as an array's does."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli

def test_strength_on_a_die_gives_each_rows_root_against_etched_silicon(die_folder):
    from tactcad.commands.die import _die_args, die_asked, plan_of
    from tactcad.products.silicon_die.design.mems_die import BOSCH_MEAN_STRENGTH_MPA

    r = run_cli("strength", "--json", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    report = json.loads(r.stdout)
    plan = plan_of(die_asked(_die_args(die_folder / EXAMPLE.name,
                                       _Args(overrides=[]), Path(".")))).plan
    for row, beam in zip(report["rows"], plan.beams[:: plan.columns]):
        # the root's peak on its fillets, the number the die command prints
        stress = plan.root_peak_stress_MPa_at_rated_force(beam)
        assert row["root_peak_stress_MPa_at_rated_force"] == pytest.approx(stress, rel=1e-12)
        assert row["root_peak_stress_MPa_per_N"] == pytest.approx(
            row["root_stress_concentration_factor"] * row["root_nominal_stress_MPa_per_N"],
            rel=1e-12)
        assert row["root_stress_concentration_factor"] > 1.0
        assert row["root_fillet_um"] == plan.root_fillet_um
        assert row["fracture_force_N"] * row["root_peak_stress_MPa_per_N"] == pytest.approx(
            BOSCH_MEAN_STRENGTH_MPA)
    assert report["requirement"]["requirement"] == "full_scale_force_N"
    refused = run_cli("strength", "--model", "fem2d", "--json", cwd=die_folder)
    assert refused.returncode == 2 and json.loads(refused.stdout)["error"]["field"] == "--model"


class _Args:
    def __init__(self, **kw):
        self.__dict__.update(kw)


def test_stiffness_on_a_die_is_each_rows_beam_and_the_api_reads_the_same(die_folder):
    import tactcad

    r = run_cli("stiffness", "--json", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    report = json.loads(r.stdout)
    project = tactcad.load(die_folder / EXAMPLE.name)
    assert isinstance(project, tactcad.DieProject)
    assert tactcad.load_die(die_folder / EXAMPLE.name).plan == project.plan  # the typed door
    ks = [row["stiffness_N_per_mm"] for row in report["rows"]]
    assert ks == [project.plan.k_r_N_per_mm, project.plan.k_m_N_per_mm]
    assert project.stiffness()["rows"] == report["rows"]  # one computation, CLI and API
    assert project.strength()["rows"] == json.loads(
        run_cli("strength", "--json", cwd=die_folder).stdout)["rows"]
    smaller = tactcad.load(die_folder / EXAMPLE.name, set={"die.columns": 3})
    assert smaller.plan.columns == 3
    with pytest.raises(tactcad.DesignErrors, match="die.columns"):
        tactcad.load(die_folder / EXAMPLE.name, set={"die.columns": "three"})
    # an --element means nothing for a die: refused by name, not ignored
    refused = run_cli("stiffness", "--element", "2", "--json", cwd=die_folder)
    assert refused.returncode == 2 and json.loads(refused.stdout)["error"]["field"] == "--element"


def test_stiffness_of_an_array_still_needs_its_element(tmp_path):
    r = run_cli("stiffness", "--json", cwd=tmp_path)
    assert r.returncode == 2 and json.loads(r.stdout)["error"]["field"] == "--element"


def test_design_for_a_5mm_jaw_writes_a_die_project_folder(tmp_path):
    argv = ("design", "--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.05", "0.5",
            "--full-scale-force", "0.0019", "--out", "palp-die")
    r = run_cli(*argv, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    folder = tmp_path / "palp-die"
    written = {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}
    # besides the project's files, only the design's kept solves, for the export after it
    assert {w for w in written if not w.startswith(".tactcad-cache/")} == {
        "README.md", ".gitignore", ".github/workflows/hardware.yml", "palp_die.toml"}
    assert ".tactcad-cache" in (folder / ".gitignore").read_text()
    assert "palp_die.toml" in (folder / ".github/workflows/hardware.yml").read_text()
    again = run_cli(*argv, cwd=tmp_path)  # the folder holds the files: named, not searched
    assert again.returncode == 2 and "--out" in again.stderr and "comb" not in again.stderr
    assert run_cli(*argv, "--force", cwd=tmp_path).returncode == 0


@pytest.mark.slow
def test_a_dies_export_has_its_review_page_and_manifest_and_checks(die_folder):
    r = run_cli("export", "--out", "exports", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    out = die_folder / "exports"
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["product"] == "silicon-die"
    # its beams as its rows, each with its role and its own rated force
    assert [(r["row"], r["role"]) for r in manifest["rows"]] == [(1, "reference"),
                                                                 (2, "measuring")]
    assert "elements" not in manifest
    assert manifest["rows"][1]["rated_force_N"] < manifest["die"]["full_scale_force_N"]
    # the arrays' sections, in their layout: one script reads every product's manifest
    requirements = manifest["requirements"]
    assert {r["requirement"] for r in requirements["closed_form_matrix"]} >= {
        "full_scale_force_N", "kr_over_km"}
    assert {r["model"] for r in requirements["closed_form_matrix"]} <= {"closed-form", "drawn"}
    first = requirements["first_resonance"]
    assert first["lowest_first_Hz"] == min(e["first_Hz"] for e in first["elements"]) > 1e3
    assert manifest["kobj_budget"]
    listed = {f["path"] for f in manifest["files"]}
    assert {"review/index.html", "grasper_jaw_5mm_mems.gds", "scenes/"
            "grasper_jaw_5mm_mems_in_jaw.glb"} <= listed
    import hashlib

    for f in manifest["files"]:
        assert hashlib.sha256((out / f["path"]).read_bytes()).hexdigest() == f["sha256"]
    page = (out / "review" / "index.html").read_text(encoding="utf-8")
    assert manifest["design"]["sha256"] in page and "kr_over_km" in page
    c = run_cli("check", "--out", "exports", "--junit", "report.xml", cwd=die_folder)
    assert c.returncode == 0, c.stdout
    assert (out / "review" / "checks.js").is_file()
    # the same die writes the same bytes (the GDS header's time is not the clock's)
    d = run_cli("diff", EXAMPLE.name, "exports", "--json", cwd=die_folder)
    assert d.returncode == 0 and json.loads(d.stdout)["changed"] is False, d.stdout


@pytest.mark.slow
def test_a_dies_check_leaves_hand_edits_as_they_are_and_fails_them(die_folder):
    """As an array's check: a file changed or removed by hand since the export is never
    written over; each fails the export_file check and the rest is checked as it is (a
    cut-short GDS is no traceback). A changed design is exported again, said in one line."""
    assert run_cli("export", "--out", "exports", "--quiet", cwd=die_folder).returncode == 0
    out = die_folder / "exports"
    gds = out / "grasper_jaw_5mm_mems.gds"
    with open(gds, "r+b") as fh:
        fh.truncate(100)
    cut = gds.read_bytes()
    with open(out / "grasper_jaw_5mm_mems_traveller.md", "a", encoding="utf-8") as fh:
        fh.write("a step of our own\n")
    traveller = (out / "grasper_jaw_5mm_mems_traveller.md").read_bytes()
    c = run_cli("check", "--out", "exports", "--json", cwd=die_folder)
    assert c.returncode == 1, c.stdout + c.stderr
    report = json.loads(c.stdout)
    assert report["reused_export"] and report["export_refusal"] is None
    edited = {x["subject"]: x["detail"] for x in report["checks"]
              if x["check"] == "export_file" and x["status"] == "fail"}
    assert set(edited) == {"grasper_jaw_5mm_mems.gds", "grasper_jaw_5mm_mems_traveller.md"}
    assert all(d.startswith("edited since the export: sha256 differs from manifest.json")
               and "`tactcad export --out exports` writes it again" in d for d in edited.values())
    assert gds.read_bytes() == cut  # left as the hand left it
    assert (out / "grasper_jaw_5mm_mems_traveller.md").read_bytes() == traveller

    assert run_cli("export", "--out", "exports", "--quiet", cwd=die_folder).returncode == 0
    c = run_cli("check", "--out", "exports", cwd=die_folder)  # now as listed: taken as it is
    assert c.returncode == 0 and "checking the export in exports as it is (same design" \
        in c.stderr, c.stderr
    assert "exporting" not in c.stderr
    c = run_cli("check", "--out", "exports", "--set", "die.columns=4", cwd=die_folder)
    assert "exporting to exports first: made from another design" in c.stderr, c.stderr


def test_a_die_takes_a_grasp_force_judged_as_grasp_computes_it(die_folder):
    """`max_grasp_force_N` in a die's file: verify closes the die's jaw to it on the
    default tissue (the grasp command's own defaults) and judges each beam against its
    breaking force, the stops taking the rest, and the stops' load path (the post, the
    cavity floor); a force the jaw cannot reach fails. With the posts on their stops and
    the face in the tissue (the whole grasp on the posts: an upper bound) the row is still
    judged; its predicted figure is a grasp force, as its target is."""
    r = run_cli("verify", "--set", "die.max_grasp_force_N=2", "--json", cwd=die_folder)
    assert r.returncode == 0, r.stdout
    row = next(x for x in json.loads(r.stdout)["matrix"]
               if x["requirement"] == "max_grasp_force_N")
    assert "not judged" not in row["binding_words"] and "upper bound" in row["binding_words"]
    assert row["verdict"] == "pass" and row["binding_item"].startswith("post")
    assert row["predicted"] == pytest.approx(2 * (1 + row["margin_rel"]), rel=1e-9)
    g = json.loads(run_cli("grasp", "--force-N", "2", "--json", cwd=die_folder).stdout)
    beam = int(row["binding_words"].split("; beam ")[1].split(":")[0])
    tip = next(t for t in g["grasp"]["tips"] if t["site"] == beam)
    assert tip["element_force_N"] == pytest.approx(row["element_force_N"], rel=1e-12)
    light = run_cli("verify", "--set", "die.max_grasp_force_N=0.005", "--json", cwd=die_folder)
    row = next(x for x in json.loads(light.stdout)["matrix"]
               if x["requirement"] == "max_grasp_force_N")
    assert row["verdict"] == "pass" and "on their stops: none" in row["binding_words"]
    # a grasp force against a grasp force: the grasp at which the beam reaches its limit
    assert row["predicted"] == pytest.approx(
        0.005 * row["overload_limit_N"] / row["element_force_N"], rel=1e-9)
    assert row["margin_rel"] == pytest.approx(row["predicted"] / row["target"] - 1, rel=1e-9)
    far = run_cli("verify", "--set", "die.max_grasp_force_N=90", "--json", cwd=die_folder)
    assert far.returncode == 1
    row = next(x for x in json.loads(far.stdout)["matrix"]
               if x["requirement"] == "max_grasp_force_N")
    assert row["verdict"] == "fail" and "reach" in row["binding_words"]
    bad = run_cli("verify", "--set", "die.max_grasp_force_N=-1", "--json", cwd=die_folder)
    assert bad.returncode == 2
    assert json.loads(bad.stdout)["error"]["field"].endswith("max_grasp_force_N")


def test_design_for_a_die_takes_max_grasp_force_or_pastes_the_jaws_reach(tmp_path):
    argv = ("design", "--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.05", "0.5",
            "--full-scale-force", "0.0019", "--out", "gripped")
    far = run_cli(*argv, "--max-grasp-force", "50", "--json", cwd=tmp_path)
    assert far.returncode == 2 and not (tmp_path / "gripped").exists()
    error = json.loads(far.stdout)["error"]
    assert error["field"] == "--max-grasp-force"
    paste = error["alternatives"][0]["option"].split()[-1]
    r = run_cli(*argv, "--max-grasp-force", paste, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    text = (tmp_path / "gripped" / "gripped.toml").read_text(encoding="utf-8")
    assert f"max_grasp_force_N = {float(paste)}" in text
    assert run_cli("verify", cwd=tmp_path / "gripped").returncode == 0


@pytest.mark.parametrize("kr_over_km, kobj, force", [
    (10.0, (0.05, 0.5), 0.05),    # the measuring row's cavity binds
    (10.0, (0.5, 5.0), 0.6),      # the strength of etched silicon at a root
    (4.0, (0.2, 2.0), 1.0),
    (20.0, (0.02, 0.2), 0.2)])
def test_the_dies_refusal_states_its_true_frontier(kr_over_km, kobj, force):
    """The rating a refusal states designs, and 1 % above it is refused (it was 'about',
    5 % steps below the limit)."""
    from tactcad.errors import DesignError
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.design.mems_die import die_plan
    from tactcad.studies.inverse_design import Targets

    room = jaw_room("5")
    with pytest.raises(DesignError) as refused:
        die_plan(Targets(kr_over_km, kobj, force), room)
    paste = float(refused.value.alternatives[0]["option"].split()[-1])
    assert f"at most {paste:g} N" in refused.value.allowed
    assert die_plan(Targets(kr_over_km, kobj, paste), room).full_scale_force_N == paste
    with pytest.raises(DesignError, match="full-scale-force"):
        die_plan(Targets(kr_over_km, kobj, 1.01 * paste), room)


def test_a_thin_robotic_jaw_gets_the_die_where_no_comb_fits(tmp_path):
    """A wristed instrument's jaw 2.5 mm thick: no comb fits it (its refusal is not the
    jaw's pocket but its arms), so auto tries the die, which does, and says why not the comb
    (it was refused with the comb's refusal alone)."""
    (tmp_path / "robot_jaw.toml").write_text(
        "[grasper_jaw]\nshaft_class_mm = \"10\"\nwidth_mm = 4.0\nlength_mm = 20.0\n"
        "thickness_mm = 2.5\npin_diameter_mm = 1.5\npin_inset_mm = 2.0\n"
        "opening_angle_deg = 45.0\n", encoding="utf-8")
    argv = ("design", "--jaw", "robot_jaw.toml", "--kr-over-km", "10", "--kobj-range", "0.05",
            "0.5", "--out", "robot")
    too_much = run_cli(*argv, "--full-scale-force", "0.01", "--json", cwd=tmp_path)
    assert too_much.returncode == 2
    error = json.loads(too_much.stdout)["error"]
    assert "silicon die" in error["message"] and "monolithic-comb" in error["message"]
    paste = error["alternatives"][0]["option"].split()[-1]
    r = run_cli(*argv, "--full-scale-force", paste, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    text = (tmp_path / "robot" / "robot.toml").read_text(encoding="utf-8")
    assert "[die]" in text and "monolithic-comb" in text  # why not the comb, in its reasons
    assert (tmp_path / "robot" / "robot_jaw.toml").is_file()
    assert run_cli("verify", cwd=tmp_path / "robot").returncode == 0


def test_a_dies_jaw_file_with_a_space_in_its_name_is_quoted_in_its_reason(tmp_path):
    """``[assumptions] die.jaw`` writes the command that chose the die: its jaw file, named
    with a space, pastes into a shell as one word; the design stays valid TOML."""
    import shlex
    import tomllib

    (tmp_path / "our jaw.toml").write_text(
        "[grasper_jaw]\nshaft_class_mm = \"10\"\nwidth_mm = 4.0\nlength_mm = 20.0\n"
        "thickness_mm = 2.5\npin_diameter_mm = 1.5\npin_inset_mm = 2.0\n"
        "opening_angle_deg = 45.0\n", encoding="utf-8")
    r = run_cli("design", "--jaw", "our jaw.toml", "--construction", "mems-die",
                "--kr-over-km", "10", "--kobj-range", "0.05", "0.5", "--full-scale-force",
                "0.002", "--out", "robot.toml", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    written = tomllib.loads((tmp_path / "robot.toml").read_text(encoding="utf-8"))
    command = written["assumptions"]["die.jaw"].split(":", 1)[0]
    assert shlex.split(command) == ["tactcad", "design", "--jaw", "our jaw.toml"], command


#: an 8 mm wristed instrument's 2.6 mm jaw (the shipped robotic example's), as a table
ROBOT_JAW = {"shaft_diameter_mm": 8.0, "width_mm": 4.2, "length_mm": 16.0,
             "thickness_mm": 2.6, "opposing_jaw_mm": 2.6, "pin_diameter_mm": 1.5,
             "pin_inset_mm": 1.1, "opening_angle_deg": 45.0}


def test_a_stated_pocket_depth_is_the_dies_and_its_carrier_fills_it():
    from tactcad.errors import DesignError
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.design.die_mount import CARRIER_MM, die_mount
    from tactcad.products.silicon_die.design.mems_die import die_plan
    from tactcad.studies.inverse_design import Targets

    plan = die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room(ROBOT_JAW, "robot.toml"))
    own = die_mount(plan, ROBOT_JAW)
    assert own.carrier_mm == CARRIER_MM  # no depth stated: the die machines its own pocket
    stated = die_mount(plan, {**ROBOT_JAW, "pocket_depth_mm": 0.9})
    assert stated.pocket_depth_mm == 0.9
    assert stated.carrier_mm == pytest.approx(0.9 - stated.die_stack_mm - stated.attach_mm)
    assert stated.carrier_mm > CARRIER_MM and "pocket_depth_mm" in stated.reasons["carrier"]
    for depth in (own.pocket_depth_mm - 0.01, 2.2):  # no stock carrier fits; no steel under
        with pytest.raises(DesignError) as err:
            die_mount(plan, {**ROBOT_JAW, "pocket_depth_mm": depth})
        assert err.value.field == "grasper_jaw.pocket_depth_mm"
        assert f"{own.pocket_depth_mm:.4g} ... 2.1 mm" == err.value.allowed


#: Lab jaw files the die does not fit (a ``[grasper_jaw]`` each, mm): too thin for the die,
#: its attach and carrier over the steel under them; thin with a shallow stated pocket; a
#: shallow stated pocket; thin in a 5 mm shaft that the thicker jaw passes only narrowed;
#: thin in a 5 mm shaft that no thicker jaw holding the die passes closed
THIN_JAW = {"shaft_diameter_mm": 8.0, "width_mm": 4.0, "length_mm": 20.0, "thickness_mm": 1.0,
            "opposing_jaw_mm": 2.6, "pin_inset_mm": -3.0, "opening_angle_deg": 45.0}
DIE_PASTE_JAWS = {
    "thin": THIN_JAW,
    "thin_shallow": {**THIN_JAW, "pocket_depth_mm": 0.4},
    "shallow": {**THIN_JAW, "thickness_mm": 2.0, "pocket_depth_mm": 0.5},
    "narrowed": {**THIN_JAW, "shaft_diameter_mm": 5.0, "opposing_jaw_mm": 2.9, "width_mm": 3.0},
    "shaft": {**THIN_JAW, "shaft_diameter_mm": 5.0, "opposing_jaw_mm": 3.6, "width_mm": 1.9},
}


def _write_jaw(path: Path, table: dict) -> None:
    """A lab's jaw file: its ``[grasper_jaw]`` table as TOML."""
    lines = [f"{k} = {json.dumps(v)}" for k, v in table.items()]
    path.write_text("[grasper_jaw]\n" + "\n".join(lines) + "\n", encoding="utf-8")


@pytest.mark.parametrize("name", sorted(DIE_PASTE_JAWS))
def test_every_die_jaw_paste_loads_through_the_jaws_rules_and_seats_the_die(tmp_path, name):
    """Each jaw file key the die's refusal offers, written into the file and read back as
    ``--jaw FILE`` is (each key's range, the pivot, the depth, the closed jaws in the
    shaft), makes a jaw the die fits; where none would (the thicker jaw passes its shaft at
    no width that holds the die), none is offered and the refusal names the shaft it needs
    (it once offered a thicker jaw that its own shaft refused)."""
    import math

    from tactcad.commands.design import jaw_of
    from tactcad.errors import DesignErrors
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.design.die_mount import die_misfit
    from tactcad.products.silicon_die.design.mems_die import DEFAULT_COLUMNS

    path = tmp_path / f"{name}.toml"
    _write_jaw(path, DIE_PASTE_JAWS[name])
    room = jaw_room(*jaw_of(str(path)))
    missed = die_misfit(room, room.table, DEFAULT_COLUMNS)
    assert missed  # the die does not fit the file as it stands
    pastes = [m["option"] for m in missed if m["option"].startswith("grasper_jaw.")]
    if name == "shaft":
        table = DIE_PASTE_JAWS[name]
        assert pastes == [] and len(missed) == 1
        words = missed[0]["words"]
        assert "no jaw of the 5 mm shaft holds it" in words and "shaft_diameter_mm" in words
        need = float(words.split("a shaft of at least ")[1].split(" mm")[0])
        thick = float(words.split("needs closed jaws ")[1].split(" mm")[0])
        assert thick >= 1.18 and need > table["shaft_diameter_mm"]
        # the thinnest jaw the die takes, at the narrowest width that holds its pocket,
        # passes no 5 mm shaft closed: the shaft named is at least their diagonal
        narrowest = float(words.split("at least ")[1].split(" mm wide")[0])
        assert need >= math.hypot(narrowest, thick + table["opposing_jaw_mm"]) - 1e-9
        with pytest.raises(DesignErrors):
            jaw_room({**table, "thickness_mm": thick, "width_mm": narrowest}, str(path))
        return
    assert pastes  # a lab's own file, a misfit its keys mend: something to paste
    for paste in pastes:
        keys, _, file = paste.rpartition(" in ")
        assert file == str(path)
        table = dict(DIE_PASTE_JAWS[name])
        for key in keys.split(" and "):
            field, value = key.removeprefix("grasper_jaw.").split(" = ")
            table[field] = float(value)
        pasted = tmp_path / f"{name}_pasted.toml"
        _write_jaw(pasted, table)
        again = jaw_room(*jaw_of(str(pasted)))  # raises on any key the jaw's rules refuse
        assert die_misfit(again, again.table, DEFAULT_COLUMNS) == []


def test_a_pocket_no_product_fits_is_refused_naming_its_keys_for_each(tmp_path):
    """A 0.5 x 1 mm pocket: the comb's width and length and the die's, each against the
    pocket's key (it was '--columns = 4: allowed at most 0 columns'), with what to paste."""
    (tmp_path / "tiny.toml").write_text(
        "[grasper_jaw]\nshaft_class_mm = \"10\"\nwidth_clearance_mm = 3.5\nlength_mm = 34.0\n"
        "thickness_mm = 5.6\npin_inset_mm = 2.5\nopening_angle_deg = 30.0\n"
        "pocket_width_mm = 0.5\npocket_length_mm = 1.0\n", encoding="utf-8")
    r = run_cli("design", "--jaw", "tiny.toml", "--kr-over-km", "10", "--kobj-range", "0.5",
                "5", "--full-scale-force", "0.009", "--columns", "4", "--out", "x", "--json",
                cwd=tmp_path)
    assert r.returncode == 2 and not (tmp_path / "x").exists()
    error = json.loads(r.stdout)["error"]
    lines = error["message"].splitlines()
    comb = next(x for x in lines if x.strip().startswith("monolithic-comb: does not fit"))
    die = next(x for x in lines if x.strip().startswith("silicon die: does not fit"))
    assert "pocket_width_mm 0.5" in comb and "pocket_length_mm 1" in comb
    assert "vs the pocket's 0.3 mm" in die and "(pocket_length_mm)" in die
    assert "at most 0 columns" not in error["allowed"]
    pasted = [a["option"] for a in error["alternatives"]]
    assert "grasper_jaw.pocket_length_mm = 5.7 in tiny.toml" in pasted and "--jaw 10" in pasted


@pytest.mark.slow  # two die designs and a verify through the command line
def test_design_for_a_die_takes_a_kobj_accuracy_or_pastes_what_it_reaches(tmp_path):
    """--kobj-accuracy with --jaw on a die: its budget's worst root sum square is judged
    before anything is written; the accuracy a refusal pastes designs, and verify judges it
    from the file."""
    (tmp_path / "robot.toml").write_text(
        "[grasper_jaw]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"')
                                    for k, v in ROBOT_JAW.items()), encoding="utf-8")
    argv = ("design", "--jaw", "robot.toml", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
            "--full-scale-force", "0.009", "--out", "robot")
    tight = run_cli(*argv, "--kobj-accuracy", "0.001", "--json", cwd=tmp_path)
    assert tight.returncode == 2 and not (tmp_path / "robot").exists()
    error = json.loads(tight.stdout)["error"]
    assert error["field"] == "--kobj-accuracy" and error["allowed"].startswith(">= 0.0")
    paste = error["alternatives"][0]["option"].split()[-1]
    r = run_cli(*argv, "--kobj-accuracy", paste, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    text = (tmp_path / "robot" / "robot.toml").read_text(encoding="utf-8")
    assert f"kobj_accuracy_rel = {float(paste)}" in text
    v = run_cli("verify", "--json", cwd=tmp_path / "robot")
    row = next(x for x in json.loads(v.stdout)["matrix"]
               if x["requirement"] == "kobj_accuracy_rel")
    assert v.returncode == 0 and row["verdict"] == "pass" and row["predicted"] <= float(paste)


@pytest.mark.slow  # three whole exports of a die (no store: each builds every file)
def test_a_dies_export_replaces_its_folder_whole_keeping_the_labs_own_files(die_folder,
                                                                            monkeypatch):
    """As an array's export: the new set is swapped in whole (a file the old export listed
    and the new one does not make is gone, a lab's own file stays), an export stopped before
    the swap leaves the old set byte for byte and no staging folder, and a folder that cannot
    be replaced whole (the working folder) is refused before any work."""
    import argparse

    from tactcad.commands import die as die_command

    out = die_folder / "exports"
    assert run_cli("export", "--out", "exports", "--quiet", cwd=die_folder).returncode == 0
    manifest = json.loads((out / "manifest.json").read_text())
    manifest["files"].append({"path": "old_only.txt", "sha256": "", "bytes": 3})
    (out / "manifest.json").write_text(json.dumps(manifest))
    (out / "old_only.txt").write_text("old")
    (out / "our_notes.txt").write_text("the lab's")
    assert run_cli("export", "--out", "exports", "--quiet", cwd=die_folder).returncode == 0
    assert not (out / "old_only.txt").exists()
    assert (out / "our_notes.txt").read_text() == "the lab's"
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}

    def stopped(*_args, **_kw):
        raise KeyboardInterrupt

    monkeypatch.chdir(die_folder)
    monkeypatch.setattr("tactcad.atomic.publish_dir", stopped)
    args = die_command._die_args(die_folder / EXAMPLE.name,
                                 argparse.Namespace(json=False, quiet=True), out)
    with pytest.raises(KeyboardInterrupt):
        die_command.run(args)
    assert {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
    assert not list(die_folder.glob(".exports.staging-*"))

    empty = die_folder / "here"
    empty.mkdir()
    r = run_cli("export", "--design", str(die_folder / EXAMPLE.name), "--out", ".", cwd=empty)
    assert r.returncode != 0 and "working folder" in r.stderr and "Traceback" not in r.stderr
    assert not list(empty.iterdir()) and not list(die_folder.glob(".here.*"))


@pytest.mark.slow  # a whole export of a die, then one read back from the store
def test_a_dies_second_export_is_read_from_the_store_byte_for_byte(die_folder, monkeypatch,
                                                                  capsys):
    """As an array's warm export: nothing changed, nothing is built again; the files and the
    printed report are the first run's. A changed design (a --set value) is built afresh."""
    from tactcad import cli
    from tactcad.commands import die as die_command

    design, store = str(die_folder / EXAMPLE.name), str(die_folder / "store")

    def export(out: str, *extra: str) -> tuple[int, dict, str]:
        code = cli.main(["export", "--design", design, "--cache", store, "--out",
                         str(die_folder / out), *extra])
        files = {p.relative_to(die_folder / out).as_posix(): p.read_bytes()
                 for p in (die_folder / out).rglob("*") if p.is_file()}
        return code, files, capsys.readouterr().out

    first = export("out_a")
    built = []
    original = die_command._build_die_export
    monkeypatch.setattr(die_command, "_build_die_export",
                        lambda *a, **k: built.append(1) or original(*a, **k))
    second = export("out_b")
    assert first[0] == second[0] == 0 and not built
    assert second[1] == first[1] and len(first[1]) > 10
    assert second[2].replace("out_b", "out_a") == first[2]
    changed = export("out_c", "--set", "die.full_scale_force_N=0.008")
    assert built == [1] and changed[1]["manifest.json"] != first[1]["manifest.json"]


@pytest.mark.slow  # three whole exports of a die
def test_a_dies_changed_requirement_rebuilds_only_the_files_it_shapes(die_folder, monkeypatch,
                                                                       capsys):
    """Each file of a die's export is a job of the store: a changed accuracy target (no
    geometry) builds no solid and keeps the STEP files, the masks and the pictures, and the
    export is byte for byte a fresh export of the changed design."""
    from tactcad import cli
    from tactcad.products.silicon_die.export import die_solid

    design, store = str(die_folder / EXAMPLE.name), str(die_folder / "store")

    def export(out: str, *extra: str) -> dict:
        assert cli.main(["export", "--design", design, "--out", str(die_folder / out), *extra,
                         "--quiet"]) == 0
        capsys.readouterr()
        return {p.relative_to(die_folder / out).as_posix(): p.read_bytes()
                for p in (die_folder / out).rglob("*") if p.is_file()}

    first = export("out_a", "--cache", store)
    built = []
    original = die_solid.die_layer_solids
    monkeypatch.setattr(die_solid, "die_layer_solids",
                        lambda *a, **k: built.append(1) or original(*a, **k))
    changed = ("--set", "die.kobj_accuracy_rel=0.5")
    second = export("out_b", "--cache", store, *changed)
    assert not built  # the solids' jobs came from the store
    name = EXAMPLE.stem
    kept = [f"{name}.step", f"{name}_in_jaw.step", f"{name}.gds", f"{name}_masks.png",
            f"{name}_in_jaw.png", f"scenes/{name}_in_jaw.glb"]
    assert all(second[f] == first[f] for f in kept)
    assert second[f"{name}.json"] != first[f"{name}.json"]
    fresh = export("out_c", "--no-cache", *changed)
    assert built and fresh == second


@pytest.mark.slow  # a whole export of a die, then one read back from the store
def test_a_dies_export_json_has_the_seconds_and_job_counts_and_quiet_prints_what_failed(
        die_folder):
    """`export --help` promises --json's seconds, jobs run and reused: a die's export gives
    them as an array's does (every job reused when the whole export is read from the store);
    `--quiet` of a die whose checks fail prints nothing on stderr and the summary an export
    without it prints (it printed the failed checks alone, an array's its whole summary)."""
    failing = ("--set", "die.kobj_accuracy_rel=0.001")  # the die's budget reaches ~0.036
    r = run_cli("export", *failing, "--out", "exports", "--json", cwd=die_folder)
    assert r.returncode == 1, r.stdout + r.stderr
    first = json.loads(r.stdout)
    assert first["seconds"] > 0 and first["jobs_run"] > 0 and first["jobs_reused"] >= 0
    q = run_cli("export", *failing, "--out", "exports", "--quiet", cwd=die_folder)
    assert q.returncode == 1 and q.stderr == "", q.stderr
    failed = [c for c in first["checks"] if c["status"] == "fail"]
    assert failed and all(c["check"] in q.stdout for c in failed), q.stdout
    loud = run_cli("export", *failing, "--out", "exports", cwd=die_folder)
    assert loud.returncode == 1 and loud.stdout == q.stdout
    again = json.loads(run_cli("export", *failing, "--out", "exports", "--json",
                               cwd=die_folder).stdout)
    assert again["jobs_run"] == 0
    assert again["jobs_reused"] == first["jobs_run"] + first["jobs_reused"]


@pytest.mark.parametrize("choice", [("--only", "dxf"), ("--scene", "x"), ("--part", "x")])
def test_an_arrays_choice_of_export_files_on_a_die_says_what_it_writes_and_pastes_it(
        die_folder, choice):
    """`export --only dxf` on a die was refused as "left out" with nothing to paste: the
    refusal says what the die's export writes (no DXF; its scene) and pastes the export."""
    r = run_cli("export", *choice, "--out", "e", "--json", cwd=die_folder)
    assert r.returncode == 2 and not (die_folder / "e").exists(), r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == choice[0]
    assert "no DXF" in error["message"] and "scenes/grasper_jaw_5mm_mems_in_jaw.glb" in \
        error["message"]
    assert error["alternatives"][0]["option"] == "tactcad export --out e"


def test_scenes_in_a_dies_folder_lists_the_scene_its_export_writes(die_folder):
    from tactcad.commands.die import DIE_FILES

    r = run_cli("scenes", "--json", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    (scene,) = json.loads(r.stdout)["scenes"]
    assert scene["name"] == "grasper_jaw_5mm_mems_in_jaw"
    assert DIE_FILES["glb"].format(name="grasper_jaw_5mm_mems") in scene["files"]
    assert {"grasper_jaw", "die_carrier", "grasper_jaw_5mm_mems_device"} <= {
        p["part"] for p in scene["groups"]["insert"]}
    r = run_cli("scenes", "wirecut", "--json", cwd=die_folder)
    assert r.returncode == 2 and scene["name"] in json.loads(r.stdout)["error"]["allowed"]


def test_a_dies_check_without_out_has_no_refusal_and_names_the_export_left_unread(
        die_folder, monkeypatch, capsys):
    """`check --json` without --out said `"export_refusal": "no manifest.json in
    /tmp/tactcad-die-check-..."` of its own temporary folder; exports/ was passed over
    without a word."""
    from tactcad import cli
    from tactcad.commands import die

    exported = []
    monkeypatch.setattr(die, "run", lambda args: exported.append(args.out))
    monkeypatch.chdir(die_folder)
    (die_folder / "exports").mkdir()
    (die_folder / "exports" / "manifest.json").write_text("{}", encoding="utf-8")
    lines = []
    args = cli.build_parser().parse_args(["check", "--json"])
    found = die.die_check(die_folder / EXAMPLE.name, args, lines.append)
    assert len(exported) == 1 and Path(exported[0]).name.startswith("tactcad-die-check-")
    assert found.export_refusal is None and not found.reused_export
    said = "\n".join(lines)
    assert "--out exports checks that export as it is" in said and "no manifest.json" not in said
    cli.main(["check", "--json"])
    report = json.loads(capsys.readouterr().out)
    assert report["export_refusal"] is None and report["reused_export"] is False
