"""One flag per quantity (issue 44, item 6): ``--size`` names block sizes on every command and
``--free-motion`` the free motion; the old names (``--sizes`` of run, spectrum and margins,
``--duration`` of rock) still parse to the same value and are left out of ``--help``."""

import pytest

from audit.cli import build_parser
from audit.cli.flags import FLAGS

#: (command line without the flag, new flag, old flag, text typed, parsed attribute, its value)
ALIASES = [
    (["run", "fema356"], "--size", "--sizes", "1:3:0.5", "size", "1:3:0.5"),
    (["spectrum"], "--size", "--sizes", "0.5,2", "size", "0.5,2"),
    (["margins", "all"], "--size", "--sizes", "2:4:1", "size", "2:4:1"),
    (["rock", "--size", "2", "--alpha", "15"], "--free-motion", "--duration", "3.5",
     "free_motion", 3.5),
]


@pytest.mark.parametrize("argv, flag, alias, text, dest, value", ALIASES)
def test_old_flag_parses_to_the_same_value(argv, flag, alias, text, dest, value):
    parser = build_parser()
    assert getattr(parser.parse_args([*argv, flag, text]), dest) == value
    assert getattr(parser.parse_args([*argv, alias, text]), dest) == value


@pytest.mark.parametrize("argv, flag, alias, text, dest, value", ALIASES)
def test_old_flag_is_not_in_help(argv, flag, alias, text, dest, value, capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args([argv[0], "--help"])
    shown = capsys.readouterr().out
    assert flag in shown and alias not in shown


def test_one_flag_per_size_and_free_motion():
    assert FLAGS["size_s"] == "--size" and FLAGS["free_motion_s"] == "--free-motion"


def test_default_sizes_unchanged_by_the_alias():
    """The hidden alias sets no default of its own: without either flag the grid is the
    command's default."""
    assert build_parser().parse_args(["run", "fema356"]).size == "0.5:8:0.05"


def test_check_takes_its_sizes_as_a_grid_or_a_list():
    from audit.cli.check import objects_of
    parser = build_parser()

    def names(sizes):
        args = parser.parse_args(["check", "--alpha", "15", "--size", sizes, "--site", "1.5,0.9"])
        return [o.name for o in objects_of(args)]
    expected = ["α=15°, 2π/p=1 s", "α=15°, 2π/p=1.5 s", "α=15°, 2π/p=2 s"]
    assert names("1:2:0.5") == names("1,1.5,2") == expected
