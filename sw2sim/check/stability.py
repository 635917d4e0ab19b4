"""The stability run (to be written)."""


def check(ctx) -> dict | None:
    return None
