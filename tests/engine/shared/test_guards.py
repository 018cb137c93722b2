"""Cost guards name what makes a command's work too large: the free motion, the longest
record, the number of records or the option of a grid, whichever is furthest beyond its usual
size (issue 23, item 6)."""

from types import SimpleNamespace

import numpy as np
import pytest

from audit.engine.shared import guards
from audit.errors import InputError
from records import GroundMotion, one_pulse

#: The --size and --alpha of the default grid: 151 sizes × 3 slendernesses.
DEFAULT_GRID = (guards.Setting("--size", 151, 151), guards.Setting("--alpha", 3, 3))


def _record(record_id, seconds, dt=0.01):
    """A record of ``seconds`` [s] whose samples take no memory (a broadcast zero)."""
    return SimpleNamespace(id=record_id, dt=dt, duration=seconds,
                           acceleration=np.broadcast_to(0.0, (int(seconds / dt) + 1,)))


def _refusal(cost) -> str:
    with pytest.raises(InputError) as refused:
        guards.check(cost, force=False)
    message = str(refused.value)
    assert "\n" not in message and "force=True" in message
    return message


def test_a_long_free_motion_is_named_by_its_option():
    pulse = one_pulse("cosine", 0.5, 1.0)
    message = _refusal(guards.estimate([pulse], 1e9, blocks=1, free_motion_option="--free-motion"))
    assert "mostly because of --free-motion 1e+09 s (free motion after each record)" in message
    assert "--size" not in message


def test_the_default_free_motion_of_short_records_is_not_blamed_for_a_fine_grid():
    # 10 s of free motion after 1 s pulses is 11 × their samples, and the default
    pulses = [one_pulse("cosine", 0.5, 1.0) for _ in range(7)]
    fine = (guards.Setting("--size", 50_000, 151), guards.Setting("--alpha", 3, 3))
    message = _refusal(guards.estimate(pulses, 10.0, blocks=150_000, settings=fine))
    assert "mostly because of --size, 50,000 values (151 by default): give fewer" in message


def test_one_long_record_is_named_with_its_length():
    records = [_record("short", 40.0), _record("endless", 300_000.0)]
    message = _refusal(guards.estimate(records, 10.0, blocks=453, settings=DEFAULT_GRID))
    assert "mostly because of record endless, 300000 s long (30,000,001 samples)" in message


def test_many_records_are_named_as_the_suite():
    records = [_record(f"r{i}", 40.0) for i in range(10_000)]
    message = _refusal(guards.estimate(records, 10.0, blocks=453, settings=DEFAULT_GRID))
    assert "mostly because of records, 10,000 of them (usually at most 56)" in message


def test_memory_refusal_names_the_record_that_fills_it():
    cost = guards.estimate([_record("huge", 400_000.0)], 0.0)  # 40 million samples stored
    assert cost.seconds == 0 and cost.memory_bytes > guards.REFUSE_MEMORY_BYTES
    message = _refusal(cost)
    assert "GB of memory" in message and "record huge, 400000 s long" in message


def test_memory_of_a_stored_free_motion_names_its_option():
    pulse = one_pulse("cosine", 0.5, 1.0)
    cost = guards.estimate([pulse], 1e6, oscillators=1, free_motion_option="--free-motion")
    assert cost.memory_cause.startswith("--free-motion 1e+06 s")


def test_no_records_cost_nothing():
    cost = guards.estimate([], 10.0, blocks=453, settings=DEFAULT_GRID)
    assert cost.seconds == 0 and cost.memory_bytes == 0
    guards.check(cost, force=False)


def test_real_motion_type_has_what_the_causes_read():
    motion = GroundMotion("rec", np.zeros(4001), 0.01)
    assert "record rec, 40 s long (4,001 samples)" in guards.estimate([motion], 0.0).memory_cause


def test_run_on_real_records_names_a_fine_sizes_grid(seed_manifest, tmp_path, capsys):
    from audit.cli import main
    # one thread doubles the estimate: refused well before any record is audited
    assert main(["run", "all", "--records", str(seed_manifest), "--size", "0.1:10:0.0001",
                 "--jobs", "1", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "mostly because of --size, 99,001 values (151 by default)" in err[0]
    assert not (tmp_path / "out").exists()
