"""ROS 2's own interface definitions, taken from its wheels on PyPI: ``python -m node_runtime.ros_wheels``.

ROS 2 Kilted's message packages are on PyPI (``ros-std-msgs``, which ``ros-kilted-std-msgs``
requires, ...), each wheel holding its package's ``share/<pkg>/{msg,srv,action}`` files beside
the compiled modules. The lab generates its std_msgs, geometry_msgs ... from those files rather
than keeping copies: this downloads the wheels ``msgs/ros_packages.txt`` pins (version and
sha256), keeps them in a cache that every checkout on the machine shares, and extracts only the
definitions, with the type hashes ROS 2 computed for them, into ``msgs/ros_interfaces/`` (not
committed). The wheels are never installed: their modules would shadow the lab's own std_msgs.

The set-up scripts run it; it does nothing when the folder is current, and needs no network when
the wheels are in the cache. It runs before the app is installed, on the standard library alone
(``server/__init__.py`` imports nothing; ``node_runtime.msgs`` needs these files to import at all).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
LOCK = HERE / "msgs" / "ros_packages.txt"
TARGET = HERE / "msgs" / "ros_interfaces"
HASHES_FILE = "type_hashes.json"  # in TARGET: ROS 2's RIHS01 hash of every type, by name
STAMP_FILE = ".lock-sha256"  # in TARGET: the lock it was extracted from
# The wheels' platform: any one holds the same definitions, so the same file is fetched anywhere.
PLATFORM = (
    "--platform",
    "manylinux_2_28_x86_64",
    "--python-version",
    "3.11",
    "--implementation",
    "cp",
    "--abi",
    "cp311",
)
_PIN = re.compile(r"^(?P<name>[a-z0-9-]+)==(?P<version>\S+)\s+--hash=sha256:(?P<sha256>[0-9a-f]{64})$")
_DEFINITION = re.compile(
    r"/data/share/(?P<pkg>\w+)/(?P<kind>msg|srv|action)/(?P<file>\w+\.(?:msg|srv|action|json))$"
)


class SetUpError(RuntimeError):
    """The definitions could not be had; the message says why and what to do."""


@dataclass(frozen=True)
class Pin:
    """One wheel of the lock: ``ros-std-msgs==5.5.1 --hash=sha256:...``."""

    name: str
    version: str
    sha256: str

    @property
    def requirement(self) -> str:
        return f"{self.name}=={self.version} --hash=sha256:{self.sha256}"

    @property
    def file_prefix(self) -> str:
        """How its wheel's file name starts (a wheel's name has underscores for dashes)."""
        return f"{self.name.replace('-', '_')}-{self.version}-"


def read_lock(text: str) -> list[Pin]:
    pins = []
    for number, line in enumerate(text.splitlines(), 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        match = _PIN.match(line)
        if match is None:
            raise SetUpError(
                f"{LOCK.name}:{number}: expected 'name==version --hash=sha256:HEX', got {line!r}"
            )
        pins.append(Pin(match["name"], match["version"], match["sha256"]))
    return pins


def cache_dir() -> Path:
    """Where downloaded wheels are kept: ``$TELEOP_CACHE`` or the user's cache folder."""
    base = (
        os.environ.get("TELEOP_CACHE")
        or Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "teleop-lab"
    )
    return Path(base) / "ros-wheels"


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def cached_wheel(pin: Pin, cache: Path) -> Path | None:
    """The pinned wheel in ``cache``, if a file there has its name and hash."""
    for path in sorted(cache.glob(f"{pin.file_prefix}*.whl")):
        if _sha256(path) == pin.sha256:
            return path
    return None


