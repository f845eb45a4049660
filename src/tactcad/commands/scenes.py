"""``tactcad scenes``: list the scenes of the exports, their groups and parts."""

from __future__ import annotations

import argparse

from tactcad.commands import add_design_arg, add_output_args, product_view, project_from_args
from tactcad.commands.finite_json import dumps


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("scenes", help="list the scenes (array, wire-cut layout, test rigs) and their parts",
                       description="List every scene of hardware/scenes.toml (beside the design "
                                   "file): its rig, groups and parts with quantities and level of "
                                   "detail. Builds no geometry.")
    add_design_arg(p, design_word=False)
    p.add_argument("name", nargs="?", default=None,
                   help="show only this scene; a design file (a name ending in .toml, or an "
                        "existing file) given here without --design is read as --design")
    add_output_args(p, "print a JSON list of the scenes: name, rig, description, parts placed, "
                       "groups with each part's quantity and level of detail")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.assembly.rig_models import describe, get_scene_spec, scene_summaries

    args.design, args.name = design_or_scene(args.design, args.name)
    shown = product_view("scenes", args)  # a silicon die's design: its scene in the jaw
    if shown is not None:
        return shown
    project = project_from_args(args)
    if args.name is not None:
        get_scene_spec(project, args.name)  # SceneError (exit 2) lists the scenes
    if args.json:
        print(dumps([s for s in scene_summaries(project) if args.name in (None, s["name"])]))
        return 0
    lines = describe(project)
    if args.name is not None:
        keep, show = [], False
        for line in lines:
            if not line.startswith(" "):
                show = line.split()[0] == args.name
            if show:
                keep.append(line)
        lines = keep
    for line in lines:
        print(line)
    return 0


def design_or_scene(design: str | None, name: str | None) -> tuple[str | None, str | None]:
    """The command's word read as the design where it names a design file (``tactcad scenes
    comb/comb10.toml``): a name ending in ``.toml`` or an existing file, with no
    ``--design``; else as the scene's name.

    Args:
        design: ``--design``'s value (None: not given). name: the command's word.

    Returns:
        (design, scene name): the word moved to the design, or both as given.
    """
    from pathlib import Path

    if design is not None or name is None:
        return design, name
    try:
        is_file = name.lower().endswith(".toml") or Path(name).is_file()
    except OSError:  # a name the system cannot look up: a scene's name
        is_file = False
    return (name, None) if is_file else (design, name)
