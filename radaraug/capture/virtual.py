"""`VirtualSensor`: the digital twin as a live radar device, for tests and for users without a board.

Frame ``k`` equals frame ``k`` of ``radaraug simulate`` with the same settings. See ``docs/capture.md``.
"""

from __future__ import annotations

import os
import time
from typing import TYPE_CHECKING, Any

import torch

from radaraug.capture.base import Frame, RadarDevice
from radaraug.config import RadarConfig
from radaraug.io.blocks import BLOCK_FRAMES, block_of
from radaraug.scene.scene import Scene

if TYPE_CHECKING:
    from radaraug.sim.twin import DigitalTwin



class VirtualSensor(RadarDevice):
    """The digital twin as a :class:`RadarDevice`.

    Args:
        scene: a :class:`~radaraug.scene.scene.Scene`, a scene file or a built-in scene name.
        config: the radar config to simulate (default: the scene's).
        profile: a fitted twin profile (object, JSON path or dict from ``radaraug diagnose``).
        seed: noise seed; frame ``k`` depends only on the settings and ``(seed, k)``.
        realtime: frames at the sensor's frame rate (late, never dropped, if the twin is slower) or at once.
        device: torch device the twin simulates on (frames are returned on the CPU).
        twin_options: more keyword arguments of :class:`~radaraug.sim.twin.DigitalTwin`.

    Raises:
        SceneError: unknown or invalid scene. ConfigError: an invalid config.
    """

    def __init__(
        self,
        scene: Scene | str | os.PathLike = "corridor",
        *,
        config: RadarConfig | None = None,
        profile: Any = None,
        seed: int = 0,
        realtime: bool = True,
        device: str = "cpu",
        twin_options: dict[str, Any] | None = None,
    ) -> None:
        from radaraug.errors import ConfigError

        super().__init__()
        self.scene = Scene.load(scene)
        if config is not None and not isinstance(config, RadarConfig):
            raise ConfigError(f"VirtualSensor: config must be a RadarConfig, got {type(config).__name__}")
        if isinstance(seed, bool) or not isinstance(seed, int):
            raise ConfigError(f"VirtualSensor: seed must be an integer, got {seed!r}")
        self._config = config or self.scene.config
        self.profile = profile
        self.seed = seed
        self.realtime = bool(realtime)
        self.device = device
        self.twin_options = dict(twin_options or {})
        self._twin: DigitalTwin | None = None
        self._block: tuple[int, torch.Tensor] | None = None
        self._next = 0
        self._t0 = 0.0
        self.late_s = 0.0
        """How late the last frame came against real time (realtime mode; 0 when on time)."""

    @property
    def config(self) -> RadarConfig:
        """The simulated radar configuration (the scene's unless one was given)."""
        return self._config

    @property
    def info(self) -> dict[str, Any]:
        """``kind`` ``"virtual"``, ``name`` and the settings a frame depends on (scene, seed, profile...)."""
        profile = self.profile
        if profile is not None:
            profile = str(profile) if isinstance(profile, (str, os.PathLike)) else "given as an object"
        return {"kind": "virtual", "name": f"virtual sensor ({self.scene.name})", "scene": self.scene.name,
                "seed": self.seed, "realtime": self.realtime, "block_frames": BLOCK_FRAMES, "profile": profile}

    def frames(self, start: int, stop: int) -> torch.Tensor:
        """Frames ``[start, stop)`` of the stream, ``(n, rx, chirps, samples)`` SDK floats, without pacing."""
        self._ensure_twin()
        out = [self._frame(k) for k in range(start, stop)]
        return torch.stack(out) if out else torch.empty(0, *self._shape())

    # ------------------------------------------------------------------ RadarDevice
    def _open(self) -> None:
        self._ensure_twin()
        # The room's trace and the first block before the clock starts, as a board is
        # configured before its first frame.
        self._frame(0)
        self._next = 0
        self.late_s = 0.0
        self._t0 = time.monotonic()

    def _read(self) -> Frame:
        k = self._next
        data = self._frame(k)
        period = self.config.frame_repetition_time_s
        if self.realtime:
            ready = self._t0 + k * period + self.config.num_chirps_per_frame * self.config.chirp_repetition_time_s
            wait = ready - time.monotonic()
            if wait > 0:
                time.sleep(wait)
            self.late_s = max(0.0, -wait)
        self._next = k + 1
        return Frame(data, k * period, k)

    def _close(self) -> None:
        self._block = None  # the twin (and its traced room) stays: a restart is quick

    # ------------------------------------------------------------------ simulation
    def _shape(self) -> tuple[int, int, int]:
        c = self.config
        return c.frame_shape

    def _ensure_twin(self) -> None:
        if self._twin is None:
            from radaraug.sim.twin import DigitalTwin

            options = dict(self.twin_options)
            if self.profile is not None:
                options["profile"] = self.profile
            self._twin = DigitalTwin(self.scene, config=self.config, device=self.device, **options)

    def _frame(self, k: int) -> torch.Tensor:
        block = block_of(k)
        if self._block is None or self._block[0] != block:
            self._block = (block, self._simulate_block(block))
        return self._block[1][k - block * BLOCK_FRAMES]

    def _simulate_block(self, block: int) -> torch.Tensor:
        from radaraug.sim.offline import simulate_frames

        twin = self._twin
        assert twin is not None
        first = block * BLOCK_FRAMES
        with torch.no_grad():
            _, x = simulate_frames(twin, self.scene.people, first, first + BLOCK_FRAMES, self.seed, block,
                                   self.device)
        return x.detach().to("cpu", torch.float32).contiguous()

    def __repr__(self) -> str:
        mode = "realtime" if self.realtime else "fast"
        return f"VirtualSensor({self.scene.name!r}, seed={self.seed}, {mode})"
