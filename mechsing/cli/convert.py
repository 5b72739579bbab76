"""Convert a robot description (URDF, MJCF; recognised by content) into a mechsing file.

The YAML written starts with a comment naming its source; it holds the bodies,
joints (placed in the ground frame at the description's zero configuration),
joint limits and output, and a reference configuration, so inputs, outputs and
configurations can be added and the work continued in YAML.  Analysing the
converted file gives the same result as analysing the description directly.
A mechanism file (YAML or JSON) needs no conversion and is refused.  Exit
status: 0 success, 2 bad input.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "convert"
HELP = "convert a URDF or MJCF description into a mechsing YAML file"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="IN", help="URDF or MJCF file (recognised by its content)")
    p.add_argument(
        "-o", "--output", metavar="OUT", help="the YAML file to write (default: standard output)"
    )


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import UserError, load_mechanism
    from mechsing.errors import working_on
    from mechsing.reader import read_source

    with working_on(file=args.file):
        source = read_source(args.file)
        if source.kind == "yaml":
            raise UserError(
                f"{args.file}: not a URDF or MJCF description (no XML root element <robot> "
                "or <mujoco>); a mechsing file needs no conversion"
            )
        yaml_text = source.yaml
        load_mechanism(source)  # the converted file must load: the same checks as analyze
        if args.output:
            try:
                Path(args.output).write_text(yaml_text, encoding="utf-8")
            except OSError as exc:
                raise UserError(
                    f"cannot write {args.output}: {exc.strerror}; choose a writable path"
                ) from None
        else:
            sys.stdout.write(yaml_text)
    return 0