def download(pins: list[Pin], cache: Path) -> None:
    """Fetch the pinned wheels into ``cache`` with pip (PyPI, hashes required, no dependencies)."""
    cache.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=cache, prefix=".download-") as tmp:
        requirements = Path(tmp) / "requirements.txt"
        requirements.write_text("".join(p.requirement + "\n" for p in pins), encoding="utf-8")
        command = [
            sys.executable,
            "-m",
            "pip",
            "download",
            "--disable-pip-version-check",
            "--quiet",
            "--no-deps",
            "--only-binary=:all:",
            *PLATFORM,
            "--require-hashes",
            "-r",
            str(requirements),
            "-d",
            str(Path(tmp) / "wheels"),
        ]
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=600, check=False)
        except (OSError, subprocess.TimeoutExpired) as error:
            raise SetUpError(f"could not run pip to download ROS 2's interface packages: {error}") from None
        if done.returncode != 0:
            tail = "\n".join((done.stderr or done.stdout).strip().splitlines()[-6:])
            names = ", ".join(p.name for p in pins)
            raise SetUpError(f"could not download ROS 2's interface packages from PyPI ({names}):\n{tail}")
        for path in (Path(tmp) / "wheels").glob("*.whl"):
            os.replace(path, cache / path.name)


def extract(wheels: list[Path], target: Path, stamp: str) -> int:
    """Write the wheels' definitions to ``target`` (replacing it whole) and their type hashes to
    ``target/type_hashes.json``; returns how many definitions."""
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}-"))
    hashes: dict[str, str] = {}
    count = 0
    try:
        for wheel in wheels:
            with zipfile.ZipFile(wheel) as archive:
                for member in archive.namelist():
                    match = _DEFINITION.search(member)
                    if match is None:
                        continue
                    data = archive.read(member)
                    if match["file"].endswith(".json"):
                        for entry in json.loads(data).get("type_hashes", []):
                            hashes[entry["type_name"]] = entry["hash_string"]
                        continue
                    path = staging / match["pkg"] / match["kind"] / match["file"]
                    path.parent.mkdir(parents=True, exist_ok=True)
                    path.write_bytes(data)
                    count += 1
        text = json.dumps(dict(sorted(hashes.items())), indent=1) + "\n"
        (staging / HASHES_FILE).write_text(text, encoding="utf-8")
        (staging / STAMP_FILE).write_text(stamp + "\n", encoding="utf-8")
        _readable_by_all(staging)
        if target.exists():
            shutil.rmtree(target)
        os.replace(staging, target)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return count


def _readable_by_all(folder: Path) -> None:
    """Every node process reads these, sandboxed ones as another user: whatever the umask (and
    mkdtemp's 0700), folders 0755 and files 0644."""
    folder.chmod(0o755)
    for path in folder.rglob("*"):
        path.chmod(0o755 if path.is_dir() else 0o644)


def lock_stamp(lock_text: str) -> str:
    return hashlib.sha256(lock_text.encode()).hexdigest()


def is_current(target: Path, lock_text: str) -> bool:
    stamp = target / STAMP_FILE
    return stamp.is_file() and stamp.read_text(encoding="utf-8").strip() == lock_stamp(lock_text)


def ensure(lock: Path = LOCK, target: Path = TARGET, cache: Path | None = None) -> str:
    """Make ``target`` hold the definitions ``lock`` pins; says what it did ("" if nothing)."""
    lock_text = lock.read_text(encoding="utf-8")
    if is_current(target, lock_text):
        return ""
    pins = read_lock(lock_text)
    cache = cache or cache_dir()
    missing = [p for p in pins if not cache.is_dir() or cached_wheel(p, cache) is None]
    if missing:
        download(missing, cache)
    wheels = []
    for pin in pins:
        wheel = cached_wheel(pin, cache)
        if wheel is None:
            raise SetUpError(f"pip downloaded no wheel of {pin.name}=={pin.version} with the pinned hash")
        wheels.append(wheel)
    count = extract(wheels, target, lock_stamp(lock_text))
    fetched = f"{len(missing)} downloaded, {len(pins) - len(missing)} from {cache}"
    return f"ROS 2's interface definitions: {count} files from {len(pins)} wheels ({fetched}) into {target}"


def main() -> int:
    try:
        done = ensure()
        if done:
            print(done)
    except (SetUpError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
