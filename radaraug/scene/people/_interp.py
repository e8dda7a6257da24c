"""Catmull-Rom (cubic Hermite) interpolation of sampled trajectories, with exact velocities.

Used for motion-capture frames and animated mesh vertices: positions are C1-continuous between
frames, and the velocity is the derivative of the interpolant (no stair-steps at frame rate).
"""

from __future__ import annotations

import torch


class FrameTrack:
    """A trajectory sampled at a constant frame rate, looped or clamped.

    Args:
        frames: ``(F, ..., 3)`` positions at ``k * frame_time_s``.
        frame_time_s: seconds per frame.
        loop: repeat the clip with period ``(F - 1) * frame_time_s`` (frame ``F-1`` meets frame
            0 of the next repetition, shifted by ``loop_offset``); otherwise hold the first/last
            frame (zero velocity) outside the clip.
        loop_offset: ``(3,)`` displacement added per repetition (root motion), or None.
    """

    def __init__(self, frames: torch.Tensor, frame_time_s: float, loop: bool,
                 loop_offset: torch.Tensor | None = None) -> None:
        self.frame_time_s = float(frame_time_s)
        self.loop = bool(loop)
        self.num_frames = int(frames.shape[0])
        self.period_s = (self.num_frames - 1) * self.frame_time_s
        shift = torch.zeros(3, dtype=frames.dtype) if loop_offset is None else loop_offset.to(frames)
        if self.num_frames == 1:
            ext = frames.expand(4, *frames.shape[1:])
        elif self.loop:
            ext = torch.cat([frames[-2:-1] - shift, frames, frames[1:2] + shift])
        else:
            ext = torch.cat([frames[:1], frames, frames[-1:]])
        self._ext = ext.contiguous()
        self._shift = shift
        self._cache: dict[tuple[torch.device, torch.dtype], tuple[torch.Tensor, torch.Tensor]] = {}

    def _tables(self, device: torch.device, dtype: torch.dtype) -> tuple[torch.Tensor, torch.Tensor]:
        key = (device, dtype)
        if key not in self._cache:
            self._cache[key] = (self._ext.to(device=device, dtype=dtype), self._shift.to(device=device, dtype=dtype))
        return self._cache[key]

    def __call__(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Positions and velocities at ``t`` ``(T,)``: both ``(T, ..., 3)``."""
        ext, shift = self._tables(t.device, t.dtype)
        extra = (1,) * (ext.ndim - 1)
        if self.num_frames == 1:
            pos = ext[1].expand(t.shape[0], *ext.shape[1:])
            return pos.clone(), torch.zeros_like(pos)
        if self.loop:
            reps = torch.floor(t / self.period_s)
            tau = t - reps * self.period_s
            inside = torch.ones_like(t, dtype=torch.bool)
        else:
            reps = torch.zeros_like(t)
            inside = (t >= 0) & (t <= self.period_s)
            tau = t.clamp(0.0, self.period_s)
        x = tau / self.frame_time_s
        i = x.floor().long().clamp(0, self.num_frames - 2)
        s = (x - i.to(x.dtype)).view(-1, *extra)
        p0, p1, p2, p3 = ext[i], ext[i + 1], ext[i + 2], ext[i + 3]
        m1, m2 = 0.5 * (p2 - p0), 0.5 * (p3 - p1)
        s2, s3 = s * s, s * s * s
        pos = (2 * s3 - 3 * s2 + 1) * p1 + (s3 - 2 * s2 + s) * m1 + (-2 * s3 + 3 * s2) * p2 + (s3 - s2) * m2
        vel = ((6 * s2 - 6 * s) * p1 + (3 * s2 - 4 * s + 1) * m1 + (-6 * s2 + 6 * s) * p2 + (3 * s2 - 2 * s) * m2)
        vel = vel / self.frame_time_s * inside.view(-1, *extra).to(vel.dtype)
        pos = pos + reps.view(-1, *extra) * shift
        return pos, vel
