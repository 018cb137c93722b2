"""A real Dask cluster of separate processes (``dask scheduler``, two ``dask worker``) reached by
``--scheduler tcp://HOST:PORT``: a worker killed mid-run, or the driver killed mid-run and the
run resumed, still gives the local run's results.csv byte for byte."""

import json
import os
import pickle
import re
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")

from audit.engine.shared.partial import PARTIAL_DIR, kept_parts  # noqa: E402

#: End to end: a cluster of processes, killed and resumed.
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
#: About 1–2 s per record on one thread, so that a kill lands while records are under way.
GRID = ["--alpha", "3,6,9", "--size", "0.5:8:0.01", "--free-motion", "30", "--jobs", "1"]
#: Generous: the machine may be loaded; a condition that never comes fails, it never skips.
TIMEOUT_S = 240


def _env(tmp_path: Path) -> dict:
    """This checkout first on the path; Dask's scratch files under ``tmp_path``."""
    return {**os.environ, "DASK_TEMPORARY_DIRECTORY": str(tmp_path),
            "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                        os.environ.get("PYTHONPATH", "")]))}


def _spawn(args, log: Path) -> subprocess.Popen:
    """``python -m ARGS`` with this interpreter, output to ``log`` (a file, not a pipe:
    nobody reads a pipe while it runs, and a full one would block the process)."""
    with open(log, "w") as file:
        return subprocess.Popen([sys.executable, "-m", *args], cwd=ROOT, env=_env(log.parent),
                                stdout=file, stderr=subprocess.STDOUT)


def _wait_for(condition, what: str, *alive: subprocess.Popen):
    """Poll ``condition()`` until it is truthy and return it; fail if a process in ``alive``
    ends first or nothing comes within TIMEOUT_S."""
    deadline = time.monotonic() + TIMEOUT_S
    while not (value := condition()):
        for process in alive:
            assert process.poll() is None, f"{process.args} ended while waiting for {what}"
        assert time.monotonic() < deadline, f"no {what} within {TIMEOUT_S} s"
        time.sleep(0.05)
    return value


def _stop(process: subprocess.Popen) -> None:
    if process.poll() is None:
        process.kill()
    process.wait(timeout=60)


@dataclass
class Cluster:
    address: str  # tcp://127.0.0.1:PORT of the scheduler
    workers: dict  # worker name → its `dask worker` process
    client: object  # the test's own distributed.Client, to see what the scheduler sees


def _scheduler_address(scheduler_file: Path):
    try:
        return json.loads(scheduler_file.read_text())["address"]
    except (OSError, ValueError, KeyError):  # not written yet, or half written
        return None


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and two single-threaded workers, each its own process, as an operator
    starts them; all stopped afterwards."""
    processes = []
    client = None
    try:
        scheduler_file = tmp_path / "scheduler.json"
        # free ports picked by the scheduler; its dashboard too (--no-dashboard still binds :8787)
        scheduler = _spawn(["dask", "scheduler", "--host", "127.0.0.1", "--port", "0",
                            "--dashboard-address", "127.0.0.1:0",
                            "--scheduler-file", str(scheduler_file)],
                           tmp_path / "scheduler.log")
        processes.append(scheduler)
        address = _wait_for(lambda: _scheduler_address(scheduler_file), "scheduler address",
                            scheduler)
        workers = {}
        for name in ("worker-a", "worker-b"):
            # --no-nanny: the process started here is the worker itself, so SIGKILL loses it
            # (a nanny would start a new one, or be killed and leave its worker running)
            workers[name] = _spawn(["dask", "worker", address, "--nthreads", "1",
                                    "--nworkers", "1", "--no-nanny", "--name", name,
                                    "--no-dashboard", "--local-directory", str(tmp_path / name)],
                                   tmp_path / f"{name}.log")
            processes.append(workers[name])
        client = distributed.Client(address, timeout="60s")
        client.wait_for_workers(2, timeout=TIMEOUT_S)
        yield Cluster(address, workers, client)
    finally:
        if client is not None:
            client.close()
        for process in reversed(processes):
            _stop(process)


def _run(manifest, out: Path, scheduler: str, *extra) -> subprocess.Popen:
    """``python -m audit run all`` on the seed records; stdout in OUT.stdout, stderr in OUT.stderr."""
    with open(f"{out}.stdout", "w") as stdout, open(f"{out}.stderr", "w") as stderr:
        return subprocess.Popen([sys.executable, "-m", "audit", "run", "all", "--records",
                                 str(manifest), "--scheduler", scheduler, "--out", str(out),
                                 *GRID, *extra],
                                cwd=ROOT, env=_env(out.parent), stdout=stdout, stderr=stderr)


def _finished(process: subprocess.Popen, out: Path) -> tuple[str, str]:
    """Wait for a run to end with exit status 0; its stdout and stderr."""
    process.wait(timeout=TIMEOUT_S)
    stdout, stderr = Path(f"{out}.stdout").read_text(), Path(f"{out}.stderr").read_text()
    assert process.returncode == 0, stderr
    return stdout, stderr


def _stored_count(out: Path) -> int:
    """Parts complete in OUT/.partial (a write under way has a temporary name)."""
    return len(kept_parts(out / PARTIAL_DIR))


def _stored_records(out: Path) -> list[str]:
    """Ids of the records whose part is complete in OUT/.partial."""
    records = []
    for path in kept_parts(out / PARTIAL_DIR):
        with open(path, "rb") as file:
            records.append(pickle.load(file)["record"])
    return sorted(records)


def _computed_records(stderr: str) -> list[str]:
    # progress lines: "[  1.2 s] record 3/7: ID (computed in 0.8 s)"
    return sorted(re.findall(r"record \d+/\d+: (\S+) \(computed", stderr))


@pytest.fixture(scope="module")
def local_results(seed_manifest, tmp_path_factory) -> bytes:
    """results.csv of the same command with ``--scheduler local``."""
    out = tmp_path_factory.mktemp("local") / "out"
    _finished(_run(seed_manifest, out, "local"), out)
    return (out / "results.csv").read_bytes()


def _busy_worker(client) -> str | None:
    """Name of a worker the scheduler has given a record to, or None."""
    names = {address: info["name"] for address, info in client.scheduler_info()["workers"].items()}
    return next((names[address] for address, keys in client.processing().items()
                 if keys and address in names), None)


@pytest.fixture(scope="module")
def record_ids(seed_suite) -> list[str]:
    return sorted(entry.id for entry in seed_suite)


def test_run_survives_a_killed_worker(cluster, seed_manifest, record_ids, local_results,
                                      tmp_path):
    out = tmp_path / "out"
    run = _run(seed_manifest, out, cluster.address)
    try:
        # a record is done and one is under way on a worker: that worker is lost
        victim = _wait_for(lambda: _stored_count(out) and _busy_worker(cluster.client),
                           "a stored part while a worker computes a record", run)
        assert run.poll() is None and _stored_count(out) < len(record_ids), "run ended first"
        cluster.workers[victim].send_signal(signal.SIGKILL)
        assert cluster.workers[victim].wait(timeout=60) == -signal.SIGKILL
        stdout, stderr = _finished(run, out)
    finally:
        _stop(run)
    assert f"the Dask cluster at {cluster.address} (2 workers)" in stdout
    # the lost worker's records were computed again on the other one, each reported once
    assert [info["name"] for info in cluster.client.scheduler_info()["workers"].values()] == [
        next(name for name in cluster.workers if name != victim)]
    assert _computed_records(stderr) == record_ids
    assert (out / "results.csv").read_bytes() == local_results
    assert not (out / PARTIAL_DIR).exists()


def test_resume_after_the_driver_is_killed(cluster, seed_manifest, seed_suite, record_ids,
                                           local_results, tmp_path):
    out = tmp_path / "out"
    crashed = _run(seed_manifest, out, cluster.address)
    # one part more than the missing records (done at once): one record with a file at least
    at_least = sum(entry.missing for entry in seed_suite) + 1
    try:
        _wait_for(lambda: _stored_count(out) >= at_least, f"{at_least} stored parts", crashed)
        crashed.send_signal(signal.SIGKILL)
        assert crashed.wait(timeout=60) == -signal.SIGKILL
    finally:
        _stop(crashed)
    kept = _stored_records(out)
    assert at_least <= len(kept) < len(record_ids), "the run ended before the kill"
    assert not (out / "results.csv").exists()

    # the same cluster, whose workers may still be finishing the dead driver's tasks
    stdout, stderr = _finished(_run(seed_manifest, out, cluster.address, "--resume"), out)
    assert f"reused {len(kept)} records of an interrupted run" in stdout
    reused = re.findall(r"record \d+/\d+: (\S+) \(reused from an interrupted run\)", stderr)
    assert sorted(reused) == kept
    assert _computed_records(stderr) == sorted(set(record_ids) - set(kept))
    assert sorted(json.loads((out / "summary.json").read_text())["resumed"]) == kept
    assert (out / "results.csv").read_bytes() == local_results
    assert not (out / PARTIAL_DIR).exists()
