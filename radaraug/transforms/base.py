"""Base classes of radaraug transforms (torchvision-v2 / kornia style ``nn.Module``s).

* :class:`RadarTransform`: deterministic; ``transform(x, params)`` does the work and
  :meth:`~RadarTransform.chain_spec` describes it as a JSON-able dict, so that the DSP chain a
  calibration was fitted with can be recorded and checked.
* :class:`RandomRadarTransform`: draws per-sample parameters with :meth:`make_params`, applies them
  with :meth:`transform`, keeps them in :attr:`last_params`, and replays them with
  ``forward(x, params=...)``. A "sample" is one item of the leading batch dims; the last
  :attr:`event_ndim` dims are the event (3: ``(rx, range, doppler)`` or ``(rx, chirps, samples)``).

Calling conventions (both classes): ``t(x)`` returns the transformed tensor; ``t(x, *rest)``
returns ``(t(x), *rest)`` with ``rest`` passed through untouched, like torchvision v2 does for a
sample made only of plain tensors (only the first one is transformed). That makes a radaraug
transform usable on ``(cube, label)`` samples inside ``torchvision.transforms.v2.Compose``.

``.eval()`` mode: random transforms become the identity (like dropout) and return their input
object itself; replaying explicit ``params`` still applies them. Deterministic DSP is unaffected.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import torch
from torch import nn

from radaraug.errors import RadarAugError
from radaraug.transforms._checks import check_tensor
from radaraug.transforms._rng import GeneratorSource

Params = dict[str, torch.Tensor]


class RadarTransform(nn.Module):
    """A deterministic radar transform.

    Subclasses implement :meth:`transform` and, when they have parameters, :meth:`extra_spec`.
    Inputs are never modified in place; dtype and device follow the input.
    """

    #: trailing dims that make one sample (the event); leading dims are batch dims.
    event_ndim: int = 3
    #: human description of the expected input, used in error messages.
    input_layout: str = "(..., rx, range, doppler)"
    #: accept complex input.
    accepts_complex: bool = False

    def check_input(self, x: Any) -> torch.Tensor:
        """Validate the input (rank, dtype, NaN/Inf) and return it."""
        return check_tensor(
            x,
            f"{type(self).__name__} expects {self.input_layout}",
            min_ndim=self.event_ndim,
            allow_complex=self.accepts_complex,
        )

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:  # pragma: no cover - abstract
        """Compute the output for a validated input."""
        raise NotImplementedError

    def forward(self, x: torch.Tensor, *rest: Any) -> Any:
        """Transform ``x``; extra positional items are passed through (see the module docstring)."""
        out = self.transform(self.check_input(x), {})
        return (out, *rest) if rest else out

    def extra_spec(self) -> dict[str, Any]:
        """The transform's parameters as JSON types (for :meth:`chain_spec`)."""
        return {}

    def chain_spec(self) -> dict[str, Any]:
        """``{"name": class name, **parameters}``: this step of a DSP chain, JSON-able."""
        return {"name": type(self).__name__, **self.extra_spec()}

    def extra_repr(self) -> str:
        return ", ".join(f"{k}={v!r}" for k, v in self.extra_spec().items())


