"""BVH motion-capture files: a small parser and vectorized forward kinematics.

BVH conventions: a joint's world transform is its parent's transform, then a translation by
``OFFSET`` (plus any position channels), then the rotation channels applied in the order
listed (``Zrotation Xrotation Yrotation`` means ``R = Rz Rx Ry``, intrinsic), in degrees. The
file's up axis is ``+Y`` (as in CMU, Mixamo and most exporters).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import torch

from radaraug.errors import SceneError
from radaraug.scene.people import _rotations as rot

_CHANNELS = ("Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation")


@dataclass
class BVHSkeleton:
    """A parsed BVH file.

    Attributes:
        names: joint names in file order; end sites are named ``<parent>_end``.
        parents: parent index per joint (-1 for the root).
        offsets: ``(J, 3)`` float64 offsets in file units.
        channels: channel names per joint (empty for end sites).
        motion: ``(F, C)`` float64 channel values per frame.
        frame_time_s: seconds per frame.
        path: the source file (for messages).
    """

    names: list[str]
    parents: list[int]
    offsets: torch.Tensor
    channels: list[list[str]]
    motion: torch.Tensor
    frame_time_s: float
    path: str = "<bvh>"
    _channel_start: list[int] = field(default_factory=list)

    @property
    def num_frames(self) -> int:
        """Number of motion frames ``F``."""
        return int(self.motion.shape[0])

    def rest_positions(self) -> torch.Tensor:
        """``(J, 3)`` joint positions with all channels zero (file units, file axes)."""
        pos = torch.zeros(len(self.names), 3, dtype=torch.float64)
        for j, p in enumerate(self.parents):
            pos[j] = self.offsets[j] if p < 0 else pos[p] + self.offsets[j]
        return pos

    def forward_kinematics(self) -> torch.Tensor:
        """World positions of every joint in every frame: ``(F, J, 3)`` (file units, file axes)."""
        f = self.num_frames
        world_r: list[torch.Tensor] = []
        world_p: list[torch.Tensor] = []
        eye = torch.eye(3, dtype=torch.float64).expand(f, 3, 3)
        for j, parent in enumerate(self.parents):
            local_t = self.offsets[j].expand(f, 3).clone()
            local_r = eye
            start = self._channel_start[j]
            for c, name in enumerate(self.channels[j]):
                values = self.motion[:, start + c]
                axis = name[0].lower()
                if name.endswith("position"):
                    local_t[:, "xyz".index(axis)] += values
                else:
                    local_r = local_r @ rot.axis_rotation(axis, torch.deg2rad(values))
            if parent < 0:
                world_p.append(local_t)
                world_r.append(local_r)
            else:
                pr = world_r[parent]
                world_p.append(world_p[parent] + (pr @ local_t.unsqueeze(-1)).squeeze(-1))
                world_r.append(pr @ local_r)
        return torch.stack(world_p, dim=1)


class _Lines:
    """Token stream over a BVH file that remembers line numbers (for error messages)."""

    def __init__(self, text: str, path: str) -> None:
        self.path = path
        self.tokens: list[tuple[str, int]] = []
        for n, line in enumerate(text.splitlines(), start=1):
            self.tokens.extend((tok, n) for tok in line.split())
        self.i = 0

    def error(self, msg: str, line: int | None = None) -> SceneError:
        if line is None:
            line = self.tokens[min(self.i, len(self.tokens) - 1)][1] if self.tokens else 1
        return SceneError(f"{self.path}: line {line}: {msg}")

    def next(self, what: str) -> tuple[str, int]:
        if self.i >= len(self.tokens):
            raise self.error(f"unexpected end of file, expected {what}")
        tok = self.tokens[self.i]
        self.i += 1
        return tok

    def expect(self, word: str) -> int:
        tok, line = self.next(repr(word))
        if tok.upper() != word.upper():
            raise self.error(f"expected {word!r}, found {tok!r}", line)
        return line

    def number(self, what: str) -> float:
        tok, line = self.next(what)
        try:
            value = float(tok)
        except ValueError:
            raise self.error(f"expected a number for {what}, found {tok!r}", line) from None
        if not math.isfinite(value):
            raise self.error(f"{what} must be finite, found {tok!r}", line)
        return value


def _add_joint(out: BVHSkeleton, offsets: list[list[float]], name: str, parent: int, offset: list[float],
               channels: list[str]) -> int:
    """Append a joint and return its index (``offsets`` collects the offsets until the file is read)."""
    out._channel_start.append(sum(len(c) for c in out.channels))
    out.names.append(name)
    out.parents.append(parent)
    out.channels.append(channels)
    offsets.append(offset)
    return len(out.names) - 1


def _parse_joint(s: _Lines, name: str, parent: int, out: BVHSkeleton, offsets: list[list[float]]) -> None:
    s.expect("{")
    s.expect("OFFSET")
    offset = [s.number(f"OFFSET of {name}") for _ in range(3)]
    tok, line = s.next("CHANNELS")
    if tok.upper() != "CHANNELS":
        raise s.error(f"joint {name!r}: expected CHANNELS, found {tok!r}", line)
    count_tok, line = s.next("channel count")
    if not count_tok.isdigit():
        raise s.error(f"joint {name!r}: bad channel count {count_tok!r}", line)
    chans = []
    for _ in range(int(count_tok)):
        ch, line = s.next("channel name")
        if ch not in _CHANNELS:
            raise s.error(f"joint {name!r}: unknown channel {ch!r} (expected one of {', '.join(_CHANNELS)})", line)
        chans.append(ch)
    idx = _add_joint(out, offsets, name, parent, offset, chans)
    while True:
        tok, line = s.next("JOINT, End Site or '}'")
        key = tok.upper()
        if key == "}":
            return
        if key == "JOINT":
            child, _ = s.next("joint name")
            _parse_joint(s, child, idx, out, offsets)
        elif key == "END":
            s.expect("Site")
            s.expect("{")
            s.expect("OFFSET")
            end_off = [s.number(f"End Site OFFSET of {name}") for _ in range(3)]
            s.expect("}")
            _add_joint(out, offsets, f"{name}_end", idx, end_off, [])
        else:
            raise s.error(f"joint {name!r}: unexpected {tok!r}", line)


def read_bvh(path: str | Path) -> BVHSkeleton:
    """Parse a BVH file (HIERARCHY + MOTION).

    Raises:
        SceneError: missing/unreadable file or malformed content (names the file and line).
    """
    p = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise SceneError(f"{p}: cannot read BVH file: {exc.strerror or exc}") from exc
    s = _Lines(text, p)
    s.expect("HIERARCHY")
    s.expect("ROOT")
    root, _ = s.next("root joint name")
    out = BVHSkeleton(names=[], parents=[], offsets=torch.empty(0), channels=[], motion=torch.empty(0),
                      frame_time_s=0.0, path=p)
    offsets: list[list[float]] = []
    _parse_joint(s, root, -1, out, offsets)
    out.offsets = torch.tensor(offsets, dtype=torch.float64)
    n_channels = sum(len(c) for c in out.channels)
    tok, line = s.next("MOTION")
    if tok.upper() == "ROOT":
        raise s.error("several ROOT joints are not supported", line)
    if tok.upper() != "MOTION":
        raise s.error(f"expected MOTION, found {tok!r}", line)
    s.expect("Frames:")
    n_tok, line = s.next("frame count")
    if not n_tok.isdigit() or int(n_tok) < 1:
        raise s.error(f"bad frame count {n_tok!r}", line)
    n_frames = int(n_tok)
    s.expect("Frame")
    s.expect("Time:")
    out.frame_time_s = s.number("frame time")
    if not out.frame_time_s > 0:
        raise s.error(f"frame time must be positive, got {out.frame_time_s}")
    values = s.tokens[s.i:]
    need = n_frames * n_channels
    if len(values) != need:
        line = values[-1][1] if values else s.tokens[-1][1]
        raise s.error(
            f"MOTION has {len(values)} values, expected {n_frames} frames x {n_channels} channels = {need}", line
        )
    flat = []
    for v, n in values:
        try:
            flat.append(float(v))
        except ValueError:
            raise s.error(f"non-numeric motion value {v!r}", n) from None
    bad_line = next((n for x, (_, n) in zip(flat, values) if not math.isfinite(x)), None)
    if bad_line is not None:
        raise s.error("motion values contain NaN/Inf", bad_line)
    out.motion = torch.tensor(flat, dtype=torch.float64).reshape(n_frames, n_channels)
    return out
