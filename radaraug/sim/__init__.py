"""On-the-fly simulation: scenario sampling, the simulated Dataset, offline sharded generation."""
