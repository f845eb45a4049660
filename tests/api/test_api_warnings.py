"""What the Python API does with the warnings its work issues: a record takes them in its
``warnings``, as the command's ``--json`` does; a result with no place for them has each
said once, as a warning of the caller's line; none reaches the console with tactcad's own
file and source line."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

import tactcad
from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning

ROOT = Path(__file__).resolve().parents[2]
#: A thin web under the example's 3 mm sheet: sheet / web 55, beyond the gauge-strain fit.
THIN_WEB = {"element.web_thickness_mm": 0.055}


@pytest.fixture(scope="module")
def thin_web():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # what loading says is the test's below
        return tactcad.load(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml",
                            set=THIN_WEB)


def caught(call):
    """``call()``'s result and every warning it let through."""
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        result = call()
    return result, said


def test_loading_a_design_beyond_a_fit_lets_no_warning_through():
    _, said = caught(lambda: tactcad.load(ROOT / "hardware" / "ti_array_2x3" /
                                          "ti_array_2x3.toml", set=THIN_WEB))
    assert [str(w.message) for w in said] == []


def test_a_records_warnings_hold_what_its_work_warned_and_nothing_reaches_the_console(thin_web):
    record, said = caught(thin_web.readout)
    assert [str(w.message) for w in said] == []
    gauge = [w for w in record["warnings"] if w.startswith("gauge strain of")]
    assert len(gauge) == 1 and "the sheet over the web thickness, b/t" in gauge[0], \
        record["warnings"]
    assert "estimated error" in gauge[0]


def test_alike_warnings_of_one_call_fold_into_one_line_with_their_largest_error(thin_web):
    record, said = caught(thin_web.budget)
    assert [str(w.message) for w in said] == []
    lines = record["warnings"]
    assert len(lines) == len(set(lines))
    firsts = [w for w in lines if w.startswith("gauge strain of")]
    folds = [w for w in lines if w.startswith(GaugeStrainRangeWarning.fold_as)]
    assert len(firsts) == 1 and len(folds) <= 1, lines
    if folds:
        assert "more alike, estimated error up to" in folds[0] \
            and not folds[0].endswith("up to 0.0 %")


def test_a_result_without_warnings_says_each_once_from_the_callers_line(thin_web):
    result, said = caught(lambda: thin_web.element(1).stiffness())
    assert result.stiffness_N_per_mm > 0
    texts = [str(w.message) for w in said]
    assert len(texts) == len(set(texts)) >= 1
    assert all(w.filename == __file__ for w in said), [w.filename for w in said]
    assert any(issubclass(w.category, GaugeStrainRangeWarning) for w in said)


def test_a_dataclass_result_takes_the_warnings_in_its_own_field():
    from tactcad.api import Verification, with_warnings

    found = Verification("auto", (), (), {}, ("said before",))
    joined, left = with_warnings(found, ["said before", "gauge strain: b/t 55"])
    assert joined.warnings == ("said before", "gauge strain: b/t 55") and left == []
    plain_record, left = with_warnings({"k": 1}, ["x"])
    assert plain_record == {"k": 1, "warnings": ["x"]} and left == []
    assert with_warnings(3.0, ["x"]) == (3.0, ["x"])


def test_a_refusal_after_warnings_says_them_first_from_the_callers_line():
    """As a command prints the warnings issued before its refusal: an API call that warned
    and then refused says each warning once, at the caller's line, and raises the refusal
    by its keyword."""
    from tactcad.api import keyword_errors
    from tactcad.errors import DesignError

    @keyword_errors
    def judged(force_N: float = 1.0) -> dict:
        warnings.warn(GaugeStrainRangeWarning("beyond the fit: error 2.7 %"))
        warnings.warn(GaugeStrainRangeWarning("beyond the fit: error 2.7 %"))
        raise DesignError("--force-N", force_N, "0 < value <= 10 (N)")

    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        with pytest.raises(DesignError) as refused:
            judged(force_N=50.0)
    assert refused.value.field == "force_N"
    assert [str(w.message) for w in said] == ["beyond the fit: error 2.7 %"]
    assert said[0].filename == __file__


@pytest.mark.parametrize("method, command", [("tolerance", "tolerance"),
                                             ("strength", "strength"),
                                             ("crosstalk", "crosstalk")])
def test_every_call_warns_alike_and_as_the_commands_json(method, command, capsys):
    """A result kept in the process from an earlier call (the design's requirements, its
    grid strain) says the warnings its computation said, each call."""
    import json

    from tactcad.cli import main

    design = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
    first = getattr(tactcad.load(design, set=THIN_WEB), method)()["warnings"]
    again = getattr(tactcad.load(design, set=THIN_WEB), method)()["warnings"]
    assert first == again and first, (first, again)
    capsys.readouterr()
    try:
        main([command, "--design", str(design), "--set",
              f"element.web_thickness_mm={THIN_WEB['element.web_thickness_mm']}", "--json"])
    except SystemExit:
        pass
    assert json.loads(capsys.readouterr().out)["warnings"] == first


def test_a_result_kept_per_process_warns_again_on_every_call():
    from tactcad.store import kept_per_process

    runs = []

    @kept_per_process(maxsize=4)
    def warned(x):
        runs.append(x)
        warnings.warn(f"said of {x}")
        return 2 * x

    for _ in range(2):
        value, said = caught(lambda: warned(3))
        assert value == 6 and [str(w.message) for w in said] == ["said of 3"]
    assert runs == [3]


@pytest.mark.parametrize("method, command", [("readout", "readout"), ("budget", "budget"),
                                             ("crosstalk", "crosstalk"),
                                             ("strength", "strength"), ("modes", "modal")])
def test_a_record_is_the_json_the_command_prints_with_its_keys(method, command, capsys):
    """Plain dicts and lists (no tuple), and a ``warnings`` list even when empty, as the
    command's ``--json`` writes them."""
    import json

    from tactcad.cli import main

    design = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
    record = getattr(tactcad.load(design), method)()
    assert json.loads(json.dumps(record)) == record
    capsys.readouterr()
    try:
        main([command, "--design", str(design), "--json"])
    except SystemExit:
        pass
    printed = json.loads(capsys.readouterr().out)
    assert set(record) == set(printed) and "warnings" in record
