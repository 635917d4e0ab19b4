"""An included script that fails at its fourth line."""

setting = None
raise RuntimeError(f"setting is {setting}")
