"""Exact solutions of Barker et al. (2021) and the error measures against
them, used by the tests (validation/), the tutorials and the benchmarks."""
