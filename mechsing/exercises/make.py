"""Making the variants of an exercise: new numbers, the mechanism file, the statement, and
the answer key computed by mechsing (:func:`mechsing.analyze`, :func:`mechsing.sweep`,
:func:`mechsing.condition`, :func:`mechsing.cusps`).

Each variant is a folder ``variant-NN`` of the output directory with

* ``statement.md``: the statement with the variant's numbers, and the questions;
* ``mechanism.yaml``: the template's mechanism file with the drawn numbers;
* ``sheet.yaml``: an empty answer sheet for the student (``docs/exercises.md``);
* ``key.yaml`` and ``key.md``: the answer key, for ``mechsing exercise check`` and for
  people.

The same template and seed give byte-identical files.
"""

from __future__ import annotations

import math
import re
import tempfile
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from mechsing.errors import MechsingError, UserError
from mechsing.exercises.draw import ANSWERED, Draw, draws
from mechsing.exercises.formulas import formula_names
from mechsing.exercises.grade import CLASSES, KEY_VERSION, expected_text
from mechsing.exercises.paths import walk
from mechsing.exercises.template import Question, Template
from mechsing.exercises.units import UNITS
from mechsing.files import write_output

__all__ = ["Variant", "answer_key", "check_output", "make_variants", "render", "write_variants"]

_PLACEHOLDER = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)(?::([^{}]*))?\}")
#: significant digits of a number in key.md
_SHOWN_DIGITS = 6
#: significant digits of a number in key.yaml: far below any grading tolerance, and above
#: the last bits in which two machines' floating point may differ
_KEY_DIGITS = 12
#: draws whose questions mechsing cannot answer before the template is refused (each such
#: draw costs a computation; a template whose path is wrong fails on every draw)
MAX_UNANSWERED = 20


@dataclass(frozen=True)
class Variant:
    """One variant: its number, its draw and its answer key (question id -> entry)."""

    number: int
    draw: Draw
    key: list[dict[str, Any]]


def render(text: str, draw: Draw) -> str:
    """``{name}`` (the parameter as the file writes it, or its value to 6 digits) and
    ``{name:SPEC}`` (its value formatted by SPEC, e.g. ``.3f``) replaced; other braces
    are left as written."""

    def one(m: re.Match[str]) -> str:
        name, spec = m[1], m[2]
        if name not in draw.values:
            return m[0]
        if spec is None:
            return draw.texts.get(name) or format(draw.values[name], f".{_SHOWN_DIGITS}g")
        try:
            return format(draw.values[name], spec)
        except ValueError:
            raise UserError(f"the placeholder {m[0]!r}: {spec!r} is not a number format") from None

    return _PLACEHOLDER.sub(one, text)


def _compute(op: str, args: dict[str, Any], path: Path, draw: Draw) -> dict[str, Any]:
    """The JSON document of one mechsing computation on the variant's file."""
    args = {k: render(v, draw) if isinstance(v, str) else v for k, v in args.items()}
    if op == "analyze":
        from mechsing.analysis import analyze

        configs = [args["config"]] if "config" in args else None
        return analyze(path, configs, precision=args.get("precision", "float")).to_json()
    if op == "sweep":
        from mechsing.sweeps import sweep

        vary = args["vary"]
        vary = [render(v, draw) for v in vary] if isinstance(vary, list) else vary
        return sweep(
            path, vary, args.get("from"), precision=args.get("precision", "float")
        ).to_json()
    if op == "cusps":
        from mechsing.assembly.cusps import cusps

        return cusps(path, args["vary"], args.get("config"), args.get("points")).to_json()
    from mechsing.conditions import condition

    symbolic = args.get("symbolic") or ()
    return condition(path, args.get("config"), list(symbolic)).to_json()


def _rounded(x: float) -> float:
    return float(f"{x:.{_KEY_DIGITS}g}")


