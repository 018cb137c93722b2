"""Schedulers: the same values whatever computes the records; records by reference or by value."""

import json
import pickle
import sys
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
import pytest

from audit.engine.run.record_audit import audit_record
from audit.engine.shared.schemas import SUITE_COLUMNS
from audit.engine.run.settings import AuditSettings
from audit.engine.run.pipeline import audit_in_memory
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.record_references import RecordReference, by_reference, resolve
from audit.engine.shared.scheduler import check_scheduler, open_scheduler
from audit.cli import main
from audit.errors import InputError
from procedures import get_procedures
from records import RecordSuite, one_pulse

GRID = dict(alpha_deg=[15.0, 20.0], size_s=np.arange(3.0, 8.01, 1.0))
FRAMES = ("results", "rocking", "spectra", "histories", "estimates_only", "suite")


@pytest.fixture(scope="module")
def three_records(seed_suite):
    """Three real records (two AT2 files, one column file) and one missing record."""
    ids = ("pacoima_dam_1971", "el_centro_5_1979", "sylmar_1994", "takatori_1995")
    return RecordSuite(tuple(seed_suite.get(i) for i in ids), "three seed records")


@pytest.fixture(scope="module")
def local_run(three_records):
    return audit_in_memory(get_procedures("all"), three_records, detail=["sylmar_1994"],
                           runtime=Runtime(jobs=2), **GRID)


def _assert_same_run(run, reference):
    for name in FRAMES:
        pd.testing.assert_frame_equal(getattr(run, name), getattr(reference, name),
                                      check_exact=True)
    assert run.summary["suite"] == reference.summary["suite"]
    assert run.summary["statistics"] == reference.summary["statistics"]


def test_local_run_fills_suite_statistics(local_run):
    suite = local_run.suite
    assert list(suite.columns) == SUITE_COLUMNS
    # one row per procedure × α × size (Priestley, FEMA 356, NTC 2018), over the records with a file
    assert len(suite) == 3 * len(GRID["alpha_deg"]) * len(GRID["size_s"])  # priestley, fema, ntc
    assert suite.loc[suite["procedure"] == "priestley1978", "records"].eq(3).all()
    fractions = suite.filter(like="frac_").drop(columns="frac_unsafe").sum(axis=1)
    np.testing.assert_allclose(fractions, 1.0, atol=5e-6)  # as saved: 6 significant digits
    assert local_run.summary["scheduler"] == "this process"
    assert local_run.summary["detail"] == ["sylmar_1994"] and local_run.summary["resumed"] == []


@pytest.mark.slow  # end to end: a local dask cluster
def test_dask_local_cluster_gives_identical_values(three_records, local_run):
    run = audit_in_memory(get_procedures("all"), three_records,
                          runtime=Runtime(jobs=2, scheduler="dask"),
                          detail=["sylmar_1994"], **GRID)
    assert "LocalCluster of 2" in run.summary["scheduler"]
    _assert_same_run(run, local_run)


def test_existing_cluster_by_address_gives_identical_values(three_records, local_run):
    from distributed import LocalCluster
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=True,
                      dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://")
        run = audit_in_memory(get_procedures("all"), three_records,
                              runtime=Runtime(scheduler=address), **GRID)
        # a record scaled after reading cannot be read back by reference: sent again by value
        pacoima = three_records.get("pacoima_dam_1971")
        scaled = replace(pacoima, motion=replace(pacoima.motion,
                                                 acceleration=0.5 * pacoima.motion.acceleration))
        settings = AuditSettings(alpha_deg=(20.0,), size_s=(6.0,))
        with open_scheduler(address, 1) as scheduler:
            [(_, remote, _), (_, unscaled, _)] = sorted(
                scheduler.map(audit_record, [scaled, pacoima], get_procedures("all"),
                              replace(settings, jobs=scheduler.solver_threads)),
                key=lambda done: done[0])
        assert scheduler.by_value == ["pacoima_dam_1971"]       # the scaled one, once
    assert address in run.summary["scheduler"]
    _assert_same_run(run, local_run)
    pd.testing.assert_frame_equal(remote.rocking,
                                  audit_record(scaled, get_procedures("all"), settings).rocking,
                                  check_exact=True)
    assert not unscaled.rocking.equals(remote.rocking)


