"""A package sent as a .zip archive: what Windows makes of a folder with "Send to >
Compressed (zipped) folder", and how exports travel by mail and cloud drives.

`unpack` copies the archive's files into a temporary folder of this process, removed
when it ends; the archive itself is only read. `shown` gives a path inside that folder
as the user would name it, through the archive: `arm.zip/Arm_Assembly/urdf/arm.urdf`.

An archive is refused, with the reason, when it cannot be read, is encrypted, names a
file outside its own folder (`../`, `/etc/...`, `C:\\...`), or would unpack to more than
MAX_BYTES or MAX_FILES. Names written with backslashes (PowerShell 5's Compress-Archive)
are read as folders, names in a Windows code page are read in the one the URDF agrees
with, and macOS's `__MACOSX/` copies are left out. A file keeps the executable mode a zip
made on Unix gives it; from a zip made on Windows (which has no such mode) a script,
a file starting with `#!`, comes out executable, as ROS wants its nodes.
"""

from __future__ import annotations

import atexit
import os
import re
import shutil
import tempfile
import zipfile
from pathlib import Path, PurePosixPath

MAX_BYTES = 2_000_000_000   # unpacked; an export's meshes rarely reach a tenth of it
MAX_FILES = 20_000
# Archives that are not read here: the user unpacks them first.
OTHER_ARCHIVES = (".7z", ".rar", ".tar", ".tar.gz", ".tgz", ".tar.xz", ".tar.bz2", ".gz")
LEFT_OUT = re.compile(r"(^|/)(__MACOSX/|\.DS_Store$|Thumbs\.db$|desktop\.ini$)", re.IGNORECASE)

_unpacked: dict[tuple, Path] = {}  # the archive (path, time, size) -> the folder it unpacked to
_shown: dict[Path, str] = {}       # that folder -> the archive as the user named it


class ArchiveError(Exception):
    """An archive that is not unpacked; `kind` as sw2sim.package.LoadError sorts them."""

    def __init__(self, message: str, fix: str, kind: str = "unreadable"):
        super().__init__(message)
        self.message, self.fix, self.kind = message, fix, kind


def is_zip(path: Path) -> bool:
    """A file named .zip, or one that starts as a zip archive does."""
    if not path.is_file():
        return False
    if path.suffix.lower() == ".zip":
        return True
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"PK\x03\x04"
    except OSError:
        return False


def other_archive(path: Path) -> str | None:
    """The kind of archive a file is by its name when it is one not read here (".7z")."""
    name = path.name.lower()
    for suffix in OTHER_ARCHIVES:
        if name.endswith(suffix) and path.is_file():
            return suffix
    return None


def unpack(archive: Path, shown_as: str | None = None) -> Path:
    """The folder holding the archive's files (unpacked once per process, and again if
    the archive changes); ArchiveError when it cannot or should not be unpacked."""
    stat = archive.stat()
    key = (archive.resolve(), stat.st_mtime_ns, stat.st_size)
    if key in _unpacked:
        return _unpacked[key]
    again = "unzip it yourself and give the package folder, or make the archive again"
    try:
        with zipfile.ZipFile(archive) as zf:
            entries = _entries(zf)
            scratch = Path(tempfile.mkdtemp(prefix="sw2sim-zip-")).resolve()
            atexit.register(shutil.rmtree, scratch, ignore_errors=True)
            # named after the archive, as the folder "Extract all" makes: a package zipped
            # without its folder gets the name it would have once unzipped
            folder = scratch / (archive.stem or "archive")
            folder.mkdir()
            try:
                _extract(zf, entries, folder)
            except BaseException:
                shutil.rmtree(scratch, ignore_errors=True)
                raise
    except zipfile.BadZipFile as exc:
        raise ArchiveError(f"not a readable zip archive ({exc})", again) from None
    except (OSError, EOFError, NotImplementedError, RuntimeError) as exc:
        raise ArchiveError(f"the archive cannot be unpacked ({type(exc).__name__}: {exc})",
                           again) from None
    _unpacked[key] = folder
    _shown[folder] = shown_as if shown_as is not None else str(archive)
    return folder


