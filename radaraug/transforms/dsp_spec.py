"""DSP chain descriptions: expand composite steps so equivalent chains compare equal."""

from __future__ import annotations

from typing import Any

from torch import nn


def expand_step(spec: dict[str, Any]) -> list[dict[str, Any]]:
    """The primitive steps of one chain step (``RangeDoppler`` -> mean removal, MTI, FFTs)."""
    if spec.get("name") != "RangeDoppler":
        return [dict(spec)]
    steps: list[dict[str, Any]] = []
    if spec.get("remove_mean", True):
        steps.append({"name": "RemoveMean"})
    if spec.get("static_clutter", False):
        steps.append({"name": "StaticClutterRemoval"})
    steps.append({"name": "RangeFFT", "window": spec.get("range_window", "hann")})
    steps.append({"name": "DopplerFFT", "window": spec.get("doppler_window", "hann")})
    return steps


def canonical_chain(specs: list[dict[str, Any]] | None) -> list[dict[str, Any]]:
    """A chain's deterministic DSP as primitive step specs; random steps (augmentations) left out."""
    out: list[dict[str, Any]] = []
    for spec in specs or []:
        if not spec.get("random", False):
            out.extend(expand_step(spec))
    return out


def describe_chain(specs: list[dict[str, Any]] | None) -> str:
    """``RemoveMean -> RangeFFT(window=hann) -> ...`` for messages."""
    parts = []
    for s in canonical_chain(specs):
        args = ", ".join(f"{k}={v}" for k, v in s.items() if k != "name")
        parts.append(f"{s['name']}({args})" if args else str(s["name"]))
    return " -> ".join(parts) if parts else "(nothing)"


def doppler_window_of(specs: list[dict[str, Any]] | None) -> str | None:
    """The Doppler window named in a chain, if any."""
    for s in canonical_chain(specs):
        if s.get("name") == "DopplerFFT":
            return str(s.get("window"))
    return None


def chain_of(pipeline: Any) -> list[dict[str, Any]] | None:
    """A pipeline's chain specs, or None when a step cannot be described.

    A pipeline is a radaraug transform or compose, or a list / ``nn.Sequential`` / torchvision ``Compose`` of them.
    """
    spec_fn = getattr(pipeline, "chain_spec", None)
    if callable(spec_fn):
        spec = spec_fn()
        return list(spec) if isinstance(spec, list) else [spec]
    is_list = isinstance(pipeline, (list, tuple, nn.ModuleList, nn.Sequential))
    steps = pipeline if is_list else getattr(pipeline, "transforms", None)  # else a torchvision Compose
    if steps is None:
        return None
    out: list[dict[str, Any]] = []
    for step in steps:
        sub = chain_of(step)
        if sub is None:
            return None
        out.extend(sub)
    return out
