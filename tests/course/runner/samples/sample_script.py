"""A small script a page includes."""

ran_main = False


def answer() -> int:
    return 6 * 7


if __name__ == "__main__":
    counter = counter + 1  # noqa: F821 - set by the page before the include
    result = answer()
    ran_main = True
