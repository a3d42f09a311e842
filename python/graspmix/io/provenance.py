"""What produced a result: graspmix's version, the source tree's commit, files by content."""

from __future__ import annotations

from pathlib import Path

# hashlib (OpenSSL) and subprocess are imported where they are used: `import graspmix` would pay some 8 ms for them
# in every command, and only the experiment's reports use them.


def package_version() -> str:
    """The installed distribution's version, or the C++ core's when running from a source tree."""
    from importlib import metadata

    try:
        return metadata.version("graspmix")
    except metadata.PackageNotFoundError:
        from .. import _core

        return _core.build_info()["graspmix"]


def git_commit(cwd: str | Path | None = None) -> str | None:
    """The commit of the source tree the run is started from (with "+dirty" if it has changes), if any."""
    import subprocess

    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=cwd, capture_output=True, text=True, timeout=10)
        if head.returncode != 0:
            return None
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=cwd,
            capture_output=True,
            text=True,
            timeout=10,
        )
        return head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return None


def sha256_file(path) -> str:
    import hashlib

    return hashlib.sha256(Path(path).read_bytes()).hexdigest()