class RandomRadarTransform(RadarTransform):
    """A random radar transform with per-sample parameters.

    Args:
        p: probability of applying the transform to each sample (drawn per sample).
        same_on_batch: draw one set of parameters and use it for every sample of a batch.
        generator: a ``torch.Generator`` to draw from (else ``seed``, else the global RNG).
        seed: integer seed of a generator the transform owns (pickles; one per device).
        reseed_in_workers: in DataLoader workers, re-seed ``generator``/``seed`` streams per
            worker (and per epoch) so workers draw different numbers; ``False`` makes every
            worker replay the same stream. See :mod:`radaraug.transforms._rng`.

    Subclasses implement :meth:`sample_params` and :meth:`transform`.
    """

    def __init__(
        self,
        p: float = 1.0,
        same_on_batch: bool = False,
        generator: torch.Generator | None = None,
        *,
        seed: int | None = None,
        reseed_in_workers: bool = True,
    ) -> None:
        super().__init__()
        p = float(p)
        if not 0.0 <= p <= 1.0:
            raise RadarAugError(f"{type(self).__name__}: p must be in [0, 1], got {p}")
        if generator is not None and seed is not None:
            raise RadarAugError(f"{type(self).__name__}: give either generator or seed, not both")
        self.p = p
        self.same_on_batch = bool(same_on_batch)
        self.rng = GeneratorSource(generator, seed, reseed_in_workers)
        self.last_params: Params | None = None

    # ------------------------------------------------------------------ random draws
    def param_shape(self, x: torch.Tensor) -> tuple[int, ...]:
        """Shape of per-sample parameters: the batch dims, or all ones with ``same_on_batch``."""
        batch = tuple(x.shape[: x.ndim - self.event_ndim])
        return tuple(1 for _ in batch) if self.same_on_batch else batch

    @staticmethod
    def draw(
        kind: str,
        shape: tuple[int, ...],
        like: torch.Tensor,
        generator: torch.Generator | None,
        mean: float = 0.0,
        std: float = 1.0,
    ) -> torch.Tensor:
        """Uniform [0, 1) (``kind="rand"``) or ``Normal(mean, std**2)`` (``"normal"``) draws.

        The result has ``shape`` and ``like``'s dtype and device. A generator on another device
        than ``like`` draws on its own device and the result is moved (correct but slower: give a
        generator on the data's device).
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

    def make_params(self, x: torch.Tensor, generator: torch.Generator | None = None) -> Params:
        """Draw the parameters for ``x``: ``apply`` (bool, per sample) and the subclass's own."""
        shape = self.param_shape(x)
        if self.p >= 1.0:
            apply = torch.ones(shape, dtype=torch.bool, device=x.device)
        elif self.p <= 0.0:
            apply = torch.zeros(shape, dtype=torch.bool, device=x.device)
        else:
            apply = self.draw("rand", shape, x, generator) < self.p
        return {"apply": apply, **self.sample_params(x, shape, generator)}

    def sample_params(
        self, x: torch.Tensor, shape: tuple[int, ...], generator: torch.Generator | None
    ) -> Params:  # pragma: no cover - abstract
        """The subclass's parameters, with leading dims ``shape`` (broadcastable to the batch)."""
        raise NotImplementedError

    # ------------------------------------------------------------------ application
    def forward(self, x: torch.Tensor, *rest: Any, params: Mapping[str, torch.Tensor] | None = None) -> Any:
        """Transform ``x`` with fresh random parameters, or replay ``params``.

        ``params`` may also be given as the second positional argument (a mapping with an
        ``"apply"`` key, e.g. ``t.last_params``); other extra positional items pass through.
        """
        if params is None and rest and isinstance(rest[0], Mapping) and "apply" in rest[0]:
            params, rest = rest[0], rest[1:]
        x = self.check_input(x)
        if params is None and not self.training:
            self.last_params = None
            out = x
        else:
            if params is None:
                params = self.make_params(x, self.rng.get(x.device))
                # p = 1 (the default): every sample applies; skip _apply_where's two host syncs.
                every = self.p >= 1.0
            else:
                params = {k: torch.as_tensor(v, device=x.device) for k, v in params.items()}
                every = False
            self.last_params = dict(params)
            out = self.transform(x, params) if every else self._apply_where(x, params)
        return (out, *rest) if rest else out

    def _apply_where(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        apply = params["apply"]
        if not bool(apply.any()):
            return x
        y = self.transform(x, params)
        if bool(apply.all()):
            return y
        mask = apply.reshape(apply.shape + (1,) * self.event_ndim)
        return torch.where(mask, y, x)

    def extra_spec(self) -> dict[str, Any]:
        return {"p": self.p, "same_on_batch": self.same_on_batch}

    def chain_spec(self) -> dict[str, Any]:
        """As :meth:`RadarTransform.chain_spec`, marked ``"random": True``."""
        return {**super().chain_spec(), "random": True}
