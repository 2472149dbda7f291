"""The documentation site (``make docs``): MkDocs Material from README.md, docs/, the cases'
READMEs and CHANGELOG.md, with its reference pages generated from the code.

The pages are staged in ``<build>/docs/src`` as they sit in the repository (README.md as the
home page, ``index.md``), so that every relative link of the repository resolves in the site
too; a file a page links to that is no page (a case.toml, a CSV) is staged beside it. Four
pages are generated, never written by hand: ``docs/reference/case-toml.md`` (every table and
key of a case file, from :mod:`floatfoam.settings` and :data:`floatfoam.case.KEY_DOCS`),
``docs/reference/commands.md`` (every command and option, from the CLI's parser),
``docs/reference/api.md`` (the package's modules and public functions, from their
docstrings) and ``docs/reference/validation-references.md`` (every case's measured references
and the studies of this build folder). ``mkdocs build --strict`` then fails on any warning,
a broken link or anchor among them.
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import os
import pkgutil
import re
import shutil
import subprocess
import sys
from dataclasses import MISSING, fields
from pathlib import Path

from floatfoam import layout

ROOT = layout.ROOT
LINK = re.compile(r"\]\(([^)\s#]+)(#[^)\s]*)?\)")

# the site's sections: (title, files or folders under the staged tree, in order)
NAV = [
    ("Home", ["index.md"]),
    ("Getting started", ["docs/getting-started.md"]),
    ("Tutorials", ["docs/tutorials/own-section.md", "docs/tutorials/own-stl.md",
                   "docs/tutorials/roll-decay.md", "docs/tutorials/grid-study.md",
                   "docs/tutorials"]),
    ("User guide", ["docs/guide", "docs/paraview.md"]),
    ("Reference", ["docs/reference/case-toml.md", "docs/reference/commands.md",
                   "docs/reference/api.md", "docs/conventions.md"]),
    ("Theory", ["docs/theory", "docs/memoir.md", "docs/potential.md"]),
    ("Validation", ["docs/validation.md", "docs/reference/validation-references.md"]),
    ("Cases", ["cases"]),
    ("Developer guide", ["docs/architecture.md", "docs/developer"]),
    ("Studies", ["docs/morphing.md", "docs/coupling.md", "docs/openfoam-v1912.md",
                 "docs/studies"]),
    ("Changelog", ["CHANGELOG.md"]),
]


def _default(item) -> str:
    if item.default is not MISSING:
        value = item.default
    elif item.default_factory is not MISSING:
        return "(table)"
    else:
        return "required"
    return "—" if value is None else f"`{value!r}`" if isinstance(value, str) else f"`{value}`"


def _range(meta: dict) -> str:
    kind = meta.get("kind", float)
    if kind is bool:
        return "true or false"
    if kind is str:
        return "text"
    if kind is tuple:
        return "a list of names"
    low, high = meta.get("minimum"), meta.get("maximum")
    what = "whole number" if kind is int else "number"
    if low is None and high is None:
        return what
    left = "" if low is None else f"{low:g} {'≤' if meta.get('closed') else '<'} "
    right = "" if high is None else f" ≤ {high:g}"
    return f"{what}, {left}x{right}"


def settings_reference() -> str:
    """The case file's every table and key: the stages' typed settings (default, range,
    meaning) and the tables above them (:data:`floatfoam.case.KEY_DOCS`)."""
    from floatfoam import settings
    from floatfoam.case import KEY_DOCS

    lines = ["# case.toml reference", "",
             "Every table and key a case file may hold, generated from the code "
             "(`floatfoam.case.KEY_DOCS` and the typed settings of `floatfoam.settings`). Any "
             "key can be overridden on the command line: `--set table.key=value`.", ""]
    for table, keys in KEY_DOCS.items():
        lines += [f"## [{table}]", "", "| key | meaning |", "|---|---|"]
        lines += [f"| `{key}` | {text} |" for key, text in keys.items()]
        lines.append("")
    for table, cls in settings.TABLES.items():
        lines += [f"## [{table}]", "", _first_paragraph(cls.__doc__), ""]
        lines += _settings_rows(cls, table)
    return "\n".join(lines) + "\n"


def _settings_rows(cls, prefix: str) -> list[str]:
    from floatfoam import settings

    rows = ["| key | default | valid | meaning |", "|---|---|---|---|"]
    nested = []
    for item in fields(cls):
        if item.name == "gmsh" and cls is settings.MeshSettings:
            nested.append(item)
            continue
        meta = item.metadata
        doc = meta.get("doc", "").replace("|", "\\|")
        rows.append(f"| `{item.name}` | {_default(item)} | {_range(meta)} | {doc} |")
    rows.append("")
    for item in nested:
        rows += [f"### [{prefix}.{item.name}]", "",
                 _first_paragraph(settings.GmshSettings.__doc__), ""]
        rows += _settings_rows(settings.GmshSettings, f"{prefix}.{item.name}")
    return rows


def _first_paragraph(doc: str | None) -> str:
    text = inspect.cleandoc(doc or "").split("\n\n")[0]
    return " ".join(text.split())


def commands_reference() -> str:
    """Every command of ``floatfoam`` and its options, from the CLI's parser."""
    from floatfoam.cli import build_parser

    parser = build_parser()
    lines = ["# Commands", "",
             "Every `floatfoam` command and option, generated from the command-line parser "
             "(`floatfoam COMMAND --help` prints the same). Bad input is one line naming the "
             "parameter and what is valid, exit code 2, before anything is written.", "",
             "```text", parser.format_usage().strip(), "```", ""]
    for command, sub in command_parsers(parser).items():
        lines += [f"## {command}", "", _first_paragraph(sub.description or _help_of(
            parser, command)), "", "```text", sub.format_usage().strip(), "```", "",
            "| argument | default | meaning |", "|---|---|---|"]
        for action in sub._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            name = ", ".join(action.option_strings) or action.metavar or action.dest
            default = "" if action.default in (None, False, [], argparse.SUPPRESS) \
                or not action.option_strings else f"`{action.default}`"
            text = (action.help or "").replace("|", "\\|").replace("\n", " ")
            lines.append(f"| `{name}` | {default} | {text} |")
        lines.append("")
    return "\n".join(lines) + "\n"


