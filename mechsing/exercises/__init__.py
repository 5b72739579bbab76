"""Exercise variants with answer keys, and grading (``mechsing exercise``).

* :mod:`mechsing.exercises.template`: the template format (``template.yaml`` beside an
  exercise) and its reader :func:`load_template`;
* :mod:`mechsing.exercises.draw`: the variants' numbers, drawn from a seed under the
  template's constraints;
* :mod:`mechsing.exercises.make`: :func:`make_variants` (answers computed by mechsing)
  and :func:`write_variants`;
* :mod:`mechsing.exercises.grade`: :func:`grade` (a student's sheet against a key);
* :func:`find_exercise` and :func:`list_exercises`: the exercises of a checkout.

Exercises and their templates live in the source tree (``examples/exercises/``), not in
the installed package: from a checkout, an exercise is named by its folder (``12``,
``12-crank-rocker-sweep``); from an install, give the path of an exercise folder.
"""

from __future__ import annotations

from pathlib import Path

from mechsing.errors import UserError
from mechsing.exercises.grade import Grade, Mark, grade
from mechsing.exercises.make import Variant, make_variants, write_variants
from mechsing.exercises.template import TEMPLATE_FILE, Template, load_template

__all__ = [
    "Grade",
    "Mark",
    "Template",
    "Variant",
    "exercises_dir",
    "find_exercise",
    "grade",
    "list_exercises",
    "load_template",
    "make_variants",
    "write_variants",
]


def exercises_dir() -> Path | None:
    """The checkout's ``examples/exercises`` (None for an installed mechsing)."""
    here = Path(__file__).resolve().parents[2] / "examples" / "exercises"
    return here if here.is_dir() else None


def list_exercises(directory: Path | None = None) -> list[tuple[str, Path | None]]:
    """The exercises of ``directory`` (default: the checkout's), each with its template's
    path (None: no template)."""
    directory = directory or exercises_dir()
    if directory is None or not directory.is_dir():
        raise UserError(
            "no exercises folder: an installed mechsing has none; run from a checkout of "
            "mechsing, or give --dir DIRECTORY of exercise folders"
        )
    out = []
    for folder in sorted(p for p in directory.iterdir() if p.is_dir()):
        if (folder / "README.md").exists() or (folder / TEMPLATE_FILE).exists():
            t = folder / TEMPLATE_FILE
            out.append((folder.name, t if t.exists() else None))
    return out


def find_exercise(name: str) -> Path:
    """The template of an exercise: a path (an exercise folder or its template file), or
    a name of the checkout's exercises (``12``, ``12-crank-rocker-sweep``,
    ``crank-rocker-sweep``)."""
    p = Path(name)
    if p.is_file():
        return p
    if p.is_dir():
        if (p / TEMPLATE_FILE).is_file():
            return p / TEMPLATE_FILE
        raise UserError(f"{p}: the exercise has no {TEMPLATE_FILE} (see docs/exercises.md)")
    directory = exercises_dir()
    if directory is None:
        raise UserError(
            f"{name}: no such exercise folder; an installed mechsing has no bundled exercises: "
            "give the path of an exercise folder (examples/exercises/NN-name in a checkout)"
        )
    found = [
        d
        for d in sorted(directory.iterdir())
        if d.is_dir()
        and (
            d.name == name
            or d.name.split("-", 1)[0] == name.zfill(2)
            or d.name.split("-", 1)[-1] == name
        )
    ]
    if not found:
        known = ", ".join(n for n, _ in list_exercises(directory))
        raise UserError(f"{name}: no exercise of that name in {directory} (exercises: {known})")
    if not (found[0] / TEMPLATE_FILE).is_file():
        with_t = ", ".join(n for n, t in list_exercises(directory) if t)
        raise UserError(
            f"{found[0].name}: this exercise has no template (those with one: {with_t})"
        )
    return found[0] / TEMPLATE_FILE
