"""Every code example of the documentation runs, so the docs cannot drift from the program.

Pages: every ``docs/*.md`` and the ``README.md``.  Each page runs in its own temporary
working directory holding a link ``examples`` to the repository's examples/ folder.

* A ```yaml (or ```xml) block whose first line is ``# file: NAME`` (``<!-- file: NAME -->``
  for XML) is written to the page's directory before the page's commands run.
* A ```console block: each line starting with ``$ mechsing `` is run through the command
  line's ``main()`` in that directory; the lines after it, up to the next ``$ `` line or
  the block's end, are its expected standard output, compared line by line after
  stripping trailing spaces: a line holding only ``...`` matches any number of lines, and
  ``...`` inside a line matches any text.  The expected exit status is 0 unless the command
  line ends with ``  # exit N``.  Other ``$ `` lines (a shell command) are not run.
* A ```python block with ``>>>`` lines is a doctest (ELLIPSIS and NORMALIZE_WHITESPACE).
* Other blocks (```text, ```yaml without ``# file:``, ```bash, ```sh) are not run.

The checks of this module are the docs' own rules: links between pages resolve, and no
page points outside the project.
"""

from __future__ import annotations

import doctest
import os
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.cli import run_cli

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]

_FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```\s*$", re.S | re.M)
_EXIT = re.compile(r"\s+#\s*exit\s+(\d+)\s*$")
_FILE_YAML = re.compile(r"^#\s*file:\s*(\S+)\s*$")
_FILE_XML = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->\s*$")


@dataclass
class Command:
    """One ``$ mechsing ...`` line of a console block and what it must print."""

    argv: list[str]
    status: int
    expected: list[str]
    line: int


@dataclass
class Page:
    """The runnable parts of one Markdown page."""

    files: dict[str, str] = field(default_factory=dict)
    commands: list[Command] = field(default_factory=list)
    doctests: list[tuple[int, str]] = field(default_factory=list)


def parse_page(text: str) -> Page:
    """The files, commands and doctests of a page, in page order."""
    page = Page()
    for m in _FENCE.finditer(text):
        lang, body = m.group(1).lower(), m.group(2)
        line = text.count("\n", 0, m.start()) + 2
        lines = body.splitlines()
        if lang in ("yaml", "yml", "xml") and lines:
            pat = _FILE_XML if lang == "xml" else _FILE_YAML
            fm = pat.match(lines[0].strip())
            if fm:
                page.files[fm.group(1)] = body
        elif lang == "console":
            page.commands.extend(_console(lines, line))
        elif lang in ("python", "pycon") and any(x.lstrip().startswith(">>>") for x in lines):
            page.doctests.append((line, body))
    return page


def _console(lines: list[str], first: int) -> list[Command]:
    out: list[Command] = []
    current: Command | None = None
    for i, raw in enumerate(lines):
        if raw.startswith("$ "):
            current = None
            if raw.startswith("$ mechsing "):
                cmd = raw[len("$ mechsing ") :]
                status = 0
                em = _EXIT.search(cmd)
                if em:
                    status = int(em.group(1))
                    cmd = cmd[: em.start()]
                current = Command(shlex.split(cmd), status, [], first + i)
                out.append(current)
        elif current is not None:
            current.expected.append(raw.rstrip())
    return out


def _line_matches(pattern: str, line: str) -> bool:
    if "..." not in pattern:
        return pattern == line
    parts = [re.escape(p) for p in pattern.split("...")]
    return re.fullmatch(".*".join(parts), line, re.S) is not None


def output_matches(expected: list[str], actual: list[str]) -> bool:
    """Line-by-line match; a line of only ``...`` matches any number of lines."""
    exp = [e.rstrip() for e in expected]
    while exp and not exp[-1]:
        exp.pop()
    act = [a.rstrip() for a in actual]
    while act and not act[-1]:
        act.pop()
    memo: dict[tuple[int, int], bool] = {}

    def go(i: int, j: int) -> bool:
        key = (i, j)
        if key in memo:
            return memo[key]
        if i == len(exp):
            ok = j == len(act)
        elif exp[i].strip() == "...":
            ok = any(go(i + 1, k) for k in range(j, len(act) + 1))
        else:
            ok = j < len(act) and _line_matches(exp[i], act[j]) and go(i + 1, j + 1)
        memo[key] = ok
        return ok

    return go(0, 0)


# -- the matcher's own rules ---------------------------------------------------------


def test_ellipsis_rules() -> None:
    assert output_matches(["a", "...", "d"], ["a", "b", "c", "d"])
    assert output_matches(["a", "...", "b"], ["a", "b"])
    assert output_matches(["x = ... m"], ["x = 1.5 m"])
    assert not output_matches(["a", "c"], ["a", "b"])
    assert not output_matches(["a"], ["a", "b"])
    assert output_matches(["a  "], ["a"])


def test_console_blocks_are_parsed() -> None:
    text = (
        "```yaml\n# file: one.yaml\nbodies: [a]\n```\n"
        "```console\n$ mechsing analyze one.yaml  # exit 2\nerror\n...\n$ ls\nx\n```\n"
        "```yaml\nnot: written\n```\n"
    )
    page = parse_page(text)
    assert list(page.files) == ["one.yaml"]
    (cmd,) = page.commands
    assert cmd.argv == ["analyze", "one.yaml"] and cmd.status == 2
    assert cmd.expected == ["error", "..."]


