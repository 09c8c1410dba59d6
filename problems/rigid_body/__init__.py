"""Rigid body about a fixed point: Euler–Poisson equations and their reduction."""