def test_file_records_travel_by_reference_and_read_back_identical(seed_suite):
    for entry in seed_suite:
        item = by_reference(entry)
        if entry.missing:
            assert item is entry
            continue
        assert isinstance(item, RecordReference) and item.entry.motion is None
        back = resolve(item)
        assert back == replace(entry, motion=back.motion)
        for name in ("id", "dt", "component", "source", "sha256", "metadata"):
            assert getattr(back.motion, name) == getattr(entry.motion, name)
        assert np.array_equal(back.motion.acceleration, entry.motion.acceleration)


def test_scaled_or_unreadable_records_are_not_resolved_and_pulses_go_by_value(seed_suite):
    entry = seed_suite.get("pacoima_dam_1971")
    scaled = replace(entry, motion=replace(entry.motion,
                                           acceleration=entry.motion.acceleration * 1.5))
    assert resolve(by_reference(scaled)) is None          # same file, other samples
    elsewhere = by_reference(entry)
    moved = replace(elsewhere, motion_fields={**elsewhere.motion_fields,
                                              "source": "/nonexistent/RSN77.AT2"})
    assert resolve(moved) is None
    pulse = replace(entry, motion=one_pulse("cosine", 0.5, 1.0, record_id="p"))
    assert by_reference(pulse) is pulse


@dataclass(frozen=True)
class _Item:
    """A stand-in record: no motion, so it travels by value."""
    id: str
    value: int
    motion: None = None


def _tripled(item, factor):
    return item.value * factor


def test_dask_submits_records_as_others_complete():
    # the scheduler holds a record sent by value only while it is queued or running: at most
    # TASKS_PER_THREAD per worker thread in flight, whatever the suite's length
    from distributed import Client
    from audit.engine.shared.scheduler import TASKS_PER_THREAD, DaskScheduler
    items = [_Item(f"r{i}", i) for i in range(12)]
    with Client(processes=False, n_workers=1, threads_per_worker=1,
                dashboard_address=None) as client:
        scheduler = DaskScheduler(client, "one thread")
        done, most = {}, 0
        for index, value, _ in scheduler.map(_tripled, items, 3):
            done[index] = value
            most = max(most, len(client.futures) - 1)  # less the scattered factor
    assert done == {i: 3 * i for i in range(12)}
    assert 1 <= most <= TASKS_PER_THREAD
    assert scheduler.by_value == [item.id for item in items]


def test_scheduler_option_is_checked():
    assert check_scheduler("tcp://10.0.0.5:8786") == "tcp://10.0.0.5:8786"
    for bad in ("threads", "tcp://host", "tcp://:8786", "10.0.0.5:8786"):
        with pytest.raises(InputError, match="^scheduler: "):  # the command line: --scheduler
            check_scheduler(bad)


def test_missing_dask_is_one_line_naming_the_package(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)   # import distributed → ImportError
    with pytest.raises(InputError, match=r"dask\[distributed\]") as error:
        with open_scheduler("dask", 2):
            pass
    assert "\n" not in str(error.value)


