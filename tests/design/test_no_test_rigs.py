"""A project whose construction has no mount for the test rigs has no test
rigs: without a rigs file it loads with none (the rigs check says so and
why), a scene of a test rig is refused naming the scene's rig, and a rigs
file its [files] table names is refused naming array.construction."""

from __future__ import annotations

import shutil

import pytest

from tactcad.checks.groups import CheckContext
from tactcad.checks.rig_checks import rig_group
from tactcad.design.array_plan import EXAMPLES
from tactcad.design.project import has_test_rigs, load_project
from tactcad.errors import DesignErrors

GRASPER = EXAMPLES / "grasper_jaw_10mm"


def _copy(tmp_path):
    shutil.copytree(GRASPER, tmp_path / "p")
    return tmp_path / "p" / "grasper_jaw_10mm.toml"


def test_the_comb_project_loads_without_test_rigs_and_the_rigs_check_says_why(tmp_path):
    project = load_project(_copy(tmp_path))
    assert not has_test_rigs(project) and project.hashes["rigs"] == ""
    found = [r for _, results in rig_group(CheckContext(project.plan, tmp_path, None, project,
                                                        None)) for r in results]
    assert len(found) == 1 and found[0].passed
    assert "monolithic-comb has no mount" in found[0].detail


def test_a_test_rig_scene_without_test_rigs_is_refused_naming_its_rig(tmp_path):
    design = _copy(tmp_path)
    scenes = design.parent / "scenes.toml"
    scenes.write_text(scenes.read_text() + '\n[scene.cal]\nrig = "calibration"\n'
                      'description = "x"\ngroups = ["array"]\n')
    with pytest.raises(DesignErrors) as err:
        load_project(design)
    assert [e.field for e in err.value.errors] == ["scene.cal.rig"]
    assert "array, wirecut" in str(err.value)


def test_a_rigs_file_named_for_the_comb_is_refused_naming_the_construction(tmp_path):
    design = _copy(tmp_path)
    shutil.copy(EXAMPLES / "ti_array_2x3" / "rigs.toml", design.parent / "rigs.toml")
    # lying beside it, it is another design's of the folder: passed over
    assert not has_test_rigs(load_project(design))
    design.write_text(design.read_text(encoding="utf-8").replace(
        "[files]\n", '[files]\nrigs = "rigs.toml"\n'), encoding="utf-8")
    with pytest.raises(DesignErrors) as err:
        load_project(design)
    assert "array.construction" in [e.field for e in err.value.errors]
