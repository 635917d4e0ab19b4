"""Checks of the joints (to be written)."""


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
