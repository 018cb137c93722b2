"""One block and one ``WIDTHxHEIGHT`` parser with one set of limits: ``check``, ``rock`` and
``margins`` (command line and API) accept or refuse a block alike (:mod:`audit.engine.shared.blocks`)."""

from __future__ import annotations

import math
from argparse import Namespace

import pytest

import audit
import records
from audit.cli import main
from audit.engine.shared.blocks import MAX_SIZE_S, Block, parse_blocks
from audit.errors import InputError

G = 9.81
# the largest height a 0.6 m wide block may have, by hand: 2π/p = 10 s gives
# p = 0.2π rad/s, R = 3g/(4p²) = 29.43 / (0.16π²) = 18.636 m, and h = 2√(R² − 0.3²) = 37.26 m
R_LIMIT = 3 * G / (4 * (2 * math.pi / 10.0) ** 2)
H_LIMIT = 2 * math.sqrt(R_LIMIT ** 2 - 0.3 ** 2)
INSIDE, OUTSIDE = f"0.6x{H_LIMIT - 0.01:.2f}", f"0.6x{H_LIMIT + 0.01:.2f}"
PULSE = ["--pulse", "cosine", "--amplitude", "0.3", "--pulse-period", "2"]


def test_the_limit_worked_by_hand():
    assert MAX_SIZE_S == 10.0
    assert R_LIMIT == pytest.approx(18.636, abs=1e-3) and H_LIMIT == pytest.approx(37.26, abs=0.01)
    (inside,) = parse_blocks([INSIDE])
    assert inside.size_s == pytest.approx(10.0, abs=2e-3) and inside.size_s < 10.0
    with pytest.raises(InputError, match="height_m"):
        parse_blocks([OUTSIDE])


def test_a_block_by_its_dimensions_by_hand():
    (block,) = parse_blocks(["0.4x2.0"])
    # α = atan(b/h) = atan(0.2/1.0); p = √(3g/(4R)), R = √(0.2² + 1²) (Eq. 4.2)
    assert block.alpha_deg == pytest.approx(math.degrees(math.atan(0.2)), rel=1e-12)
    assert block.size_s == pytest.approx(2 * math.pi / math.sqrt(3 * G / (4 * math.hypot(0.2, 1))),
                                         rel=1e-12)
    assert (block.width_m, block.height_m, block.label) == (0.4, 2.0, "0.4x2")


def test_one_class_from_the_api_to_the_engine():
    from audit.cli.check import objects_of
    from audit.engine.design.settings import MarginsSettings
    assert audit.Block is Block
    (obj,) = objects_of(Namespace(block=["0.6x1.8"], objects=None, alpha=None, size=None))
    settings = MarginsSettings.parse(blocks=["0.6x1.8"])
    assert type(obj) is Block and type(settings.blocks[0]) is Block
    assert obj.name == "0.6x1.8" and settings.blocks[0].label == "0.6x1.8"
    # the same block either way (the check's object keeps the name it was typed with)
    assert (obj.alpha_deg, obj.size_s) == (settings.blocks[0].alpha_deg,
                                           settings.blocks[0].size_s)


def _refusals(block: str, tmp_path, capsys) -> dict[str, str]:
    """The one line each command prints for ``--block block``, before any work ("" if the
    command accepted the block)."""
    commands = {
        "check": ["check", "--block", block, "--site", "1.5,0.9", "--out", str(tmp_path / "c")],
        "rock": ["rock", "--block", block, *PULSE, "--json"],
        "margins": ["margins", "fema356", "--records", "pulses", "--alpha", "15", "--size",
                    "3:3:1", "--block", block, "--out", str(tmp_path / "m")],
    }
    lines = {}
    for name, argv in commands.items():
        status = main(argv)
        err = capsys.readouterr().err.strip().splitlines()
        lines[name] = err[-1].removeprefix("error: ") if status else ""
        assert status in (0, 2)
        if status:
            assert len(err) == 1, err
    assert not (tmp_path / "c").exists() and not (tmp_path / "m").exists()
    return lines


