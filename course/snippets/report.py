"""Human-readable reports: what failed where, what ran, what was skipped and why."""

from __future__ import annotations

import textwrap

from .execute import PageResult
from .parse import Block


def format_failure(result: PageResult) -> str:
    """The report of a failed page: `page.md:line: Type: message`, then details indented."""
    if result.errors:
        return "\n".join(str(e) for e in result.errors)
    failure = result.failure
    if failure is None:
        return ""
    block = failure.block
    detail = [
        f"in the block starting at {block.location}" + (f" (include_code {block.include})" if block.include else "")
    ]
    if failure.traceback:
        detail.append(failure.traceback.rstrip())
    if failure.output.strip():
        detail.append("output of the block:\n" + textwrap.indent(failure.output.rstrip(), "| ", lambda _: True))
    return failure.headline + "\n" + textwrap.indent("\n".join(detail), "    ")


def format_summary(result: PageResult) -> str:
    """One line per page: status, blocks run and skipped, time."""
    status = "ok" if result.ok else "FAILED"
    return (
        f"{status:6} {result.page.path} ({len(result.ran)} run, "
        f"{len(result.page.skipped)} skipped, {result.seconds:.1f} s)"
    )


def format_skipped(blocks: list[Block]) -> list[str]:
    """`page.md:line: reason` for each skipped block."""
    return [f"{b.location}: {b.skip}" for b in blocks]
