"""Exact solutions of Barker et al. (2021) used by the validation tests."""
