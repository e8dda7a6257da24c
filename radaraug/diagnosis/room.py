"""Room parameters the diagnosis loop fits: properties of the traced room, not receiver effects.

Today one: ``diffuse_gain_dB``, a power gain on every diffuse path (the
:class:`~radaraug.raytrace.RayTracer` option of that name). It is not in the effect chain: the search
carries a ``room`` dict beside it and names it with the pseudo-stage :data:`ROOM_STAGE`. Why a gain and
not the scattering coefficient: ``docs/diagnosis.md``, "The room's diffuse gain".
"""

from __future__ import annotations

from radaraug.sensor.effects.base import Prior

ROOM_STAGE = "room"
"""Pseudo-stage name of the room parameters in the search's ``(stage, ParamSpec)`` lists."""

Room = dict[str, float]
"""Room parameter values by name (e.g. ``{"diffuse_gain_dB": 4.2}``)."""

ROOM_PRIORS: dict[str, Prior] = {
    # The default S = 0.7 was fitted to two real rooms within ~5 dB; +-20 dB covers a bare
    # concrete box (S ~ 0.1, -17 dB) up to a cluttered room, linear in dB like every gain.
    "diffuse_gain_dB": Prior(-20.0, 20.0, "lin"),
}
"""Search range of each room parameter."""

__all__ = ["ROOM_PRIORS", "ROOM_STAGE", "Room"]
