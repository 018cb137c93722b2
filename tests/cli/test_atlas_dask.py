"""``atlas build --scheduler tcp://HOST:PORT`` on a real Dask cluster (two single-threaded worker
processes, tests/cli/test_dask_cluster.py's): a worker killed while it computes a record's chunk
still gives the atlas a local build gives, array for array."""

import signal
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("distributed")

from test_dask_cluster import (ROOT, TIMEOUT_S, _busy_worker, _env, _stop,  # noqa: E402
                               _wait_for, cluster)  # noqa: F401  (cluster: a fixture)

#: Longer records (free motion 30 s), so that a kill lands while chunks are under way.
OPTIONS = ["--free-motion", "30", "--jobs", "1"]


def _build(manifest, folder, scheduler: str) -> subprocess.Popen:
    env = {**_env(folder.parent), "ROCKING_AUDIT_ATLAS_DIR": str(folder)}
    return subprocess.Popen([sys.executable, "-m", "audit", "atlas", "build", "--records",
                             str(manifest), "--scheduler", scheduler, *OPTIONS], cwd=ROOT,
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _arrays(folder) -> dict:
    (npz,) = folder.glob("*/atlas.npz")
    with np.load(npz) as data:
        return {name: data[name] for name in data.files}


@pytest.mark.slow
def test_atlas_survives_a_killed_worker(cluster, seed_manifest, tmp_path):
    local = _build(seed_manifest, tmp_path / "local", "local")
    assert local.wait(timeout=TIMEOUT_S) == 0, local.stderr.read()
    build = _build(seed_manifest, tmp_path / "dask", cluster.address)
    try:
        chunks = lambda: list((tmp_path / "dask").glob("*/parts/*.npz"))  # noqa: E731
        victim = _wait_for(lambda: chunks() and _busy_worker(cluster.client),
                           "a stored chunk while a worker computes a record", build)
        cluster.workers[victim].send_signal(signal.SIGKILL)
        assert cluster.workers[victim].wait(timeout=60) == -signal.SIGKILL
        assert build.wait(timeout=TIMEOUT_S) == 0, build.stderr.read()
    finally:
        _stop(build)
    assert f"the Dask cluster at {cluster.address}" in build.stderr.read()
    expected, got = _arrays(tmp_path / "local"), _arrays(tmp_path / "dask")
    assert expected.keys() == got.keys()
    for name in expected:
        np.testing.assert_array_equal(got[name], expected[name])
