"""flexrig.sweep(..., client=...) on a Dask LocalCluster of 2 worker processes: the same table as
the local sweep."""

import os

import pandas as pd
import pytest

import flexrig
from conftest import missing

try:
    from dask.distributed import Client, LocalCluster
except ImportError:  # pragma: no cover
    Client = LocalCluster = None

GRID = {
    "operator.start.release_angle_deg": "15:45:4",
    "robot.design": ["cj", "cl"],
    "robot.payload_kg": [0.2, -1.0],
    "operator.start.from": "contact",
    "stop.at": "peak",
}


@pytest.fixture(scope="module")
def client():
    if LocalCluster is None:
        missing("dask.distributed")
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(cluster)
    client.wait_for_workers(2, timeout=120)
    yield client
    client.close()
    cluster.close()


def test_a_dask_sweep_is_identical_to_the_local_one(client):
    local = flexrig.sweep("cj_iron", GRID)
    assert len(client.nthreads()) == 2
    for chunk_size in (None, 1, 5, 100):
        remote = flexrig.sweep("cj_iron", GRID, client=client, chunk_size=chunk_size)
        pd.testing.assert_frame_equal(local, remote)
    assert (local["status"] == "error").sum() == 8


def test_both_worker_processes_take_part(client):
    pids = set(client.run(os.getpid).values())
    assert len(pids) == 2 and os.getpid() not in pids
    text = flexrig.scene_text("cj_iron", **{"operator.start.from": "contact", "stop.at": "peak"})
    native = flexrig.Sweep(text, [("robot.payload_kg", "0.1:0.5:16")])
    futures = client.map(flexrig._run_chunk, [[i] for i in range(16)], sweep=native, pure=False)
    parts = client.gather(futures)
    assert sorted(int(p["index"][0]) for p in parts) == list(range(16))
    workers = {w for addresses in client.who_has(futures).values() for w in addresses}
    assert len(workers) == 2, workers
