"""Every code block of the documentation runs, or says why not (docs/about.md).

Each page runs in a fresh, empty folder (a page marked ``% runs: in a checkout
(REASON)`` with a copy of the checkout's ``hardware/``); its blocks run in order
and share that folder (a tutorial's
``cd fingertip`` holds for its next block). ``tactcad`` lines run in this
process (:func:`conftest.run_cli`), so a page costs its commands, not an
interpreter start each; a slow page's exports start from the run's store of the
example's export jobs.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from conftest import EXAMPLE_DESIGN, _filled_store, run_cli, warm_store_copy
from doc_pages import DOCS, ROOT, RUNNABLE, Block, blocks, in_checkout, is_slow, pages

#: Commands whose exit 1 is an answer, not a failure: ``diff`` found a change, ``verify``
#: found a requirement not met (a page may show a design that fails one).
EXIT_ONE_IS_AN_ANSWER = {"diff", "verify"}
#: A command line of a ``text`` block would be a command that never runs.
COMMAND_LINE = re.compile(r"^\s*(\$ |\.?/?tactcad |make )", re.M)


def _page_param(page: Path):
    marks = [pytest.mark.slow] if is_slow(page) else []
    return pytest.param(page, id=page.relative_to(DOCS).as_posix(), marks=marks)


PAGES = [p for p in pages() if any(not b.not_run and b.language in RUNNABLE for b in blocks(p))]


# --- the conventions ----------------------------------------------------------------------------
def test_every_block_runs_or_says_why_not():
    found = [b for p in pages() for b in blocks(p)]
    assert len(found) > 40  # the pages were read
    wrong = [f"{b.where()}: ```{b.language}" for b in found
             if not b.not_run and b.language not in (*RUNNABLE, "text")]
    assert not wrong, ("blocks that neither run (sh, console, python, toml) nor start with "
                       "'# not run: REASON':\n" + "\n".join(wrong))
    commands = [b.where() for b in found if b.language == "text" and COMMAND_LINE.search(b.code)]
    assert not commands, "text blocks holding commands (make them sh or console):\n" + \
        "\n".join(commands)


def test_the_runner_refuses_what_it_cannot_run(tmp_path):
    block = Block("x.md", 1, "sh", "rm -rf hardware\n")
    with pytest.raises(AssertionError, match="not run: REASON"):
        run_sh(block, tmp_path)
    with pytest.raises(AssertionError, match="exit 2"):
        run_sh(Block("x.md", 1, "sh", "tactcad stiffness --element 99\n"), tmp_path)


def test_a_toml_block_marked_with_a_file_name_is_saved_for_the_next_commands(tmp_path):
    saved = Block("x.md", 1, "toml", "# file: our_jaw.toml\n[grasper_jaw]\nshaft_class_mm = '10'\n")
    run_toml(saved, tmp_path)
    assert tomllib.loads((tmp_path / "our_jaw.toml").read_text())["grasper_jaw"] == {
        "shaft_class_mm": "10"}
    run_toml(Block("x.md", 1, "toml", "[grasper_jaw]\n"), tmp_path / "nowhere")  # only read
    with pytest.raises(AssertionError, match="x.md:1"):
        run_toml(Block("x.md", 1, "toml", "# file: bad.toml\n[grasper_jaw\n"), tmp_path)
    assert not (tmp_path / "bad.toml").exists()


def test_an_excerpt_is_checked_line_by_line_against_the_output():
    printed = "targets: K_r 17.25\n  check requirements: 8 passed, 0 failed\n  not searched: a (b)\n"
    assert shown_but_not_printed(["targets:  K_r 17.25", "...", "  not searched: a (...)"],
                                 printed) == []
    assert shown_but_not_printed(["  check requirements: 7 passed, 0 failed"], printed) == [
        "check requirements: 7 passed, 0 failed"]


def test_a_marked_slow_page_says_why():
    for page in pages():
        for marked in re.findall(r"^% runs:.*$", page.read_text(encoding="utf-8"), re.M):
            assert re.fullmatch(r"% runs: (slow|in a checkout) \(.+\)", marked), (
                f"{page}: write '% runs: slow (REASON)' or '% runs: in a checkout (REASON)'")


def test_a_page_that_says_it_runs_in_an_empty_folder_is_run_in_one():
    # the die tutorial said so, but ran beside a copy of hardware/ and read from it
    for page in pages():
        text = " ".join(page.read_text(encoding="utf-8").split())
        if "in an empty folder" in text:
            assert not in_checkout(page), page


# --- running a page -----------------------------------------------------------------------------
def commands_of(code: str) -> list[list[str]]:
    """The commands of a shell block: continuation lines joined, comments dropped,
    ``a && b`` as two commands."""
    out: list[list[str]] = []
    for line in code.replace("\\\n", " ").splitlines():
        words = shlex.split(line, comments=True)
        while words:
            cut = words.index("&&") if "&&" in words else len(words)
            if words[:cut]:
                out.append(words[:cut])
            words = words[cut + 1:]
    return out


def run_tactcad(words: list[str], cwd: Path, where: str,
                expect: int | None = None) -> subprocess.CompletedProcess:
    """Run one ``tactcad`` command of a block in ``cwd``; its exit code checked."""
    try:
        result = run_cli(*words[1:], cwd=cwd)
    except SystemExit as exc:  # argparse's own --version and --help end the program
        result = subprocess.CompletedProcess(words, exc.code or 0, "", "")
    allowed = {expect} if expect is not None else (
        {0, 1} if words[1:2] and words[1] in EXIT_ONE_IS_AN_ANSWER else {0})
    assert result.returncode in allowed, (
        f"{where}: {shlex.join(words)}: exit {result.returncode}\n{result.stderr[-2000:]}")
    return result


#: Pages whose ``console`` blocks are checked against what their commands print now:
#: every line shown under a ``$`` line is a line of its output (``...`` alone stands for
#: lines left out, a line ending ``(...)`` for the rest of a line).
EXCERPTS_CHECKED = {"how-to/design-array.md", "tutorials/mems-die.md", "reference/design-file.md"}


def shown_but_not_printed(shown: list[str], printed: str) -> list[str]:
    """The lines of ``shown`` (a block's excerpt of one command) that ``printed`` (its
    stdout and stderr) has not, spaces collapsed."""
    flat = lambda line: " ".join(line.split())  # noqa: E731
    lines = [flat(line) for line in printed.splitlines()]
    missing = []
    for line in map(flat, shown):
        if line in ("", "..."):
            continue
        head, cut, _ = line.partition("(...)")
        if not any(out.startswith(head) if cut else out == line for out in lines):
            missing.append(line)
    return missing


def run_command(words: list[str], cwd: Path, where: str, expect: int | None = None) -> Path:
    """Run one command of a block in ``cwd``; the folder the next one runs in."""
    if words[0] == "cd":
        target = (cwd / words[1]).resolve()
        assert target.is_dir(), f"{where}: cd {words[1]}: no such folder"
        return target
    if words[0] == "ls":
        missing = [w for w in words[1:] if not w.startswith("-") and not (cwd / w).exists()]
        assert not missing, f"{where}: ls: {missing} not there"
        return cwd
    if words[0] in ("tactcad", "./tactcad"):
        run_tactcad(words, cwd, where, expect)
        return cwd
    raise AssertionError(f"{where}: {shlex.join(words)}: the runner runs tactcad, cd and ls "
                         "only; mark the block '# not run: REASON'")


def run_sh(block: Block, cwd: Path) -> Path:
    for words in commands_of(block.code):
        cwd = run_command(words, cwd, block.where())
    return cwd


def run_console(block: Block, cwd: Path) -> Path:
    """``$ `` lines run; a block that shows ``tactcad: error:`` must exit 2. On a page of
    :data:`EXCERPTS_CHECKED`, the lines shown under a command are lines it prints."""
    expect = 2 if "tactcad: error:" in block.code else None
    lines = block.code.splitlines()
    for k, line in enumerate(lines):
        if not line.startswith("$ "):
            continue
        commands = commands_of(line[2:])
        if block.page in EXCERPTS_CHECKED and len(commands) == 1 and commands[0][0] == "tactcad":
            result = run_tactcad(commands[0], cwd, block.where(), expect)
            after = lines[k + 1:]
            shown = after[:next((j for j, s in enumerate(after) if s.startswith("$ ")), None)]
            missing = shown_but_not_printed(shown, result.stdout + result.stderr)
            assert not missing, f"{block.where()}: shown, not printed now:\n" + "\n".join(missing)
            continue
        for words in commands:
            cwd = run_command(words, cwd, block.where(), expect)
    return cwd


def run_python(block: Block, cwd: Path) -> Path:
    script = cwd / f"_docs_block_{block.line}.py"
    script.write_text(block.code, encoding="utf-8")
    out = subprocess.run([sys.executable, str(script)], cwd=cwd, capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "src"),
                              "OMP_NUM_THREADS": "1"})
    assert out.returncode == 0 and out.stderr == "", f"{block.where()}:\n{out.stderr[-3000:]}"
    return cwd


def run_toml(block: Block, cwd: Path) -> Path:
    try:
        tomllib.loads(block.code)
    except tomllib.TOMLDecodeError as exc:
        raise AssertionError(f"{block.where()}: {exc}") from None
    if block.saved_as:
        (cwd / block.saved_as).write_text(block.code, encoding="utf-8")
    return cwd


RUNNERS = {"sh": run_sh, "console": run_console, "python": run_python, "toml": run_toml}


@pytest.mark.parametrize("page", [_page_param(p) for p in PAGES])
def test_page_code_runs(page, tmp_path, tmp_path_factory, monkeypatch):
    exports = any("tactcad export" in b.code for b in blocks(page) if not b.not_run)
    if is_slow(page) and exports:
        # a tutorial's export of the example starts from the run's store of its jobs
        # (filled once per run by one cold export), as a lab's second export would
        import tactcad.store

        store = _filled_store(tmp_path_factory, "example-design", EXAMPLE_DESIGN)
        monkeypatch.setattr(tactcad.store, "DEFAULT_STORE",
                            warm_store_copy(store, tmp_path / "store"))
    work = tmp_path / "work"
    work.mkdir()
    if in_checkout(page):  # else the page runs as a reader who installed tactcad meets it
        shutil.copytree(ROOT / "hardware", work / "hardware")
    cwd = work
    for block in blocks(page):
        if block.not_run or block.language not in RUNNERS:
            continue
        cwd = RUNNERS[block.language](block, cwd)