# -- the pages -----------------------------------------------------------------------


def _run_page(path: Path, tmp_path: Path) -> None:
    page = parse_page(path.read_text(encoding="utf-8"))
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    for name, body in page.files.items():
        (tmp_path / name).write_text(body, encoding="utf-8")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        for cmd in page.commands:
            run = run_cli(cmd.argv)
            where = f"{path.name}:{cmd.line}: mechsing {' '.join(cmd.argv)}"
            assert run.status == cmd.status, f"{where}: exit {run.status}\n{run.err}"
            assert output_matches(cmd.expected, run.out.splitlines()), (
                f"{where}: output differs\n--- expected\n"
                + "\n".join(cmd.expected)
                + "\n--- got\n"
                + run.out
            )
    finally:
        os.chdir(here)
    if page.doctests:
        here = os.getcwd()
        os.chdir(ROOT)
        try:
            parser = doctest.DocTestParser()
            flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
            runner = doctest.DocTestRunner(optionflags=flags)
            globs: dict = {}
            for line, body in page.doctests:
                test = parser.get_doctest(body, globs, path.name, str(path), line)
                runner.run(test)
            assert runner.failures == 0, f"{path.name}: {runner.failures} doctest failures"
        finally:
            os.chdir(here)


@pytest.mark.parametrize(
    "path", PAGES, ids=[p.name if p.parent.name != "docs" else f"docs/{p.name}" for p in PAGES]
)
def test_page_examples_run(path: Path, tmp_path: Path) -> None:
    """Every console block, file and doctest of the page runs as the page says."""
    _run_page(path, tmp_path)


_LINK = re.compile(r"\]\(([^)\s]+)\)")


@pytest.mark.parametrize("path", PAGES, ids=[p.name for p in PAGES])
def test_relative_links_resolve(path: Path) -> None:
    """Every relative link of a page names a file of the project (anchors are not checked)."""
    text = path.read_text(encoding="utf-8")
    for target in _LINK.findall(text):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        file = target.split("#", 1)[0]
        assert (path.parent / file).exists(), f"{path.name}: {target}"


def test_docs_index_lists_every_page() -> None:
    index = (ROOT / "docs" / "README.md").read_text(encoding="utf-8")
    for page in sorted((ROOT / "docs").glob("*.md")):
        if page.name != "README.md":
            assert f"({page.name})" in index, page.name
