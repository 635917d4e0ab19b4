"""An included script whose function fails on bad input."""


def check(value: int) -> int:
    if value < 0:
        raise ValueError(f"negative value {value}")
    return value


check(1)
