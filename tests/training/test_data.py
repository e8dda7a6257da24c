"""RadarDataModule on captures the twin did not make: Infineon folders, per-file labels, errors."""

import pytest
import torch
from data import point_scatterer_frames, small_config

from radaraug.errors import ConfigError
from radaraug.io import write_capture, write_infineon_recording
from radaraug.training import RadarDataModule

SMALL = {"train_items": 6, "val_items": 0, "tracer_rays": 16, "image_size": [32, 16], "randomization": False,
         "progress": False, "batch_size": 3}


def test_infineon_folders_with_a_count_per_file(tmp_path):
    cfg = small_config()
    cal = write_infineon_recording(tmp_path / "empty", point_scatterer_frames(cfg, 0, 8, 1), cfg)
    walk = write_infineon_recording(tmp_path / "walk2", point_scatterer_frames(cfg, 2, 5, 2), cfg)
    dm = RadarDataModule(task="counting", method="cdr", calibration=str(cal), cache_dir=str(tmp_path / "c"),
                         test=[{"path": str(walk), "count": 2}], out_dir=str(tmp_path / "run"), **SMALL)
    dm.setup("fit")
    x, y = next(iter(dm.test_dataloader()))
    assert x.shape == (3, cfg.num_rx, cfg.num_range_bins, cfg.num_chirps_per_frame)  # per-RX dB maps
    assert y.tolist() == [2, 2, 2]
    img, _ = dm.on_after_batch_transfer((x, y), 0)
    assert img.shape == (3, 3, 32, 16) and 0 <= float(img.min()) and float(img.max()) <= 1
    # occupancy labels the same file "occupied"
    dm2 = RadarDataModule(task="occupancy", method="rt", calibration=str(cal), cache_dir=str(tmp_path / "c"),
                          test=[{"path": str(walk), "count": 2}], **SMALL)
    dm2.setup("fit")
    assert {int(v) for _, v in dm2._test} == {1}
    assert (tmp_path / "run" / "clip_range.json").is_file()


def test_config_mismatch_and_bad_entries_are_clear_errors(tmp_path):
    cfg = small_config()
    cal = write_capture(tmp_path / "empty.h5", point_scatterer_frames(cfg, 0, 6, 1), cfg)
    other = cfg.replace(if_gain_dB=48)
    walk = write_capture(tmp_path / "walk.h5", point_scatterer_frames(other, 1, 3, 2), other)
    dm = RadarDataModule(task="occupancy", method="rt", calibration=str(cal), test=[{"path": str(walk), "count": 1}],
                         cache_dir=str(tmp_path / "c"), **SMALL)
    with pytest.raises(ConfigError, match="walk.h5.*another radar config"):
        dm.setup("fit")
    bad = RadarDataModule(task="occupancy", method="rt", calibration=str(cal), test=["walk.h5"],
                          cache_dir=str(tmp_path / "c"), **SMALL)
    with pytest.raises(ConfigError, match="test\\[0\\]"):
        bad.setup("fit")
    with pytest.raises(ConfigError, match="task"):
        RadarDataModule(task="segmentation")
    with pytest.raises(ConfigError, match="needs data.calibration"):
        RadarDataModule(task="occupancy", method="cdr", test=[{"path": str(cal), "count": 0}],
                        calibrate_noise=False, cache_dir=str(tmp_path / "c"), **SMALL).setup("fit")


def test_dr_only_on_simulated_splits(tmp_path, captures):
    cal, tests = captures
    dm = RadarDataModule(task="occupancy", method="randomdr", calibration=str(cal),
                         test=[{"path": str(tests[0][0]), "count": 0}], cache_dir=str(tmp_path / "c"), **SMALL)
    dm.setup("fit")
    x = torch.full((2, 3, 32, 16), -200.0)  # far below any floor: DR would lift it

    class T:  # the trainer states the hook reads
        def __init__(self, **kw):
            self.training = self.validating = self.sanity_checking = False
            self.__dict__.update(kw)

    dm.trainer = T(testing=True)
    test_img, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    dm.trainer = T(training=True)
    train_img, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    assert torch.equal(test_img, dm.image(x)) and not torch.equal(train_img, test_img)
    # test_dr: the test captures go through the run's DR too (opt-in, not the paper's protocol)
    dm.hparams["test_dr"] = True
    dm.trainer, dm.image = T(testing=True), torch.nn.Identity()  # the maps before clipping
    lifted, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    assert bool((lifted > -150).all())
    assert RadarDataModule().hparams["test_dr"] is False
