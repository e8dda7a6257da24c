"""Benchmarks: each reports figures as a ratio against a baseline run in the same process."""
