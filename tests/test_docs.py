"""The documentation site (floatfoam.docsite, ``make docs``): its reference pages are generated
from the code and list every key and command; the site builds with no warning (MkDocs'
strict mode: a broken link or anchor fails it)."""

from dataclasses import fields

from floatfoam import docsite, settings
from floatfoam.case import KEY_DOCS, SCHEMA
from floatfoam.cli import COMMANDS, build_parser


def test_the_case_file_reference_lists_every_table_and_key():
    page = docsite.settings_reference()
    for table, keys in SCHEMA.items():
        assert f"## [{table}]" in page
        if table in settings.TABLES:  # the typed settings: below, field by field
            continue
        documented = KEY_DOCS.get(table) or {}
        for key in keys or documented:  # [reference] is free-form: its one pattern
            assert f"| `{key}` |" in page, f"{table}.{key}"
    sections = {part.split("]", 1)[0]: part for part in page.split("\n## [")[1:]}
    for table, cls in settings.TABLES.items():  # each key in its own table's section
        for item in fields(cls):
            assert f"| `{item.name}` |" in sections[table] \
                or f"### [{table}.{item.name}]" in sections[table], f"{table}.{item.name}"
    for item in fields(settings.GmshSettings):
        assert f"| `{item.name}` |" in sections["mesh"].split("### [mesh.gmsh]")[1]


def test_every_schema_key_has_its_meaning():
    """A key added to the case file without a line in KEY_DOCS (or a settings doc) fails
    here, not in a user's reading."""
    for table, keys in SCHEMA.items():
        if table in settings.TABLES or keys is None:
            continue
        assert set(keys) == set(KEY_DOCS[table]), table


def test_the_commands_reference_lists_every_command_and_option():
    page = docsite.commands_reference()
    parsers = docsite.command_parsers(build_parser())
    assert sorted(parsers) == sorted(c.replace("_", "-") for c in COMMANDS)
    for name, parser in parsers.items():
        assert f"## {name}" in page
        for action in parser._actions:
            for option in action.option_strings:
                if option not in ("-h", "--help"):
                    assert option in page, f"{name} {option}"


def test_the_site_builds_without_a_warning(tmp_path):
    """~5 s: the reference pages (the API's imports every module), then mkdocs --strict."""
    site = docsite.build(tmp_path / "docs")
    assert (site / "index.html").is_file()
    assert (site / "docs" / "reference" / "case-toml.html").is_file()
    assert (site / "cases" / "flume_section_roll_sway_held" / "index.html").is_file()  # README


def test_every_setting_says_what_it_means():
    """The reference's meaning column comes from each field's doc: none is left empty."""
    for cls in (*settings.TABLES.values(), settings.GmshSettings):
        for item in fields(cls):
            if item.name == "gmsh":
                continue
            assert item.metadata.get("doc"), f"{cls.__name__}.{item.name}"


def test_the_validation_page_lists_every_measured_reference(tmp_path):
    """Generated from the cases' [reference] tables: every entry of every case is a row (an
    empty build folder: no study)."""
    from floatfoam.case import load_case
    from floatfoam.layout import list_cases

    page = docsite.validation_page(tmp_path)
    for folder in list_cases():
        for key in load_case(folder.name).reference:
            assert f"cases/{folder.name}/README.md) | {key}" in page, (folder.name, key)
    assert "No study of today's settings in this build folder" in page
