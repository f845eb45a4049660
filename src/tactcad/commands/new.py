"""``tactcad new DIR``: make a sensor project folder (design, rigs, scenes,
README, .gitignore, CI workflow) from a shipped example or a design file."""

from __future__ import annotations

import argparse
import json
import shlex

from tactcad.commands.options import output_folder
from tactcad.commands import add_output_args
from tactcad.project_folder import DEFAULT_EXAMPLE, die_examples, examples


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "new", help="make a sensor project folder: design, rigs, scenes, README, CI workflow",
        description="Makes the folder DIR of a sensor project: the design file (naming its "
                    "rigs and scenes files in its [files] table), rigs.toml with samples over "
                    "the design's own K_obj range (N/mm; none for a construction without a "
                    "mount for the test rigs), scenes.toml, purchased-parts.md (the bought "
                    "parts of the design's BOM; an example's own list for --example), a "
                    "README, a .gitignore (exports, cache) and .github/workflows/hardware.yml "
                    "(export, check --junit, diff). DIR may exist if it holds none of these "
                    "files (a new git repository, say). Builds no geometry.")
    p.add_argument("dir", metavar="DIR", type=output_folder, help="the project folder to make")
    start = p.add_mutually_exclusive_group()
    start.add_argument("--example", metavar="NAME", default=None,
                       help="start from this shipped example, its own rigs and scenes "
                            "included: " + ", ".join([*examples(), *die_examples()])
                            + f" (default: {DEFAULT_EXAMPLE}; macro_array is the paper's 2 x 5 "
                            "array, grasper_jaw_10mm a comb insert for a 10 mm grasper's jaw, "
                            "grasper_jaw_5mm_mems a silicon die for a 5 mm grasper: its "
                            "project holds the die design file, a README and a .gitignore)")
    start.add_argument("--from-design", metavar="FILE", default=None,
                       help="start from this design file; its rigs and scenes files are "
                            "copied where it has them and the rigs fit it (check's rigs "
                            "group passes), else made for it, saying so")
    p.add_argument("--force", action="store_true",
                   help="overwrite the project's files where DIR has them (default: refuse); "
                        "those tactcad wrote for the project DIR held and the new one does not "
                        "write are removed, files of your own are kept")
    add_output_args(p, "print JSON: the folder, the design file and every file written")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from tactcad.project_folder import new_project

    made = new_project(args.dir, example=args.example, from_design=args.from_design,
                       force=args.force)
    if args.json:
        print(json.dumps({"folder": str(made.folder), "design": str(made.design),
                          "files": list(made.files), "removed": list(made.removed),
                          "notes": list(made.notes)}))
        return 0
    for note in made.notes:  # the design's own rigs did not fit it: made anew
        print(f"note: {note}")
    print(f"made {made.folder}/ with {len(made.files)} files:")
    for rel in made.files:
        print(f"  {rel}")
    if made.removed:  # --force: the earlier project's files the new one does not write
        print(f"removed the earlier project's {', '.join(made.removed)}")
    design = made.design.name
    folder = str(made.folder)
    folder = f"./{folder}" if folder.startswith("-") else folder  # not an option of cd
    print(f"next: cd {shlex.quote(folder)} && tactcad export --design "
          f"{shlex.quote(design)} --out exports")
    return 0