def command_parsers(parser) -> dict:
    """The subcommands' parsers by name."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _help_of(parser, command: str) -> str:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for choice in action._choices_actions:
                if choice.dest == command:
                    return choice.help or ""
    return ""


def api_reference() -> str:
    """The package's modules, their summaries and their public functions and classes."""
    import floatfoam

    lines = ["# Python API", "",
             "## The public API: `floatfoam.__all__`", "",
             "What the command line is a layer over, importable from `floatfoam` itself "
             "(each name loaded when first used):", "",
             "```python", "import floatfoam", "",
             'case = floatfoam.load_case("sphere")           # a name under cases/, or a folder',
             "theory = floatfoam.theory_summary(case)        # floatfoam theory",
             'series = floatfoam.decay_series(case, "cummins")  # floatfoam decay-model',
             'fit = floatfoam.analyse_decay(series["time"], series["z"]).summary()',
             'run = floatfoam.run_case(case, "coarse", 2)    # floatfoam run (OpenFOAM)',
             "study = floatfoam.run_study(case, 2)           # floatfoam validate",
             "```", ""]
    for name in floatfoam.__all__:
        if name.startswith("__") or name == "package_version":
            continue
        member = getattr(floatfoam, name)
        try:
            signature = str(inspect.signature(member))
        except (TypeError, ValueError):
            signature = ""
        signature = "(…)" if len(signature) > 80 else signature
        lines.append(f"- `{name}{signature}` (`{floatfoam.API[name]}`): "
                     f"{_first_paragraph(member.__doc__)}")
    lines += ["", "## The modules", "",
              "The package's modules by subpackage, each with its docstring's first paragraph "
              "and its public functions and classes (generated from the code).", ""]
    for info in sorted(pkgutil.walk_packages(floatfoam.__path__, "floatfoam."),
                       key=lambda i: i.name):
        if info.name.startswith("floatfoam.cli") or info.name == "floatfoam.__main__":
            continue
        module = importlib.import_module(info.name)
        lines += [f"### `{info.name}`", "", _first_paragraph(module.__doc__), ""]
        for name, member in inspect.getmembers(module):
            if name.startswith("_") or getattr(member, "__module__", None) != info.name:
                continue
            if inspect.isfunction(member) or inspect.isclass(member):
                try:
                    signature = str(inspect.signature(member))
                except (TypeError, ValueError):
                    signature = "(…)"
                if len(signature) > 80:
                    signature = "(…)"
                lines.append(f"- `{name}{signature}`: {_first_paragraph(member.__doc__)}")
        lines.append("")
    return "\n".join(lines) + "\n"


def validation_page(build: Path | None = None) -> str:
    """Each case's measured references (its ``[reference]`` table: value, uncertainty, source)
    and, where ``floatfoam validate`` has left a study of the case's settings of today in the
    build folder, the CFD's finest level ± U_num for each quantity."""
    from floatfoam.analysis.measured import reference_entry
    from floatfoam.analysis.uncertainty import current_study
    from floatfoam.analysis.validation import QUANTITIES
    from floatfoam.case import load_case

    lines = ["# Validation: references and studies", "",
             "Generated from the cases' `[reference]` tables and the studies `floatfoam validate` "
             "has written in this machine's build folder (`make docs` regenerates it). A study "
             "made with other settings than the case's of today is left out.", "",
             "| case | measured | value | uncertainty | source |", "|---|---|---|---|---|"]
    studies = []
    for folder in layout.list_cases():
        case = load_case(folder.name)
        for key in case.reference:
            if key.endswith("_record"):
                source = case.reference[key].get("source", "")
                lines.append(f"| [{case.name}](../../cases/{case.name}/README.md) | {key} "
                             f"(a record: `{case.reference[key]['file']}`) | | | {source} |")
                continue
            value, uncertainty, source = reference_entry(case.reference, key)
            spread = "" if uncertainty is None else f"± {uncertainty:g}"
            lines.append(f"| [{case.name}](../../cases/{case.name}/README.md) | {key} | "
                         f"{value:g} | {spread} | {source} |")
        study, _ = current_study(case, build)
        if study is not None:
            studies.append((case.name, study))
    lines += ["", "## Grid and time-step studies", ""]
    if not studies:
        lines.append("No study of today's settings in this build folder: "
                     "`make validate CASE=<case>` makes one.")
    for name, study in studies:
        lines += [f"### {name}", "", "| DoF | quantity | finest level | U_num |",
                  "|---|---|---|---|"]
        for dof, entry in study["dofs"].items():
            finest = [run for run in ("fine", "medium", "coarse") if run in entry["runs"]]
            for key, words, _ in QUANTITIES:
                q = entry["quantities"].get(key, {})
                value = entry["runs"][finest[0]].get(key) if finest else None
                u = q.get("uncertainty")
                shown = "—" if value is None else f"{value:.5g} ({finest[0]})"
                lines.append(f"| {dof} | {words} | {shown} | "
                             f"{'—' if u is None else f'{100 * u:.2g} %'} |")
        lines.append("")
    return "\n".join(lines) + "\n"


