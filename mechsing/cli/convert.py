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
from pathlib import Path

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
    from mechsing.formats import xml_format, xml_spec
    from mechsing.formats.writer import restrict_to, to_yaml
    from mechsing.formats.xmlsafe import MAX_XML_BYTES

    with working_on(file=args.file):
        path = Path(args.file)
        try:
            if path.stat().st_size > MAX_XML_BYTES:
                raise UserError(
                    f"{args.file}: the file has more than {MAX_XML_BYTES // 2**20} MB, more "
                    "than mechsing reads; remove the meshes or other large parts from it"
                )
            text = path.read_bytes().decode("utf-8-sig")
        except OSError as exc:
            raise UserError(f"{args.file}: cannot read the file ({exc.strerror})") from None
        except UnicodeDecodeError:
            raise UserError(f"{args.file}: the file is not UTF-8 text; save it as UTF-8") from None
        if xml_format(text) is None:
            raise UserError(
                f"{args.file}: not a URDF or MJCF description (no XML root element <robot> "
                "or <mujoco>); a mechsing file needs no conversion"
            )
        spec = xml_spec(text, args.file)
        # the converted file must load: the same checks as analyze
        mech = load_mechanism(args.file)
        chosen = apply_scene(mech, args, args.file)
        yaml_text = to_yaml(spec if chosen is mech else restrict_to(spec, chosen))
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
