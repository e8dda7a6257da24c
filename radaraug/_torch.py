"""Small torch runtime helpers: a set number of intra-op threads, a device given by the user."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import torch

from radaraug.errors import ConfigError


@contextlib.contextmanager
def torch_threads(n: int) -> Iterator[None]:
    """Run the block on ``n`` torch threads (intra-op); the number before is restored after."""
    before = torch.get_num_threads()
    torch.set_num_threads(n)
    try:
        yield
    finally:
        torch.set_num_threads(before)


def parse_device(device: object, label: str = "device") -> torch.device:
    """``device`` as a :class:`torch.device`; ``label`` names it in the error.

    Raises:
        ConfigError: ``device`` is not a torch device.
    """
    try:
        return torch.device(device)  # type: ignore[call-overload]
    except (RuntimeError, TypeError):
        raise ConfigError(f"{label} {device!r}: not a torch device (use cpu, cuda or cuda:N)") from None
