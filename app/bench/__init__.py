"""Benchmarks: reference implementations (e.g. MuJoCo) to time our integrators against."""