def _key_value(q: Question, got: Any) -> Any:
    """The answer found at the question's path, as the key states it."""
    if isinstance(got, (list, set)) and q.kind not in ("classes", "vector") and len(got) == 1:
        got = next(iter(got))
    if q.kind == "number":
        if isinstance(got, bool) or not isinstance(got, int | float) or not math.isfinite(got):
            raise UserError(f"question {q.id}: mechsing's answer {got!r} is not a number")
        return _rounded(float(got) / (UNITS[q.unit][1] if q.unit else 1.0))
    if q.kind == "vector":
        ok = isinstance(got, list) and all(
            isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) for x in got
        )
        if not ok or not got:
            raise UserError(f"question {q.id}: mechsing's answer {got!r} is not a vector")
        scale = UNITS[q.unit][1] if q.unit else 1.0
        return [_rounded(float(x) / scale) for x in got]
    if q.kind == "integer":
        if isinstance(got, bool) or not isinstance(got, int):
            raise UserError(f"question {q.id}: mechsing's answer {got!r} is not an integer")
        return got
    if q.kind == "boolean":
        if not isinstance(got, bool):
            raise UserError(f"question {q.id}: mechsing's answer {got!r} is not true or false")
        return got
    if q.kind == "classes":
        names = sorted({str(x) for x in (got if isinstance(got, (list, set)) else [got])})
        odd = [n for n in names if n not in CLASSES]
        if odd:
            raise UserError(f"question {q.id}: {odd} are not singularity classes")
        return names
    if not isinstance(got, str):
        raise UserError(f"question {q.id}: mechsing's answer {got!r} is not text")
    return got


def _domains(formula: str, path: Path, draw: Draw) -> dict[str, str]:
    """The domain of each variable of a formula answer (grading draws its values there):
    a joint's angle or a pose's angle ``phi`` over a period, a parameter of positive value
    positive, anything else (a slide, a pose's coordinate) of either sign."""
    from mechsing.reader import read_mechanism

    units = {j.name: j.units[0] for j in read_mechanism(path).joints if len(j.units) == 1}
    out = {}
    for name in sorted(formula_names(formula)):
        if name in units:
            out[name] = "angle" if units[name] == "rad" else "real"
        elif name in draw.values:
            out[name] = "positive" if draw.values[name] > 0 else "real"
        else:
            out[name] = "angle" if name == "phi" or name.startswith("phi_") else "real"
    return out


def answer_key(template: Template, draw: Draw, workdir: Path) -> list[dict[str, Any]]:
    """The key's entries, computed by mechsing on the draw's mechanism file."""
    path = workdir / "mechanism.yaml"
    write_output(path, draw.mechanism, [template.path], follow_links=False)
    cache: dict[str, dict[str, Any]] = {}
    entries = []
    for q in template.questions:
        op, args = q.compute
        tag = repr((op, sorted(args.items())))
        if tag not in cache:
            cache[tag] = _compute(op, args, path, draw)
        try:
            got = walk(cache[tag], render(q.path, draw))
        except (KeyError, IndexError, ValueError, StopIteration, TypeError):
            raise UserError(
                f"question {q.id}: mechsing's {op} output has nothing at {q.path!r}"
            ) from None
        entry: dict[str, Any] = {"id": q.id, "kind": q.kind, "value": _key_value(q, got)}
        if q.unit:
            entry["unit"] = q.unit
        if q.tol is not None:
            entry["tol"] = q.tol
        if q.up_to_factor:
            entry["up_to_factor"] = True
        if q.kind == "formula":
            entry["variables"] = _domains(entry["value"], path, draw)
        if q.up_to_sign:
            entry["up_to_sign"] = True
        entries.append(entry)
    return entries


def make_variants(template: Template, count: int, seed: int) -> list[Variant]:
    """``count`` variants drawn from ``seed``.  A draw whose answers mechsing cannot
    compute (a configuration it cannot reach) is refused like one that breaks a
    constraint; a UserError names the constraint that failed most when none is kept in
    :data:`~mechsing.exercises.draw.MAX_DRAWS` draws."""
    if count < 1:
        raise UserError(f"--variants must be at least 1 (got {count})")
    failures: Counter[str] = Counter()
    out: list[Variant] = []
    with tempfile.TemporaryDirectory(prefix="mechsing-exercise-") as tmp:
        for draw in draws(template, seed, failures):
            try:
                key = answer_key(template, draw, Path(tmp))
            except MechsingError as exc:
                failures[ANSWERED] += 1
                if failures[ANSWERED] >= MAX_UNANSWERED:
                    numbers = ", ".join(f"{k} = {v}" for k, v in draw.texts.items())
                    raise UserError(
                        f"{template.path}: mechsing could not answer the questions of "
                        f"{MAX_UNANSWERED} draws that met the constraints; the last ({numbers}): "
                        f"{exc}. Check the questions' compute and path, or add the "
                        "constraint these draws break"
                    ) from None
                continue
            out.append(Variant(len(out) + 1, draw, key))
            if len(out) == count:
                break
    return out


def _dump(doc: Any) -> str:
    return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True, width=100)