@pytest.mark.parametrize("block", ["1x80", "1x500", OUTSIDE])
def test_every_command_refuses_a_block_too_large_alike(block, tmp_path, capsys):
    width, height = (float(x) for x in block.split("x"))
    # by hand: R = √(b² + h²), p = √(3g/(4R)), 2π/p (1x80: R = 40.003 m, 2π/p = 14.6 s)
    size_s = 2 * math.pi / math.sqrt(3 * G / (4 * math.hypot(width / 2, height / 2)))
    lines = _refusals(block, tmp_path, capsys)
    for name, line in lines.items():
        assert line.startswith(f"--block {block}: height_m: "), (name, line)
        assert f"has 2π/p = {size_s:.3g} s, beyond the 10 s" in line, (name, line)
        assert "metres?" not in line  # a 1 m wide base is not a width typed in millimetres
    # one parser: the same words from every command
    assert len(set(lines.values())) == 1


@pytest.mark.parametrize("block", ["2x1", "0x1.8", "0.6x", "axb", "0.6"])
def test_every_command_refuses_a_bad_block_alike(block, tmp_path, capsys):
    lines = _refusals(block, tmp_path, capsys)
    assert all(line.startswith(f"--block {block}: ") for line in lines.values()), lines
    assert len(set(lines.values())) == 1


def test_a_block_at_the_limit_is_accepted_by_every_command():
    from audit.cli.check import objects_of
    from audit.engine.design.settings import MarginsSettings
    (obj,) = objects_of(Namespace(block=[INSIDE], objects=None, alpha=None, size=None))
    (named,) = MarginsSettings.parse(blocks=[INSIDE]).blocks
    response = audit.rock(INSIDE, records.one_pulse("cosine", 0.3, 2.0))
    assert obj.size_s == named.size_s == response.block.size_s < 10.0


def test_millimetres_get_the_block_in_metres(tmp_path, capsys):
    lines = _refusals("500x2000", tmp_path, capsys)
    for line in lines.values():
        assert line.endswith("; millimetres? 0.5x2.0 m"), line
    with pytest.raises(InputError, match=r"^height_m: .*millimetres\? 0.6x1.8 m$") as caught:
        Block.from_dimensions(600, 1800)
    assert caught.value.fields == ("height_m",)
    # a base of 10 m or more is taken as millimetres (60 × 180 mm: 0.06 × 0.18 m)
    with pytest.raises(InputError, match=r"millimetres\? 0.06x0.18 m$"):
        parse_blocks(["60x180"])


def test_rock_takes_the_block_as_text():
    pulse = records.one_pulse("cosine", 0.3, 2.0)
    typed = audit.rock("0.8x2.0", pulse)
    made = audit.rock(audit.Block.from_dimensions(0.8, 2.0), pulse)
    assert typed.as_dict() == made.as_dict()
    assert (typed.block.width_m, typed.block.height_m) == (0.8, 2.0)
    with pytest.raises(InputError, match="^block 0.8x200: height_m"):
        audit.rock("0.8x200", pulse)
    # a block by slenderness and size meets the same limit (rock --alpha 10 --size 12)
    with pytest.raises(InputError, match=r"^block: height_m: .* 2π/p = 12 s"):
        audit.rock(audit.Block(alpha_deg=10, size_s=12.0), pulse)


def test_a_block_by_slenderness_has_its_dimensions():
    # α = 15°, 2π/p = 2 s: p = π rad/s, R = 3g/(4π²) = 0.7455 m; 2R sin 15°, 2R cos 15°
    block = Block(alpha_deg=15.0, size_s=2.0)
    radius = 3 * G / (4 * math.pi ** 2)
    assert block.width_m == pytest.approx(2 * radius * math.sin(math.radians(15)), rel=1e-12)
    assert block.height_m == pytest.approx(2 * radius * math.cos(math.radians(15)), rel=1e-12)
    with pytest.raises(InputError, match="^width_m"):
        Block(alpha_deg=15.0, size_s=2.0, width_m=0.5, height_m=block.height_m)
