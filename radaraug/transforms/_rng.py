"""Where random transforms draw from, across pickling and DataLoader workers.

Precedence: :func:`use_generator`'s scoped generator, the transform's ``generator``, its ``seed`` (an owned
generator per device), torch's global RNG. See docs/transforms.md, "Seeding story".
"""

from __future__ import annotations

import os
from typing import Any

import torch
from torch.utils.data import get_worker_info

from radaraug._augmentation import scoped_generator, use_generator
from radaraug._seeding import mix

__all__ = ["use_generator", "draw", "mix_seed", "GeneratorSource"]


def draw(
    kind: str,
    shape: tuple[int, ...],
    like: torch.Tensor,
    generator: torch.Generator | None,
    mean: float = 0.0,
    std: float = 1.0,
) -> torch.Tensor:
    """Uniform [0, 1) (``kind="rand"``) or ``Normal(mean, std**2)`` (``"normal"``) draws of ``shape``.

    The result has ``like``'s dtype and device; a generator on another device draws there and the result is moved.
    """
    device = (
        like.device
        if generator is None or generator.device.type == like.device.type
        else generator.device
    )
    out = torch.empty(shape, dtype=like.dtype, device=device)
    if kind == "rand":
        out.uniform_(0.0, 1.0, generator=generator)
    else:
        out.normal_(mean, std, generator=generator)
    return out.to(like.device)


_WORKER_TAG = 0x574B5253  # separates worker re-seeds from every other use of the mixer


def mix_seed(seed: int, worker_seed: int) -> int:
    """A well-mixed 63-bit seed from a user seed and a DataLoader worker seed (:func:`radaraug._seeding.mix`)."""
    return mix(seed, worker_seed, _WORKER_TAG)


def _process_key() -> tuple[int, int | None]:
    info = get_worker_info()
    return os.getpid(), (None if info is None else int(info.seed))


class GeneratorSource:
    """Picks the generator a random transform draws from (see the module docstring).

    Args:
        generator: a user generator, or None.
        seed: an integer seed for an owned generator, or None.
        reseed_in_workers: re-seed per DataLoader worker so workers draw different numbers.
    """

    def __init__(self, generator: torch.Generator | None, seed: int | None, reseed_in_workers: bool = True):
        if generator is not None and not isinstance(generator, torch.Generator):
            raise TypeError(f"generator must be a torch.Generator or None, got {type(generator).__name__}")
        self.user_generator = generator
        self.seed = None if seed is None else int(seed)
        self.reseed_in_workers = bool(reseed_in_workers)
        self._active_seed = self.seed
        self._owned: dict[str, torch.Generator] = {}
        self._key = _process_key()

    @property
    def uses_global_rng(self) -> bool:
        """True when draws come from torch's global RNG."""
        return self.user_generator is None and self.seed is None

    def get(self, device: torch.device) -> torch.Generator | None:
        """The generator to use for a draw on ``device`` (None: global RNG)."""
        scoped = scoped_generator()
        if scoped is not None:  # per-item augmentation (use_generator) wins
            return scoped
        if self.uses_global_rng:
            return None
        key = _process_key()
        if key != self._key:
            self._enter_process(key)
        if self.user_generator is not None:
            return self.user_generator
        name = str(torch.device(device))
        gen = self._owned.get(name)
        if gen is None:
            seed = self._active_seed
            assert seed is not None  # not the global RNG (returned above), no user generator: seeded
            gen = self._owned[name] = torch.Generator(device=device).manual_seed(seed)
        return gen

    def _enter_process(self, key: tuple[int, int | None]) -> None:
        self._key = key
        worker_seed = key[1]
        if worker_seed is None or not self.reseed_in_workers:
            return
        if self.user_generator is not None:
            seed = mix_seed(self.user_generator.initial_seed(), worker_seed)
            self.user_generator = torch.Generator(device=self.user_generator.device).manual_seed(seed)
        elif self.seed is not None:  # (no generator and no seed: the global RNG, not re-seeded here)
            self._active_seed = mix_seed(self.seed, worker_seed)
            self._owned = {}

    # torch.Generator only pickles in recent torch: store device + state explicitly.
    @staticmethod
    def _pack(gen: torch.Generator) -> tuple[str, int, torch.Tensor]:
        return str(gen.device), gen.initial_seed(), gen.get_state()

    @staticmethod
    def _unpack(packed: tuple[str, int, torch.Tensor]) -> torch.Generator:
        device, initial_seed, state = packed
        try:
            # manual_seed keeps initial_seed() meaningful after the round trip
            gen = torch.Generator(device=device).manual_seed(initial_seed)
        except RuntimeError:  # e.g. a CUDA generator unpickled on a CPU-only machine
            return torch.Generator().manual_seed(initial_seed)
        gen.set_state(state)
        return gen

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        if self.user_generator is not None:
            state["user_generator"] = self._pack(self.user_generator)
        state["_owned"] = {k: self._pack(g) for k, g in self._owned.items()}
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        # The pickled state holds (device, seed, state) tuples where generators were (__getstate__).
        packed_user, packed_owned = state.pop("user_generator"), state.pop("_owned")
        self.__dict__.update(state)
        self.user_generator = None if packed_user is None else self._unpack(packed_user)
        self._owned = {k: self._unpack(v) for k, v in packed_owned.items()}
