"""Checks of the inertia (to be written)."""


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