def stage(out: Path) -> Path:
    """The site's sources in ``out``: the repository's pages where they sit, the generated
    reference, every file a page links to, and mkdocs.yml. Returns mkdocs.yml's path."""
    if out.exists():
        shutil.rmtree(out)
    src = out / "src"
    pages = [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted((ROOT / "docs").rglob("*.md")),
             *sorted((ROOT / "cases").glob("*/README.md"))]
    for page in pages:
        target = src / ("index.md" if page == ROOT / "README.md" else page.relative_to(ROOT))
        target.parent.mkdir(parents=True, exist_ok=True)
        text = page.read_text()
        if page == ROOT / "README.md":  # the home page sits where README.md does: links hold
            text = text.replace("](README.md", "](index.md")
        target.write_text(text)
        _stage_links(page, text, src)
    reference = src / "docs" / "reference"
    reference.mkdir(parents=True, exist_ok=True)
    (reference / "case-toml.md").write_text(settings_reference())
    (reference / "commands.md").write_text(commands_reference())
    (reference / "api.md").write_text(api_reference())
    (reference / "validation-references.md").write_text(validation_page())
    config = out / "mkdocs.yml"
    config.write_text(_config(src, out / "site"))
    return config


def _stage_links(page: Path, text: str, src: Path) -> None:
    """Copy into the staged tree every repository file ``page`` links to that is no page."""
    for match in LINK.finditer(text):
        target = match.group(1)
        if "://" in target or target.startswith("mailto:") or target.endswith(".md"):
            continue
        path = (page.parent / target).resolve()
        if path.is_file() and ROOT in path.parents:
            staged = src / path.relative_to(ROOT)
            staged.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, staged)
        elif path.is_dir() and ROOT in path.parents:
            (src / path.relative_to(ROOT)).mkdir(parents=True, exist_ok=True)


def _nav(src: Path) -> list:
    nav = []
    for title, entries in NAV:
        items = []
        for entry in entries:
            path = src / entry
            if path.is_dir():  # its pages not named before it, by name
                found = sorted(path.rglob("*.md"))
                items += [p.relative_to(src).as_posix() for p in found
                          if p.relative_to(src).as_posix() not in items]
            elif path.is_file() and entry not in items:
                items.append(entry)
        if len(items) == 1 and title != "Cases":
            nav.append({title: items[0]})
        elif items:
            nav.append({title: items})
    return nav


def _config(src: Path, site: Path) -> str:
    import json

    nav = json.dumps(_nav(src), ensure_ascii=False)
    return "\n".join([
        "site_name: floatfoam",
        "site_description: " + json.dumps("Oscillation and stability of floating bodies: "
                                          "theory, potential flow, CFD"),
        f"docs_dir: {json.dumps(str(src))}",
        f"site_dir: {json.dumps(str(site))}",
        "use_directory_urls: false",
        "theme:",
        "  name: material",
        "  features: [navigation.sections, navigation.indexes, search.highlight]",
        "markdown_extensions: [tables, toc, admonition, attr_list, md_in_html, "
        "pymdownx.superfences, pymdownx.arithmatex]",
        "validation:",
        "  omitted_files: info",
        "  absolute_links: warn",
        "  unrecognized_links: warn",
        "  anchors: warn",
        f"nav: {nav}",
        "",
    ])


def build(out: Path | None = None) -> Path:
    """Stage the site and build it with ``mkdocs build --strict``; returns the site's folder."""
    out = Path(out or layout.build_dir() / "docs")
    config = stage(out)
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}  # Material's banner about MkDocs 2
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f",
                           str(config)], capture_output=True, text=True, env=env)
    if done.returncode:  # the warnings (a broken link or anchor…), without mkdocs' INFO lines
        sys.stderr.write("".join(line for line in (done.stdout + done.stderr).splitlines(True)
                                 if not line.startswith("INFO")))
        raise SystemExit(f"docs: mkdocs build failed (exit {done.returncode}); the sources "
                         f"are in {out / 'src'}")
    return out / "site"


if __name__ == "__main__":
    print(build() / "index.html")
