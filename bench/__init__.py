"""Benchmarks: each bench_*.py runs as `python -m bench.<name>` and prints its figures as JSON."""
