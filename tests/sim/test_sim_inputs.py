"""Bad input to the simulation entry points, per-frame time-locked effects, and resume safety."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.cli import main
from radaraug.errors import CaptureError, ConfigError, InputTensorError, SceneError
from radaraug.scene.scene import Scene
from radaraug.sensor import FMCWReceiver
from radaraug.sensor.effects import SpurTone
from radaraug.sim import offline
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.twin import DigitalTwin

FAST = {"tracer_options": {"rays": 48}}


def test_batched_twin_frames_keep_their_own_start_time() -> None:
    """A block simulated at once equals its frames simulated one by one (time-locked spur)."""
    scene = Scene.builtin("corridor")
    cfg = scene.config
    rx = FMCWReceiver(cfg, effects=[SpurTone(freq_Hz=123_456.7, amplitude_counts=5.0)])
    shape = (cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    twin = DigitalTwin(scene, receiver=rx, static_signal=torch.zeros(shape), tracer_options={"rays": 8})
    times = twin.frame_times(range(3))
    batch = twin.simulate(None, times, generators=torch.Generator().manual_seed(0))
    one_by_one = twin.simulate(None, times, generators=[torch.Generator().manual_seed(k) for k in range(3)])
    torch.testing.assert_close(batch, one_by_one, rtol=0, atol=1e-6)
    assert not torch.allclose(batch[0], batch[1])
    with pytest.raises(InputTensorError, match="one generator per frame"):
        twin.simulate(None, times, generators=[torch.Generator()])


def test_dataset_rejects_bad_arguments_with_config_errors() -> None:
    with pytest.raises(ConfigError, match="target"):
        SimulatedRadarDataset("corridor", target="speed")
    with pytest.raises(ConfigError, match="frames_per_item"):
        SimulatedRadarDataset("corridor", frames_per_item=0)
    with pytest.raises(SceneError, match="unknown built-in scene"):
        SimulatedRadarDataset("no_such_scene")


def test_scene_names_win_over_a_folder_of_the_same_name(tmp_path, monkeypatch) -> None:
    (tmp_path / "corridor").mkdir()
    monkeypatch.chdir(tmp_path)
    assert Scene.load("corridor").name == Scene.builtin("corridor").name


def test_resume_refuses_files_of_another_job_or_not_ours(tmp_path) -> None:
    scene = Scene.builtin("corridor")
    out = tmp_path / "run.h5"
    offline.simulate_capture(scene, out, frames=16, seed=1, progress=False, twin_options=FAST)
    # Fewer frames than the file holds: refused, not "finished" with 16 frames in an 8-frame job.
    with pytest.raises(CaptureError, match="not made by this job"):
        offline.simulate_capture(scene, out, frames=8, seed=1, progress=False, twin_options=FAST)
    # Another device type draws other noise: not resumed there either (refused before any CUDA use).
    with pytest.raises(CaptureError, match="not made by this job"):
        offline.simulate_capture(scene, out, frames=16, seed=1, device="cuda", progress=False)
    # The same job is finished and not redone.
    assert offline.simulate_capture(scene, out, frames=16, seed=1, progress=False)["simulated"] == 0
    # A file that is not a simulated capture is never overwritten.
    other = tmp_path / "notes.h5"
    other.write_text("keep me")
    with pytest.raises(CaptureError, match="not made by this job"):
        offline.simulate_capture(scene, other, frames=16, seed=1, progress=False)
    assert other.read_text() == "keep me"


def test_a_job_killed_before_its_first_frame_starts_again(tmp_path) -> None:
    from radaraug.io import CaptureWriter

    scene = Scene.builtin("corridor")
    out = tmp_path / "run.h5"
    job = {"scene": offline._jsonable(scene.to_dict()), "seed": 1, "frames_total": 16, "shard": [0, 1],
           "first_frame": 0, "block_frames": offline.BLOCK_FRAMES, "device_type": "cpu"}
    CaptureWriter(out, scene.config, labels_schema={"count": "int64", "occupancy": "int64"},
                  attrs={"simulation": job}).close()  # created, no frame yet
    res = offline.simulate_capture(scene, out, frames=16, seed=1, progress=False, twin_options=FAST)
    assert res["simulated"] == 16


def test_simulate_capture_python_api_validates() -> None:
    with pytest.raises(ConfigError, match="frames"):
        offline.simulate_capture("corridor", "x.h5", frames=0)
    with pytest.raises(ConfigError, match="shard"):
        offline.simulate_capture("corridor", "x.h5", frames=4, shard=(2, 2))
    with pytest.raises(ConfigError, match="device"):
        offline.simulate_capture("corridor", "x.h5", frames=4, device="nonsense")
    with pytest.raises(SceneError):
        offline.simulate_capture("no_such_scene", "x.h5", frames=4)


@pytest.mark.parametrize("argv, message", [
    (["trace", "no_such_scene"], "unknown built-in scene"),
    (["trace", "missing.yaml"], "cannot be read"),
    (["trace", "corridor", "--time", "nan"], "--time must be a finite"),
    (["trace", "corridor", "--rays", "0"], "ray"),
    (["simulate", "no_such_scene", "--frames", "2", "-o", "x.h5"], "unknown built-in scene"),
    (["simulate", "corridor", "--frames", "0", "-o", "x.h5"], "--frames must be >= 1"),
    (["simulate", "corridor", "--frames", "2", "-o", "x.h5", "--shard", "2/2"], "--shard"),
    (["simulate", "corridor", "--frames", "2", "-o", "x.h5", "--shard", "a/b"], "--shard"),
])
def test_cli_bad_input_is_one_line_error(argv, message, tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 3
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and message in err and "\n" not in err
    assert not (tmp_path / "x.h5").exists()


@pytest.mark.skipif(torch.cuda.is_available(), reason="checks the message on a machine without CUDA")
def test_cli_cuda_without_a_gpu_is_one_line_error(tmp_path, capsys) -> None:
    assert main(["simulate", "corridor", "--frames", "2", "-o", str(tmp_path / "x.h5"), "--accelerator", "cuda"]) == 3
    assert "CUDA is not available" in capsys.readouterr().err


def test_cli_trace_json_is_valid(capsys) -> None:
    import json

    assert main(["trace", "corridor", "--rays", "8", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["num_paths"] > 0 and math.isfinite(data["time_s"])
