"""The one seed mixer of radaraug: SplitMix64 over a sequence of 64-bit words.

Every derived seed (a simulated item's, a transform's per-worker re-seed, a per-item augmentation's) is
:func:`mix` of a few integers, so nearby inputs give unrelated streams. Imported by ``sim`` and ``transforms``.
"""

from __future__ import annotations

MASK64 = (1 << 64) - 1


def splitmix64(x: int) -> int:
    """One SplitMix64 step (Steele, Lea & Flood 2014) on a 64-bit integer.

    ``splitmix64(0)`` is ``0xE220A8397B1DCDAF``, the first output of SplitMix64 seeded with 0.
    """
    x = (x + 0x9E3779B97F4A7C15) & MASK64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK64
    return x ^ (x >> 31)


def mix(*words: int) -> int:
    """A 63-bit seed (a valid ``torch.Generator.manual_seed``) from one or more integers.

    ``mix(w0, w1, ..., wk) = h >> 1`` with ``h = splitmix64(w0)`` then ``h = splitmix64(h ^ wi)``
    for each further word; each word is taken modulo ``2**64`` (negative ints in two's complement).
    """
    if not words:
        raise ValueError("mix needs at least one word")
    h = splitmix64(int(words[0]) & MASK64)
    for w in words[1:]:
        h = splitmix64(h ^ (int(w) & MASK64))
    return h >> 1