@pytest.mark.parametrize("option, message", [
    (["--scheduler", "threads"], "--scheduler: expected local, dask or tcp://HOST:PORT"),
    (["--detail", "pacoima_dam_1971,nowhere"], "--detail: unknown record(s) nowhere"),
])
def test_cli_refuses_bad_scheduler_and_detail_before_writing(seed_manifest, tmp_path, capsys,
                                                             option, message):
    out = tmp_path / "out"
    assert main(["run", "all", "--records", str(seed_manifest), "--out", str(out), *option]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_local_scheduler_overlaps_two_records_and_yields_in_order():
    # each task waits until a second one has started: run one at a time they would time out
    import threading
    from audit.engine.shared.scheduler import RECORDS_IN_FLIGHT, LocalScheduler
    both = threading.Barrier(RECORDS_IN_FLIGHT, timeout=60)
    lock, running, most = threading.Lock(), [0], [0]

    def task(item, factor):
        with lock:
            running[0] += 1
            most[0] = max(most[0], running[0])
        if item.value < 2:
            both.wait()
        with lock:
            running[0] -= 1
        return item.value * factor

    items = [_Item(f"r{i}", i) for i in range(7)]
    yielded = [(index, value) for index, value, _ in LocalScheduler().map(task, items, 3)]
    assert yielded == [(i, 3 * i) for i in range(7)]
    assert most[0] == RECORDS_IN_FLIGHT


def test_local_scheduler_starts_the_next_record_when_a_later_one_finishes_first():
    # the first record waits until the third has run: the third must start on the thread the
    # second frees, before anyone has taken the first (which the caller waits for)
    import threading
    from audit.engine.shared.scheduler import LocalScheduler
    third_ran = threading.Event()

    def task(item, factor):
        if item.value == 0:
            assert third_ran.wait(timeout=60), "the third record never started"
        if item.value == 2:
            third_ran.set()
        return item.value * factor

    items = [_Item(f"r{i}", i) for i in range(5)]
    yielded = [(index, value) for index, value, _ in LocalScheduler().map(task, items, 3)]
    assert yielded == [(i, 3 * i) for i in range(5)]


def _tripled_with(item, procedures, factor):
    return item.value * factor


@pytest.mark.slow  # end to end: a local dask cluster
def test_dask_maps_one_after_another_with_the_same_arguments():
    # a design-level audit maps several times on one cluster with the same procedures (the
    # stripes, then the required α and its bisections): each map's arguments must outlive the
    # release of the last map's. Scattered under one key (hash=True) they did not, at random:
    # "lost dependencies" within a few maps on two worker processes.
    from distributed import Client, LocalCluster
    from audit.engine.shared.scheduler import DaskScheduler
    items = [_Item(f"r{i}", i) for i in range(6)]
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        scheduler = DaskScheduler(client, "two processes")
        for _ in range(30):
            done = {index: value for index, value, _ in
                    scheduler.map(_tripled_with, items, get_procedures("all"), 3)}
            assert done == {i: 3 * i for i in range(6)}


def test_parts_handed_back_out_of_order_are_written_in_the_suites_order(three_records, tmp_path,
                                                                        monkeypatch):
    """A Dask cluster hands records back as they complete, and a resumed run's reused parts
    come first: the files are the local run's byte for byte, and each part ahead of its turn
    waits on disk, not in memory (in a scratch folder, or among the parts kept to resume)."""
    from audit.engine.run import pipeline as suite_run
    from audit.engine.shared.scheduler import LocalScheduler

    class LastFirst(LocalScheduler):
        description = "last first"

        def map(self, task, entries, *args):
            yield from reversed(list(super().map(task, entries, *args)))

    saved = []
    save = suite_run.PartialStore.save
    monkeypatch.setattr(suite_run.PartialStore, "save",
                        lambda store, entry, part: saved.append((store.directory, entry.id))
                        or save(store, entry, part))
    procedures, settings = get_procedures("all"), AuditSettings.parse(**GRID)
    ids = [entry.id for entry in three_records]
    kept = tmp_path / "kept-parts"
    runs = (("local", dict(scheduler="local")),
            ("scratch", dict(scheduler=LastFirst())),
            ("kept", dict(scheduler=LastFirst(), partial_dir=kept)),
            # the first record's part lost: the others, reused, wait for it to be computed
            ("resumed", dict(scheduler="local", partial_dir=kept, resume=True)))
    summaries, folders = {}, {}
    for name, how in runs:
        if name == "resumed":
            for path in kept.glob("*.pkl"):
                if pickle.loads(path.read_bytes())["record"] == ids[0]:
                    path.unlink()
        saved.clear()
        folders[name] = tmp_path / name
        folders[name].mkdir()
        summaries[name] = suite_run.run_audit(procedures, three_records, settings,
                                                Runtime.parse(Runtime(jobs=2, **how)), folders[name])
        if name == "scratch":  # all but the first waited in a scratch folder, last first
            assert [record for _, record in saved] == ids[:0:-1]
            assert all(folder != kept for folder, _ in saved)
        if name == "kept":  # every part kept to resume, none saved twice
            assert saved == [(kept, record) for record in reversed(ids)]
    assert summaries["resumed"]["resumed"] == ids[1:]
    names = sorted(path.name for path in folders["local"].iterdir())
    for other in ("scratch", "kept", "resumed"):
        assert names == sorted(path.name for path in folders[other].iterdir())
        for name in names:
            local, theirs = ((folders[k] / name).read_bytes() for k in ("local", other))
            if name == "summary.json":
                local, theirs = (json.loads(text) for text in (local, theirs))
                for summary in (local, theirs):
                    del summary["scheduler"], summary["resumed"]
            assert local == theirs, (other, name)