def _files(template: Template, variant: Variant, seed: int) -> dict[str, str]:
    title = f"{template.title} (variant {variant.number})"
    asks = [template.questions[i] for i in range(len(template.questions))]
    lines = [
        f"# {title}",
        "",
        render(template.statement, variant.draw).rstrip(),
        "",
        "## Questions",
        "",
    ]
    for i, q in enumerate(asks, 1):
        unit = f", in {q.unit}" if q.unit else ""
        lines.append(f"{i}. {render(q.ask, variant.draw)} (`{q.id}`{unit})")
    lines += [
        "",
        "Write your answers in `sheet.yaml` (one line per question, its id: your answer; a",
        "number may carry its unit, e.g. `33.1 deg`).",
        "",
    ]
    statement = "\n".join(lines)
    sheet = ["# Answer sheet: write each answer after its id (see statement.md)", "answers:"]
    for q in asks:
        hint = {
            "number": f"a number{' in ' + q.unit + ' (or give its unit)' if q.unit else ''}",
            "vector": f"numbers in brackets, e.g. [1, 0, -1]{' in ' + q.unit if q.unit else ''}",
            "integer": "an integer",
            "boolean": "true or false",
            "word": "a word",
            "classes": "class names, separated by commas",
            "formula": "a formula, e.g. 2*a*sin(B)",
        }[q.kind]
        sheet.append(f"  {q.id}:    # {hint}")
    key = {
        "key": KEY_VERSION,
        "exercise": template.exercise,
        "title": template.title,
        "variant": variant.number,
        "seed": seed,
        "numbers": dict(variant.draw.texts),
        "questions": variant.key,
    }
    md = [f"# Answer key: {title}", "", f"Seed {seed}. Numbers of this variant: "]
    md[-1] += ", ".join(f"{k} = {v}" for k, v in variant.draw.texts.items()) + "."
    md += ["", "| # | question | answer |", "|---|---|---|"]
    for i, entry in enumerate(variant.key, 1):
        md.append(f"| {i} | `{entry['id']}` | {expected_text(entry)} |")
    md += [
        "",
        "Computed by mechsing. Grade a sheet with `mechsing exercise check sheet.yaml --key key.yaml`.",
        "",
    ]
    return {
        "statement.md": statement,
        "mechanism.yaml": variant.draw.mechanism,
        "sheet.yaml": "\n".join(sheet) + "\n",
        "key.yaml": _dump(key),
        "key.md": "\n".join(md),
    }


def check_output(template: Template, out: Path, force: bool = False) -> None:
    """Refuse (UserError) an output directory that is a file, the template's folder or a
    folder inside it, or not empty without ``force``: called before the variants are
    computed."""
    out = Path(out)
    template_dir = template.path.resolve().parent
    if out.resolve() == template_dir or template_dir in out.resolve().parents:
        raise UserError(
            f"{out}: is the template's folder {template_dir} or inside it; mechsing never "
            "writes into an exercise's folder: write the variants elsewhere (-o)"
        )
    if out.exists() and not out.is_dir():
        raise UserError(f"{out}: is a file, not a directory: give a directory for -o")
    if out.exists() and any(out.iterdir()) and not force:
        raise UserError(
            f"{out}: the directory is not empty; choose a new one, or add --force to write "
            "the variant folders into it (files of the same names are replaced)"
        )


def _variant_folder(folder: Path, template_dir: Path) -> None:
    """Create a variant's folder (or keep it, under --force): a real directory, never a
    symbolic link (the files would go where it points) nor the exercise's folder."""
    if folder.is_symlink():
        raise UserError(
            f"{folder}: is a symbolic link; mechsing writes no file through a link: remove "
            "it or choose another -o"
        )
    if folder.resolve() == template_dir:
        raise UserError(f"{folder}: is the template's folder; choose another -o")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UserError(f"-o {folder}: cannot create the folder ({exc.strerror})") from None
    if not folder.is_dir() or folder.is_symlink():
        raise UserError(f"{folder}: exists and is not a directory; choose another -o")


def write_variants(
    template: Template, variants: list[Variant], seed: int, out: Path, force: bool = False
) -> list[Path]:
    """Write each variant's folder under ``out`` (checked by :func:`check_output`); never
    into the exercise's folder, never through a link planted in ``out``
    (:func:`mechsing.files.write_output` with ``follow_links=False``: each file is written
    whole beside its name and renamed over it), never over the template (a hard link to it
    is refused).  Returns the folders written."""
    out = Path(out)
    check_output(template, out, force)
    template_dir = template.path.resolve().parent
    width = max(2, len(str(len(variants))))
    written = []
    for v in variants:
        folder = out / f"variant-{v.number:0{width}d}"
        _variant_folder(folder, template_dir)
        for name, text in _files(template, v, seed).items():
            write_output(folder / name, text, [template.path], "-o", follow_links=False)
        written.append(folder)
    return written
