"""Convert a robot description (URDF, MJCF; recognised by content) into a mechsing file.

The YAML written starts with a comment naming its source; it holds the bodies,
joints (placed in the ground frame at the description's zero configuration),
joint limits and output, and a reference configuration, so inputs, outputs and
configurations can be added and the work continued in YAML.  Analysing the
converted file gives the same result as analysing the description directly.  With
--output-body (--output-point, --relative-to) or --inputs the file holds that scene: the
output, the inputs, and only the part the output requires (a comment names what was left
out).
A mechanism file (YAML or JSON) needs no conversion and is refused.  Exit
status: 0 success, 2 bad input.
"""

from __future__ import annotations

import argparse
import sys

NAME = "convert"
HELP = "convert a URDF or MJCF description into a mechsing YAML file"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="IN", help="URDF or MJCF file (recognised by its content)")
    p.add_argument(
        "-o", "--output", metavar="OUT", help="the YAML file to write (default: standard output)"
    )
    from mechsing.cli.options import add_scene_options

    add_scene_options(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import UserError, load_mechanism
    from mechsing.cli.options import apply_scene
    from mechsing.errors import working_on
    from mechsing.files import check_output, write_output
    from mechsing.formats import xml_spec
    from mechsing.formats.writer import restrict_to, to_yaml
    from mechsing.reader import read_source

    with working_on(file=args.file):
        if args.output:
            check_output(args.output, [args.file])
        source = read_source(args.file)  # read once: a pipe or FIFO cannot be read twice
        if source.kind == "yaml":
            raise UserError(
                f"{args.file}: not a URDF or MJCF description (no XML root element <robot> "
                "or <mujoco>); a mechsing file needs no conversion"
            )
        # the converted file must load: the same checks (and warnings) as analyze
        mech = load_mechanism(source)
        chosen = apply_scene(mech, args, args.file)
        yaml_text = (
            source.yaml
            if chosen is mech
            else to_yaml(restrict_to(xml_spec(source.text, args.file), chosen))
        )
        if args.output:
            write_output(args.output, yaml_text, [args.file])
        else:
            sys.stdout.write(yaml_text)
    return 0
