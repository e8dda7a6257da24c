"""Vectorized torch ray tracer: shooting-and-bouncing rays + physical optics."""
