"""Exercise variants for a class, with answer keys computed by mechsing, and grading.

  mechsing exercise list                      the exercises, and which have a template
  mechsing exercise make EXERCISE --variants N --seed S -o DIR
                                              N variants: statement, mechanism file,
                                              empty sheet and answer key each
  mechsing exercise check SHEET.yaml --key KEY.yaml
                                              grade a student's sheet

EXERCISE is an exercise folder (or its template.yaml), or, in a checkout of mechsing, the
name of a bundled exercise (12, 12-crank-rocker-sweep).  The same seed gives the same
files.  docs/exercises.md explains templates, keys and sheets.  Exit status of check: 0
when every answer is right, 1 when one is wrong or missing (the grades are printed all the
same); 2 for a sheet or key that cannot be read.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

NAME = "exercise"
HELP = "make exercise variants with answer keys, and grade answer sheets"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    sub = parser.add_subparsers(dest="action", metavar="ACTION", required=True)
    p = sub.add_parser("list", help="the exercises, and which have a template")
    p.add_argument(
        "--dir", metavar="DIR", help="a folder of exercise folders (default: the checkout's)"
    )
    p.add_argument("--format", choices=("text", "json"), default="text", help="output format")
    p = sub.add_parser("make", help="variants of an exercise, each with its answer key")
    p.add_argument(
        "exercise", metavar="EXERCISE", help="an exercise folder, or a bundled exercise's name"
    )
    p.add_argument("--variants", type=int, default=1, metavar="N", help="how many (default 1)")
    p.add_argument(
        "--seed",
        type=int,
        required=True,
        metavar="S",
        help="the seed of the draws (an integer >= 0)",
    )
    p.add_argument(
        "-o", "--output", required=True, metavar="DIR", help="where the variant folders go"
    )
    p.add_argument(
        "--force",
        action="store_true",
        help="write into DIR even if it is not empty (variant files of the same names are replaced)",
    )
    p.add_argument("--quiet", action="store_true", help="print nothing on success")
    p = sub.add_parser(
        "check",
        help="grade an answer sheet against a key (exit 0: all right, 1: not all right)",
        description="Grade a student's answer sheet against a variant's key.  Exit status: 0 "
        "when every answer is right, 1 when one is wrong or missing (the grades are printed "
        "all the same), 2 when the sheet or the key cannot be read.",
    )
    p.add_argument("sheet", metavar="SHEET", help="the student's answer sheet (YAML)")
    p.add_argument("--key", required=True, metavar="KEY", help="the variant's key.yaml")
    p.add_argument("--format", choices=("text", "json"), default="text", help="output format")


def run(args: argparse.Namespace) -> int:
    from mechsing.errors import UserError

    if args.action == "list":
        from mechsing.exercises import list_exercises

        found = list_exercises(Path(args.dir) if args.dir else None)
        if args.format == "json":
            rows = [{"exercise": n, "template": str(t) if t else None} for n, t in found]
            print(json.dumps({"exercises": rows}, indent=2))
        else:
            width = max((len(n) for n, _ in found), default=8)
            for n, t in found:
                print(f"{n:<{width}}  {'template' if t else '-'}")
            print(f"{sum(1 for _, t in found if t)} of {len(found)} exercises have a template")
        return 0
    if args.action == "make":
        from mechsing.exercises import find_exercise, load_template, make_variants, write_variants
        from mechsing.exercises.make import check_output

        if args.seed < 0:
            raise UserError(f"--seed must be an integer >= 0 (got {args.seed})")
        template = load_template(find_exercise(args.exercise))
        check_output(template, Path(args.output), args.force)  # before the work
        variants = make_variants(template, args.variants, args.seed)
        written = write_variants(template, variants, args.seed, Path(args.output), args.force)
        if not args.quiet:
            print(
                f"{template.exercise}: {len(written)} variant{'s' if len(written) != 1 else ''} "
                f"(seed {args.seed}) in {args.output}"
            )
            for folder in written:
                print(f"  {folder}")
        return 0
    from mechsing.exercises import grade

    result = grade(args.sheet, args.key)
    if args.format == "json":
        print(json.dumps(result.to_json(), indent=2))
    else:
        print(result.text())
    sys.stdout.flush()
    # as graders and CI scripts expect: success only when the sheet is all right
    return 0 if result.count("right") == len(result.marks) else 1