def _entries(zf: zipfile.ZipFile) -> list[tuple[zipfile.ZipInfo, PurePosixPath]]:
    """The files to unpack with their paths inside the archive, after every check."""
    entries, total = [], 0
    names = _names(zf)
    for info in zf.infolist():
        name = names[info.filename].replace("\\", "/")
        if name.endswith("/") or LEFT_OUT.search(name):
            continue
        path = PurePosixPath(name)
        if (path.is_absolute() or re.match(r"^[A-Za-z]:", name) or ".." in path.parts
                or not path.parts):
            raise ArchiveError(f"the archive names a file outside its own folder ({info.filename})",
                               "unzip it yourself, look at what it holds, and give the package "
                               "folder", kind="unsafe")
        if info.flag_bits & 0x1:
            raise ArchiveError(f"the archive is encrypted ({info.filename} needs a password)",
                               "unzip it with its password and give the package folder")
        total += info.file_size
        entries.append((info, path))
    if len(entries) > MAX_FILES or total > MAX_BYTES:
        raise ArchiveError(f"the archive unpacks to {len(entries):,} files, {total / 1e9:.1f} GB: "
                           f"more than a package needs ({MAX_FILES:,} files, "
                           f"{MAX_BYTES / 1e9:.0f} GB at most)",
                           "unzip the package folder alone and give it", kind="unreadable")
    return entries


# The code pages Windows writes the names in a zip in when it does not mark them UTF-8
# (its OEM code page: 936 on a Chinese Windows, 866 on a Russian one, 850 in western
# Europe), tried in this order.
CODE_PAGES = ("utf-8", "cp936", "cp932", "cp949", "cp950", "cp866", "cp850", "cp437")


def _names(zf: zipfile.ZipFile) -> dict[str, str]:
    """Each entry's name, by the name zipfile read. zipfile reads a name that is not
    marked UTF-8 as code page 437; where that name is not plain ASCII, it is decoded in
    the first code page that makes it a name the archive's URDFs and xacros use (their
    text is UTF-8), else as UTF-8 where it is valid UTF-8, else left as read."""
    names = {info.filename: info.filename for info in zf.infolist()}
    unmarked = [i for i in zf.infolist() if not i.flag_bits & 0x800 and not i.filename.isascii()]
    if not unmarked:
        return names
    text = ""
    for info in zf.infolist():
        if info.filename.lower().endswith((".urdf", ".xacro")) and info.file_size < 20_000_000:
            text += zf.read(info).decode("utf-8", errors="replace")
    for info in unmarked:
        raw = info.filename.encode("cp437")
        readings = []
        for code_page in CODE_PAGES:
            try:
                readings.append((code_page, raw.decode(code_page)))
            except UnicodeDecodeError:
                continue
        named = [name for _, name in readings
                 if any(part in text for part in name.replace("\\", "/").split("/")
                        if not part.isascii())]
        utf8 = [name for code_page, name in readings if code_page == "utf-8"]
        names[info.filename] = (named or utf8 or [info.filename])[0]
    return names


def _extract(zf: zipfile.ZipFile, entries, folder: Path) -> None:
    """Copy the entries' bytes into `folder`, counting what really comes out (an entry
    may claim a smaller size than it unpacks to), and make executable what runs."""
    written = 0
    for info, path in entries:
        target = folder.joinpath(*path.parts)
        target.parent.mkdir(parents=True, exist_ok=True)
        with zf.open(info) as source, open(target, "wb") as out:
            first = b""
            while chunk := source.read(1 << 20):
                first = first or chunk[:2]
                written += len(chunk)
                if written > MAX_BYTES:
                    raise ArchiveError(f"the archive unpacks to more than {MAX_BYTES / 1e9:.0f} GB",
                                       "unzip the package folder alone and give it")
                out.write(chunk)
        if _executable(info, first):
            target.chmod(target.stat().st_mode | 0o111)


def _executable(info: zipfile.ZipInfo, first: bytes) -> bool:
    """Whether an unpacked file should run, as roslaunch and rosrun want a node to: the
    archive says so (a zip made on Unix keeps the file's mode), or, in one made on
    Windows, which has no such mode, the file starts with `#!` as a script does."""
    mode = info.external_attr >> 16
    if info.create_system == 3 and mode:   # Unix
        return bool(mode & 0o111)
    return first == b"#!"


def shown(path: str | os.PathLike) -> str | None:
    """A path inside an unpacked archive as the user would name it, through the archive
    (`arm.zip/Arm_Assembly/urdf/arm.urdf`); None for any other path."""
    path = Path(os.path.abspath(path))
    for folder, archive in _shown.items():
        if path == folder:
            return archive
        if folder in path.parents:
            return f"{archive}/{path.relative_to(folder).as_posix()}"
    return None


def discard() -> None:
    """Remove every folder unpacked so far (their paths must not be used after this)."""
    for folder in list(_shown):
        shutil.rmtree(folder.parent, ignore_errors=True)
    _unpacked.clear()
    _shown.clear()
