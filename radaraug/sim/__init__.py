"""On-the-fly simulation: scenario sampling, twin randomization, the simulated Dataset, offline sharded
generation."""
