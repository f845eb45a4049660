"""A sensor project is a folder: ``tactcad new``, the ``[files]`` table, the
rigs and scenes made for a design that has none, the design a command picks
without ``--design``, and the three.js the package ships."""

from __future__ import annotations

import json
import re
import shutil
import tomllib
from pathlib import Path

import pytest

from conftest import run_cli

import tactcad
from tactcad.cli import main
from tactcad.design.array_plan import DEFAULT_DESIGN, EXAMPLES
from tactcad.errors import DesignError, DesignErrors
from tactcad.project_folder import (companion_texts, default_design, examples, new_project,
                                    sample_stiffnesses)

#: The paper's samples (N/mm) and texts: never in what a non-paper design is given.
PAPER_SAMPLES = ("10.01", "7.26", "6.28", "5.41", "4.51", "3.85", "3.57", "2.34")


def _bare_design(folder: Path, text_edit=lambda t: t) -> Path:
    """The Ti example's design file alone in ``folder``, its [files] table removed."""
    text = (EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml").read_text(encoding="utf-8")
    text = re.sub(r"\[files\]\nrigs = .*\nscenes = .*\n", "", text)
    path = folder / "bare.toml"
    path.write_text(text_edit(text), encoding="utf-8")
    return path


def test_the_examples_are_project_folders_shipped_in_the_package():
    found = examples()
    assert set(found) >= {"macro_array", "ti_array_2x3"}
    assert found["macro_array"] == DEFAULT_DESIGN
    for design in found.values():
        files = tomllib.loads(design.read_text(encoding="utf-8"))["files"]
        assert files and all((design.parent / name).is_file() for name in files.values())
        assert (design.parent / files["scenes"]).is_file()


def test_new_from_an_example_copies_its_own_rigs_and_makes_the_rest(tmp_path):
    made = new_project(tmp_path / "p", example="ti_array_2x3")
    assert set(made.files) == {"p.toml", "rigs.toml", "scenes.toml", "README.md",
                               ".gitignore", ".github/workflows/hardware.yml",
                               "purchased-parts.md"}
    example = EXAMPLES / "ti_array_2x3"
    rigs, own = (tomllib.loads((f / "rigs.toml").read_text(encoding="utf-8"))
                 for f in (made.folder, example))
    assert {**rigs, "rigs": None} == {**own, "rigs": None}  # the hardware kept, renamed
    project = tactcad.load(made.design)
    assert project.validated.rigs_file == "rigs.toml"
    readme = (made.folder / "README.md").read_text(encoding="utf-8")
    assert "tactcad export --design p.toml" in readme and "$" not in readme
    assert "exports*/" in (made.folder / ".gitignore").read_text(encoding="utf-8")
    assert (made.folder.stat().st_mode & 0o777) != 0o700  # a shared folder, not a temp one


def test_new_from_the_grasper_example_has_no_rigs_and_its_own_bought_parts(tmp_path):
    made = new_project(tmp_path / "p", example="grasper_jaw_10mm")
    assert "rigs.toml" not in made.files and not (made.folder / "rigs.toml").exists()
    example = EXAMPLES / "grasper_jaw_10mm"
    assert (made.folder / "purchased-parts.md").read_bytes() == \
        (example / "purchased-parts.md").read_bytes()
    project = tactcad.load(made.design)  # a rigs file would be refused for a comb
    assert project.validated.rigs is None


def test_new_around_a_comb_design_without_scenes_makes_scenes_of_the_insert_only(tmp_path):
    text = (EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml").read_text(encoding="utf-8")
    design = tmp_path / "comb.toml"
    design.write_text(re.sub(r"\[files\]\nscenes = .*\n", "", text), encoding="utf-8")
    made = new_project(tmp_path / "p", from_design=design)
    assert set(made.files) == {"p.toml", "scenes.toml", "README.md", ".gitignore",
                               ".github/workflows/hardware.yml", "purchased-parts.md"}
    scenes = tomllib.loads((made.folder / "scenes.toml").read_text(encoding="utf-8"))["scene"]
    assert {s["rig"] for s in scenes.values()} == {"array", "grasper"}
    assert tomllib.loads(made.design.read_text(encoding="utf-8"))["files"] == {
        "scenes": "scenes.toml"}
    assert set(tactcad.load(made.design).validated.scenes) == set(scenes)


def test_a_comb_design_passes_over_a_rigs_file_that_only_lies_beside_it(tmp_path):
    example = EXAMPLES / "grasper_jaw_10mm"
    for name in ("grasper_jaw_10mm.toml", "scenes.toml"):
        shutil.copy(example / name, tmp_path / name)
    (tmp_path / "rigs.toml").write_text("not [ toml", encoding="utf-8")  # another design's
    project = tactcad.load(tmp_path / "grasper_jaw_10mm.toml").validated  # not even read
    assert project.rigs is None


def test_new_around_a_design_makes_rigs_over_its_own_kobj_range(tmp_path):
    design = _bare_design(tmp_path)
    made = new_project(tmp_path / "p", from_design=design)
    rigs = tomllib.loads((made.folder / "rigs.toml").read_text(encoding="utf-8"))
    samples = rigs["sample"]["stiffness_N_per_mm"]
    assert samples == [5.0, 2.24, 1.0]  # the design states K_obj 1 ... 5 N/mm
    scenes = (made.folder / "scenes.toml").read_text(encoding="utf-8")
    described = {n: s.description for n, s in tactcad.load(made.design).validated.scenes.items()}
    assert described["array"].startswith("The 2 x 3 array")
    assert "the 6 elements and 4 spacers" in described["wirecut"]
    text = (made.folder / "rigs.toml").read_text(encoding="utf-8") + scenes
    assert not [k for k in PAPER_SAMPLES if k in text] and "paper" not in text.lower()
    tables = tomllib.loads(made.design.read_text(encoding="utf-8"))
    assert tables["files"] == {"rigs": "rigs.toml", "scenes": "scenes.toml"}
    assert tactcad.load(made.design).validated.rigs.sample_stiffness_N_per_mm == (5.0, 2.24, 1.0)


def test_a_design_without_a_stated_range_gets_samples_over_its_elements_span(tmp_path):
    design = _bare_design(tmp_path, lambda t: re.sub(
        r"kobj_range_N_per_mm = \[\n.*\n.*\n\]\n", "", t))
    plan = tactcad.load(design).plan
    samples, reason = sample_stiffnesses(plan)
    assert "derived from the elements" in reason
    ks = sorted(e.stiffness().stiffness_N_per_mm for e in tactcad.load(design).elements)
    assert samples[0] == pytest.approx(ks[-1], rel=0.01) and samples[-1] == pytest.approx(ks[0], rel=0.01)


def test_a_bare_design_gets_rigs_made_for_it_never_the_papers(tmp_path):
    project = tactcad.load(_bare_design(tmp_path))
    assert project.validated.rigs_file == "rigs.toml (made for bare.toml)"
    assert project.validated.rigs.sample_stiffness_N_per_mm == (5.0, 2.24, 1.0)
    text = companion_texts(project.plan)["rigs"]
    assert "measure your own gauge" in text and "Sauter" not in text  # sized: not the paper's


@pytest.mark.parametrize("name, why", [
    ("missing.toml", "no file missing.toml beside"),
    ("../rigs.toml", "a relative path inside the design file's folder"),
    ("/etc/passwd", "a relative path inside the design file's folder"),
])
def test_a_named_companion_that_is_missing_or_outside_is_refused(tmp_path, name, why):
    design = _bare_design(tmp_path, lambda t: t + f'\n[files]\nrigs = "{name}"\n')
    with pytest.raises(DesignErrors) as err:
        tactcad.load(design)
    assert err.value.errors[0].field == "files.rigs" and why in str(err.value)


def test_a_folder_with_the_projects_files_is_refused_and_a_git_repository_is_not(tmp_path):
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    new_project(tmp_path / "repo")
    with pytest.raises(DesignError, match="DIR.*allowed a folder without the project's files"):
        new_project(tmp_path / "repo")
    new_project(tmp_path / "repo", force=True)
    assert not list(tmp_path.glob(".repo.staging-*"))


def test_a_renamed_project_folder_is_refused_once_for_its_other_design_not_for_force(tmp_path):
    """A project copied to a new name and designed into offered --force, which then refused
    for the other design file: the first refusal names the design file to move away."""
    from tactcad.project_folder import check_project_target

    new_project(tmp_path / "ti6")
    shutil.copytree(tmp_path / "ti6", tmp_path / "ti6b")
    for force in (False, True):
        with pytest.raises(DesignError) as info:
            check_project_target(tmp_path / "ti6b", "ti6b.toml", force)
        assert info.value.allowed == "a folder without another design file"
        assert "it holds ti6.toml" in str(info.value) and "move it away" in str(info.value)


def test_without_design_a_command_takes_the_project_folders_one_design(tmp_path, monkeypatch):
    assert default_design(tmp_path) == DEFAULT_DESIGN
    made = new_project(tmp_path / "p")
    monkeypatch.chdir(made.folder)
    assert default_design().resolve() == made.design.resolve()
    assert tactcad.load().name == "p"
    shutil.copy(made.design, made.folder / "second.toml")
    with pytest.raises(DesignError, match="--design.*one of p.toml, second.toml"):
        default_design()


def test_a_project_whose_design_file_does_not_parse_is_refused_not_replaced(tmp_path,
                                                                          monkeypatch, capsys):
    # a slip in the file made it no design file, so commands took the shipped example and
    # export overwrote the project's exports with the paper's array, exit 0
    made = new_project(tmp_path / "p")
    with open(made.design, "a", encoding="utf-8") as f:
        f.write("x =\n")
    monkeypatch.chdir(made.folder)
    with pytest.raises(DesignError, match="p.toml.*valid TOML"):
        default_design()
    assert main(["export", "--quiet"]) == 2
    assert "p.toml" in capsys.readouterr().err and not (made.folder / "exports").exists()


def test_new_on_the_command_line_says_what_it_wrote(tmp_path, capsys):
    assert main(["new", str(tmp_path / "p"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert Path(out["design"]).name == "p.toml" and "rigs.toml" in out["files"]
    assert main(["new", str(tmp_path / "q"), "--example", "nope"]) == 2
    assert f"--example = 'nope': allowed one of {', '.join(sorted(examples()))}" in capsys.readouterr().err
    assert not (tmp_path / "q").exists()


@pytest.mark.slow  # a whole chain through the command line or an export
def test_the_manifest_names_the_design_file_not_a_path():
    from tactcad.export.manifest import design_facts

    facts = design_facts(tactcad.load(DEFAULT_DESIGN.resolve()).plan)
    assert facts["design"]["source"] == "macro_array.toml"


def test_shipped_threejs_is_checked_before_a_page_carries_it(tmp_path, monkeypatch):
    from tactcad.export import review_assets as ra

    shipped = ra.three_dir()
    assert ra.three_version() == json.loads((shipped / "package.json").read_text())["version"]
    assert (shipped / "LICENSE").read_text().startswith("The MIT License")
    copy = tmp_path / "three"
    shutil.copytree(Path(str(shipped)), copy)
    (copy / "build" / "three.core.js").write_text("// changed", encoding="utf-8")
    monkeypatch.setattr(ra, "three_dir", lambda: copy)
    ra._import_map.cache_clear()
    try:
        with pytest.raises(ra.ReviewAssetsError, match="build/three.core.js .* not the file"):
            ra.import_map()
    finally:
        ra._import_map.cache_clear()


@pytest.mark.parametrize("name", ["rigs.toml\x00", "a" * 300 + ".toml", 5, ""])
def test_hostile_companion_names_are_refused_naming_the_field(tmp_path, name):
    design = _bare_design(tmp_path)
    with pytest.raises(DesignErrors) as err:
        tactcad.load(design, set={"files.rigs": name})
    assert [e.field for e in err.value.errors] == ["files.rigs"]


#: Characters that print nothing, or something else than themselves, in a file name:
#: zero-width space, right-to-left override, byte order mark, no-break space, unassigned.
INVISIBLE = ("\u200b", "\u202e", "\ufeff", "\u00a0", "\uffff")


def _export_refused(design: Path, out: Path, capsys) -> str:
    """stderr of an export of ``design`` into ``out`` that must be refused (exit 2, nothing written)."""
    code = main(["export", "--design", str(design), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert not out.exists()
    assert "Traceback" not in err
    return err


@pytest.mark.parametrize("kind", ["rigs", "scenes"])
@pytest.mark.parametrize("char", INVISIBLE)
def test_a_companion_name_with_a_character_that_does_not_print_is_refused(tmp_path, capsys, kind,
                                                                            char):
    named = f"{kind}{char}.toml"
    design = _bare_design(tmp_path, lambda t: t + f'\n[files]\n{kind} = "{named}"\n')
    new_project(tmp_path / "p")  # a readable companion under that very name: not what refuses it
    shutil.copy(tmp_path / "p" / f"{kind}.toml", tmp_path / named)
    err = _export_refused(design, tmp_path / "out", capsys)
    assert f"files.{kind} = {named!r}: allowed a file name of 1 ... 500 printable characters" in err
    assert f"found U+{ord(char):04X}" in err


@pytest.mark.parametrize("kind", ["rigs", "scenes"])
def test_a_companion_name_that_is_a_symbolic_link_loop_is_refused(tmp_path, capsys, kind):
    (tmp_path / "a.toml").symlink_to("b.toml")
    (tmp_path / "b.toml").symlink_to("a.toml")
    design = _bare_design(tmp_path, lambda t: t + f'\n[files]\n{kind} = "a.toml"\n')
    err = _export_refused(design, tmp_path / "out", capsys)
    assert f"files.{kind} = 'a.toml': allowed an existing {kind} file" in err
    assert "a.toml is a symbolic link loop" in err


def test_a_default_companion_that_is_a_symbolic_link_loop_is_refused_not_made_anew(tmp_path,
                                                                                   capsys):
    design = _bare_design(tmp_path)
    (tmp_path / "rigs.toml").symlink_to("rigs.toml")
    err = _export_refused(design, tmp_path / "out", capsys)
    assert "files.rigs = 'rigs.toml': allowed a rigs file, or none, beside bare.toml" in err


def _folders_the_docs_write() -> set[str]:
    """The output folders the documentation's examples write in a project: each
    ``--out NAME`` (not of ``tactcad design``, whose ``--out`` is a new design
    file or project, nor a design file or placeholder) and the Python
    example's ``project.export("NAME", ...)``."""
    from doc_pages import pages

    text = "\n".join(p.read_text(encoding="utf-8") for p in pages()).replace("\\\n", " ")
    lines = [line for line in text.splitlines() if not re.search(r"\btactcad design\b", line)]
    named = [n for line in lines for n in re.findall(r"--out ([A-Za-z0-9_.-]+)", line)]
    named += re.findall(r'\.export\("([^"]+)"', text)
    return {n for n in named if not n.endswith(".toml") and n != "DIR"}


def test_the_projects_gitignore_keeps_every_folder_the_docs_write_out_of_git(tmp_path):
    import subprocess

    folders = _folders_the_docs_write()
    assert {"exports", "exports-web0p2", "diff"} <= folders  # the Python example's among them
    made = new_project(tmp_path / "p")
    subprocess.run(["git", "init", "-q", str(made.folder)], check=True)
    for name in sorted(folders):
        (made.folder / name).mkdir()
        (made.folder / name / "manifest.json").write_text("{}", encoding="utf-8")
    ignored = subprocess.run(["git", "-C", str(made.folder), "check-ignore", *sorted(folders)],
                             capture_output=True, text=True).stdout.split()
    assert sorted(ignored) == sorted(folders)
    assert subprocess.run(["git", "-C", str(made.folder), "check-ignore", "-q",
                           made.design.name]).returncode == 1  # the design itself is kept


def test_the_next_step_new_prints_can_be_pasted_for_a_folder_with_a_space(tmp_path, capsys):
    import shlex

    (tmp_path / "my work").mkdir()  # the space in a folder above it: its own name is a design's
    assert main(["new", str(tmp_path / "my work" / "proj")]) == 0
    line = [x for x in capsys.readouterr().out.splitlines() if x.startswith("next: ")][0]
    words = shlex.split(line.removeprefix("next: "))
    assert words[:2] == ["cd", str(tmp_path / "my work" / "proj")] and words[2] == "&&"


def test_new_names_the_design_for_its_project_folder(tmp_path):
    # `new palp-strip` writes palp_strip.toml named palp_strip, not the example's name
    made = new_project(tmp_path / "palp-strip", example="ti_array_2x3")
    assert made.design.name == "palp_strip.toml" and "ti_array_2x3.toml" not in made.files
    assert tomllib.loads(made.design.read_text(encoding="utf-8"))["design"]["name"] == "palp_strip"
    text = made.design.read_text(encoding="utf-8")
    assert text.startswith("# Written by")  # the file's comments kept
    assert (made.folder / "README.md").read_text(encoding="utf-8").startswith("# palp_strip")
    assert tactcad.load(made.design).plan.name == "palp_strip"


@pytest.mark.parametrize("folder, paste", [("my sensor", "my_sensor"),
                                           ("ünï cødé", "uni_code")])
def test_a_folder_whose_name_is_no_design_name_is_refused_with_one_to_paste(
        tmp_path, folder, paste):
    from tactcad.vocabulary.schema import NAME_ALLOWED

    proc = run_cli("new", folder, cwd=tmp_path)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert proc.stderr.startswith(f"tactcad: error: DIR = {folder!r}: allowed {NAME_ALLOWED}")
    assert f"e.g. {paste} " in proc.stderr
    assert list(tmp_path.iterdir()) == []  # no project with the example's name
    assert new_project(tmp_path / paste, example="ti_array_2x3").design.name == f"{paste}.toml"


def test_a_new_projects_bought_parts_are_its_own_boms(tmp_path):
    # the Ti design's M2 x 20 clamp bolts and its rigs' force gauge, never the paper's
    # array's M2 x 30 bolts or its FH 5; a comb's M1.2 screws and dowel pins
    made = new_project(tmp_path / "ti", from_design=_bare_design(tmp_path))
    text = (made.folder / "purchased-parts.md").read_text(encoding="utf-8")
    bom = tactcad.load(made.design)
    from tactcad.assembly.inventory import design_assemblies
    from tactcad.export.bom import complete_kit

    bought = [r.part for r in complete_kit(bom, design_assemblies(bom)) if r.kind != "fabricated"]
    assert bought and all(f"| {part} |" in text for part in bought)
    assert "bolt_M2x20" in text and "bolt_M2x30" not in text and "FH 5" not in text
    assert "purchased-parts.md" in made.files and made.files[-1] == "ti.toml"
    comb = (EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml").read_text(encoding="utf-8")
    design = tmp_path / "comb.toml"
    design.write_text(re.sub(r"\[files\]\nscenes = .*\n", "", comb), encoding="utf-8")
    text = (new_project(tmp_path / "c", from_design=design).folder
            / "purchased-parts.md").read_text(encoding="utf-8")
    assert "M1.2" in text and "bolt_M2" not in text


@pytest.mark.parametrize("fails_at", ["README.md", ".github/workflows/hardware.yml"])
@pytest.mark.parametrize("again", [False, True])
def test_a_write_into_an_existing_folder_that_fails_part_way_leaves_the_folder_as_it_was(
        tmp_path, monkeypatch, fails_at, again):
    import os

    import tactcad.project_folder as pf

    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    (repo / "notes.txt").write_text("the lab's own\n", encoding="utf-8")
    if again:  # --force over a project: every file it held comes back
        new_project(repo, example="macro_array")
    before = {p.relative_to(repo).as_posix(): p.read_bytes()
              for p in sorted(repo.rglob("*")) if p.is_file()}
    dirs_before = sorted(p.relative_to(repo).as_posix() for p in repo.rglob("*") if p.is_dir())
    real_replace = os.replace
    failed = []

    def replace(src, dst):  # the new file refused once (the old one may go back)
        if Path(dst) == repo / fails_at and not failed:
            failed.append(dst)
            raise PermissionError(13, "Permission denied", str(dst))
        return real_replace(src, dst)

    monkeypatch.setattr(pf.os, "replace", replace)
    with pytest.raises(PermissionError, match=re.escape(fails_at.split("/")[-1])):
        new_project(repo, force=again)
    after = {p.relative_to(repo).as_posix(): p.read_bytes()
             for p in sorted(repo.rglob("*")) if p.is_file()}
    assert after == before
    assert sorted(p.relative_to(repo).as_posix() for p in repo.rglob("*") if p.is_dir()) \
        == dirs_before
    assert not list(tmp_path.glob(".repo.staging-*"))


def test_new_from_the_die_example_makes_a_die_project_named_for_its_folder(tmp_path):
    from tactcad.products.silicon_die.design.die_file import load_die_design

    made = new_project(tmp_path / "my-die", example="grasper_jaw_5mm_mems")
    # the CI workflow too, as an array's project has (export, check, diff)
    assert sorted(made.files) == [".github/workflows/hardware.yml", ".gitignore", "README.md",
                                  "my_die.toml"]
    workflow = (made.folder / ".github/workflows/hardware.yml").read_text(encoding="utf-8")
    assert "DESIGN: my_die.toml" in workflow
    assert made.design == tmp_path / "my-die" / "my_die.toml"
    assert load_die_design(made.design).die.name == "my_die"
    assert default_design(made.folder) == made.design  # every command takes it
    readme = (made.folder / "README.md").read_text(encoding="utf-8")
    assert "my_die.toml" in readme and "$" not in readme.replace("```sh", "")
    assert not any(s in readme for s in PAPER_SAMPLES)


def test_new_from_a_die_design_file_keeps_its_labs_jaw_file_beside_it(tmp_path):
    from tactcad.products.silicon_die.design.die_file import load_die_design

    source = tmp_path / "src"
    source.mkdir()
    text = (EXAMPLES / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml").read_text(
        encoding="utf-8").replace('jaw = "5"', 'jaw = "lab_jaw.toml"')
    (source / "die.toml").write_text(text, encoding="utf-8")
    (source / "lab_jaw.toml").write_text("[grasper_jaw]\njaw_length_mm = 20.0\n",
                                         encoding="utf-8")
    made = new_project(tmp_path / "insert", from_design=source / "die.toml")
    assert (made.folder / "lab_jaw.toml").read_text(encoding="utf-8") == \
        (source / "lab_jaw.toml").read_text(encoding="utf-8")
    assert load_die_design(made.design).jaw == str((made.folder / "lab_jaw.toml").resolve())


def _files_in(folder: Path) -> list[str]:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())


def test_force_over_another_products_project_leaves_only_the_new_projects_and_the_users_files(
        tmp_path):
    folder = tmp_path / "mix"
    new_project(folder, example="ti_array_2x3")  # rigs, scenes, bought parts: the array's
    (folder / "notes.md").write_text("the lab's own\n", encoding="utf-8")
    made = new_project(folder, example="grasper_jaw_5mm_mems", force=True)
    assert _files_in(folder) == sorted([*made.files, "notes.md"])
    assert sorted(made.removed) == ["purchased-parts.md", "rigs.toml", "scenes.toml"]


def test_force_over_a_die_project_removes_the_jaw_file_its_design_named(tmp_path):
    source = tmp_path / "src"
    source.mkdir()
    text = (EXAMPLES / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml").read_text(
        encoding="utf-8").replace('jaw = "5"', 'jaw = "lab_jaw.toml"')
    (source / "die.toml").write_text(text, encoding="utf-8")
    (source / "lab_jaw.toml").write_text("[grasper_jaw]\njaw_length_mm = 20.0\n",
                                         encoding="utf-8")
    folder = tmp_path / "insert"
    new_project(folder, from_design=source / "die.toml")
    assert (folder / "lab_jaw.toml").is_file()
    made = new_project(folder, example="grasper_jaw_10mm", force=True)
    assert "lab_jaw.toml" in made.removed and _files_in(folder) == sorted(made.files)


@pytest.mark.parametrize("kind", ["array", "die"])
def test_a_command_run_among_an_exports_files_names_the_design_not_the_shipped_example(
        tmp_path, kind):
    """An export folder holds a record naming its design file, no design: a command run
    there must not quietly take the paper's array (the shipped example)."""
    project = tmp_path / "lab"
    project.mkdir()
    exports = project / "exports"
    exports.mkdir()
    record = ({"design": {"name": "lab", "source": "lab.toml", "sha256": "0"}, "files": {}}
              if kind == "array" else {"design": {"name": "lab", "source": "lab.toml"},
                                       "die": {}, "files": {}})
    (exports / ("manifest.json" if kind == "array" else "lab.json")).write_text(
        json.dumps(record), encoding="utf-8")
    with pytest.raises(DesignError) as caught:
        default_design(exports)
    assert caught.value.field == "--design" and "--design PATH/lab.toml" in caught.value.allowed
    (project / "lab.toml").write_text("", encoding="utf-8")  # the design beside: pasteable
    with pytest.raises(DesignError) as caught:
        default_design(exports)
    assert caught.value.alternatives[0]["option"] == "--design ../lab.toml"
    # a folder holding other JSON is still a folder without a design
    (exports / "manifest.json").unlink(missing_ok=True)
    (exports / "lab.json").unlink(missing_ok=True)
    (exports / "notes.json").write_text('{"files": 3}', encoding="utf-8")
    assert default_design(exports) == DEFAULT_DESIGN


def test_a_command_deep_in_an_exports_folder_names_the_design_by_its_relative_path(tmp_path):
    project = tmp_path / "lab"
    (project / "exports" / "step").mkdir(parents=True)
    (project / "lab.toml").write_text("", encoding="utf-8")
    (project / "exports" / "manifest.json").write_text(json.dumps(
        {"design": {"name": "lab", "source": "lab.toml"}, "files": {}}), encoding="utf-8")
    with pytest.raises(DesignError) as caught:
        default_design(project / "exports" / "step")
    assert caught.value.alternatives[0]["option"] == "--design ../../lab.toml"
    assert "lies inside it" in caught.value.why


def test_a_new_project_is_not_written_beside_another_design_file(tmp_path):
    folder = tmp_path / "twod"
    folder.mkdir()
    shutil.copy(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml", folder / "old.toml")
    with pytest.raises(DesignError, match="old.toml"):
        new_project(folder)
    assert sorted(p.name for p in folder.iterdir()) == ["old.toml"]
    made = new_project(tmp_path / "x.toml")  # a folder named like a file: no x.toml.toml
    assert made.design.name == "x.toml"


def test_new_from_a_file_that_is_no_design_is_refused_as_such(tmp_path):
    # a project's rigs.toml gave 112 errors, one for each design table it lacks
    rigs = EXAMPLES / "ti_array_2x3" / "rigs.toml"
    with pytest.raises(DesignError, match="--from-design.*a design file.*no \\[design\\] table"):
        new_project(tmp_path / "x", from_design=rigs)
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("example", sorted(set(examples()) - {"macro_array"}))
def test_a_new_project_from_another_example_names_not_the_papers_design(tmp_path, example):
    # ti_array_2x3 carried 13 reasons "Kept from the base design macro_array, ..." into
    # every project made from it
    made = new_project(tmp_path / "gripsense", example=example)
    for name in made.files:
        text = (made.folder / name).read_text(encoding="utf-8").lower()
        assert "macro_array" not in text and "macro array" not in text, name


def _edited(design: Path, columns: int, arms: list[float], grade: str) -> None:
    """The design file with its grid, arm lengths and grade changed, as a lab edits it."""
    text = design.read_text(encoding="utf-8")
    text = re.sub(r"^columns = \d+", f"columns = {columns}", text, flags=re.MULTILINE)
    text = re.sub(r"^lengths_mm = \[[^\]]*\]", f"lengths_mm = {arms}", text, flags=re.MULTILINE)
    text = re.sub(r'^grade = "[^"]*"', f'grade = "{grade}"', text, flags=re.MULTILINE)
    design.write_text(text, encoding="utf-8")


def test_a_new_projects_scene_texts_follow_its_edited_design(tmp_path):
    # the example's scenes said "the six elements and four spacers" and "The 2 x 3
    # array" after the lab's design had grown to 2 x 4
    from tactcad.assembly.rig_models import describe

    made = new_project(tmp_path / "myarray")
    _edited(made.design, 4, [15.0, 7.0, 15.0, 15.0, 15.0, 7.0, 15.0, 15.0], "17-4PH-H900")
    project = tactcad.load(made.design).validated
    plan = project.plan
    assert (plan.rows, plan.columns, len(plan.slots)) == (2, 4, 8)
    described = {n: s.description for n, s in project.scenes.items()}
    assert (f"the {len(plan.slots)} elements and {len(plan.spacer_placements)} spacers"
            in described["wirecut"])
    assert described["array"].startswith(f"The {plan.rows} x {plan.columns} array")
    gauge = project.rigs.part("force_gauge").model
    assert f"force gauge {gauge} with the" in described["calibration-rig"]
    lines = "\n".join(describe(project))
    assert "six" not in lines and "2 x 3 array" not in lines and "$" not in lines


def test_a_new_projects_rigs_name_the_project_not_the_example(tmp_path):
    made = new_project(tmp_path / "myarray")
    text = (made.folder / "rigs.toml").read_text(encoding="utf-8")
    rigs = tomllib.loads(text)["rigs"]
    assert rigs["name"] == "myarray_rigs" and rigs["description"].endswith("rigs of myarray")
    assert "example_rigs" not in text and "titanium example array" not in text
    assert text.startswith("# Test rigs of myarray")
    assert tactcad.load(made.design).validated.rigs.name == "myarray_rigs"


def test_a_scene_description_with_an_unknown_word_is_refused_naming_it(tmp_path):
    made = new_project(tmp_path / "p")
    scenes = made.folder / "scenes.toml"
    text = scenes.read_text(encoding="utf-8")
    scenes.write_text(text.replace("the $n_elements elements", "the $n_elemnts elements"),
                      encoding="utf-8")
    with pytest.raises(DesignErrors) as caught:
        tactcad.load(made.design).validated
    assert "scene.wirecut.description" in str(caught.value) and "$n_elemnts" in str(caught.value)
    assert "$n_elements" in str(caught.value)


def _wider_design_beside_the_examples_rigs(folder: Path) -> Path:
    """A design of K_obj 0.5 ... 5 N/mm at 0.122 N without a [files] table, beside the
    Ti example's rigs and scenes (sized for 1 ... 5 N/mm at 0.1 N), as `tactcad design
    --out mine.toml` leaves it in a project made by `tactcad new`."""
    for name in ("rigs.toml", "scenes.toml"):
        shutil.copy(EXAMPLES / "ti_array_2x3" / name, folder / name)
    return _bare_design(folder, lambda t: re.sub(
        r"kobj_range_N_per_mm = \[[^\]]*\]", "kobj_range_N_per_mm = [0.5, 5.0]",
        t.replace("full_scale_force_N = 0.1\n", "full_scale_force_N = 0.122\n")))


def test_new_from_a_design_whose_rigs_beside_it_do_not_fit_makes_rigs_sized_for_it(tmp_path):
    from tactcad.checks.rig_checks import rig_checks

    design = _wider_design_beside_the_examples_rigs(tmp_path)
    made = new_project(tmp_path / "p3", from_design=design)
    project = tactcad.load(made.design).validated
    assert project.rigs.sample_stiffness_N_per_mm == (5.0, 1.58, 0.5)
    results = rig_checks(project.plan, project.rigs)
    assert all(r.passed for r in results), [r.line() for r in results]
    [note] = made.notes
    assert "rig force gauge, rig sample kit fail" in note and "made for it" in note


def test_new_from_a_design_whose_rigs_beside_it_fit_copies_them(tmp_path):
    for name in ("rigs.toml", "scenes.toml"):
        shutil.copy(EXAMPLES / "ti_array_2x3" / name, tmp_path / name)
    (tmp_path / "rigs.toml").write_text((tmp_path / "rigs.toml").read_text(encoding="utf-8")
                                        .replace("height_mm = 10.0", "height_mm = 12.0", 1),
                                        encoding="utf-8")  # a lab's own edit, to be kept
    made = new_project(tmp_path / "p", from_design=_bare_design(tmp_path))
    assert made.notes == ()
    assert "height_mm = 12.0" in (made.folder / "rigs.toml").read_text(encoding="utf-8")


def test_design_into_a_folder_whose_rigs_do_not_fit_warns_with_a_command_that_works(
        tmp_path, capsys):
    import shlex

    from tactcad.commands.design import rigs_beside, rigs_misfit_line
    from tactcad.vocabulary.schema import read_toml

    design = _wider_design_beside_the_examples_rigs(tmp_path)
    data = read_toml(design, "design file")
    rigs = rigs_beside(data, tmp_path / "mine.toml", str(tmp_path / "mine.toml"))
    assert rigs["fits"] is False and rigs["fail"] == ["rig force gauge", "rig sample kit"]
    line = rigs_misfit_line(rigs)
    assert line.startswith("warning: rigs: ") and "tactcad new " in line
    (tmp_path / "mine.toml").write_text(design.read_text(encoding="utf-8"), encoding="utf-8")
    design.unlink()
    assert main(shlex.split(rigs["next"])[1:]) == 0  # pasted as printed
    assert "note: the rigs rigs.toml of mine.toml do not fit it" in capsys.readouterr().out
    fitting = tmp_path / "fits"
    fitting.mkdir()
    for name in ("rigs.toml", "scenes.toml"):
        shutil.copy(EXAMPLES / "ti_array_2x3" / name, fitting / name)
    assert rigs_beside(read_toml(_bare_design(fitting), "design file"), fitting / "b.toml",
                       "b.toml")["fits"] is True


@pytest.mark.parametrize("where", [["--verify", "none"], ["--jaw", "10"]], ids=["stacked", "jaw"])
def test_designing_into_a_folder_lists_the_scenes_force_would_replace(tmp_path, where):
    """A lab's edited scenes.toml went under --force although the refusal without it had
    not named it: the refusal, made before the search, names every file --force replaces."""

    folder = tmp_path / "lab_array"
    folder.mkdir()
    (folder / "scenes.toml").write_text("# MY EDIT\n", encoding="utf-8")
    (folder / "README.md").write_text("# our array\n", encoding="utf-8")
    done = run_cli("design", "--kr-over-km", "3", "--kobj-range", "5", "20",
                   "--full-scale-force", "0.3", *where, "--out", folder)
    assert done.returncode == 2, done.stderr
    assert "--out" in done.stderr and "README.md, scenes.toml already" in done.stderr
    assert (folder / "scenes.toml").read_text(encoding="utf-8") == "# MY EDIT\n"
    assert sorted(p.name for p in folder.iterdir()) == ["README.md", "scenes.toml"]
