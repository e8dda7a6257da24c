"""`radaraug demo`: a walkthrough of one capture through the paper's chain (the main job is `make demo`).

Writes RD images of the bundled recording, its noise-floor histogram against the fitted CalibratedDR,
``cdr.json`` and ``summary.json`` (docs/cli.md).
"""

from __future__ import annotations

from pathlib import Path

import torch

from radaraug.files import atomic_savefig, atomic_write_json


def run_demo(out_dir: Path, *, capture: str | Path | None = None) -> dict:
    """Run the demo and return its summary dict.

    Args:
        out_dir: folder for the outputs (created).
        capture: capture to use instead of the bundled recording.
    """
    from radaraug._optional import pyplot

    plt = pyplot()

    from radaraug.io import open_capture, sample_recording_path
    from radaraug.transforms import (
        CalibratedDR,
        ClipNormalize,
        Colormap,
        CombineRx,
        RangeDoppler,
        Resize,
        ToDecibels,
    )
    from radaraug.transforms.summary import summarize_capture
    from radaraug.units import DB_CONVENTION

    out_dir.mkdir(parents=True, exist_ok=True)
    path = Path(capture) if capture is not None else sample_recording_path()
    print(f"[demo] capture: {path}")
    with open_capture(path) as reader:
        summary = summarize_capture(reader)
        frames = reader.read()
        cfg = reader.config
    print(f"[demo] {cfg.describe()}")

    cdr = CalibratedDR.fit(frames, config=cfg)
    cdr.save(out_dir / "cdr.json")
    print(f"[demo] CalibratedDR fitted: m_t = {cdr.mean_db:.2f} dB, s_t = {cdr.std_db:.2f} dB")

    db = ToDecibels()(RangeDoppler()(frames))  # (F, rx, range, doppler): what CDR was fitted on
    combined = CombineRx("mean_power", db=True)(db)  # (F, 1, range, doppler)
    clip = ClipNormalize.estimate(combined)
    to_image = torch.nn.Sequential(clip, Colormap("viridis"), Resize((224, 224)))
    images = []
    for i in torch.linspace(0, frames.shape[0] - 1, 4).round().long().tolist():
        img = to_image(combined[i])  # (3, 224, 224)
        png = out_dir / f"rd_frame{i:04d}.png"
        plt.imsave(png, img.clamp(0, 1).permute(1, 2, 0).numpy())
        images.append(png.name)

    values = db.flatten()
    gen = torch.Generator().manual_seed(0)
    model = torch.randn(values.numel(), generator=gen, dtype=values.dtype) * cdr.std_db + cdr.mean_db
    fig, ax = plt.subplots(figsize=(6, 3.5), dpi=120)
    bins = torch.linspace(float(values.min()), float(values.max()), 120).tolist()
    ax.hist(values.numpy(), bins=bins, density=True, alpha=0.6, label="capture RD cells")
    ax.hist(model.numpy(), bins=bins, density=True, histtype="step", lw=1.5,
            label=f"CDR model N({cdr.mean_db:.1f}, {cdr.std_db:.1f}^2)")
    ax.set_xlabel("RD magnitude [dBFS]")
    ax.set_ylabel("density")
    ax.set_title("Noise-floor histogram")
    ax.legend(fontsize=8)
    fig.text(0.01, 0.01, DB_CONVENTION, fontsize=5)
    fig.tight_layout()
    atomic_savefig(fig, out_dir / "noise_floor_histogram.png")
    plt.close(fig)

    result = {
        "capture": str(path),
        "cdr": {"mean_db": cdr.mean_db, "std_db": cdr.std_db, "file": "cdr.json"},
        "clip_range_db": [clip.vmin, clip.vmax],
        "images": images,
        "histogram": "noise_floor_histogram.png",
        "info": summary,
        "db_convention": DB_CONVENTION,
    }
    atomic_write_json(out_dir / "summary.json", result, newline=False, indent=2)
    print(f"[demo] wrote {len(images)} RD images, noise_floor_histogram.png, cdr.json, summary.json to {out_dir}")
    return result
