"""A PEP 517 build backend for the client distribution (client/pyproject.toml): exactly the modules
and data files ``[tool.teleop-lab-client]`` lists, found in its ``roots``, in a pure-Python wheel.

The sdist holds those same files at their package paths beside the pyproject and this backend, so
a wheel built from the sdist (whose only root that exists is ".") ships the same files.
"""

from __future__ import annotations

import base64
import hashlib
import io
import tarfile
import tomllib
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

PROJECT = Path(__file__).resolve().parents[1]
TOOL = "teleop-lab-client"
WHEEL_TAG = "py3-none-any"
# A fixed time for every archived file, so two builds of the same tree give the same bytes.
EPOCH = (2026, 1, 1, 0, 0, 0)


class BuildError(RuntimeError):
    """The pyproject names a module or file that is not there."""


@dataclass(frozen=True)
class Distribution:
    name: str
    version: str
    metadata: str  # METADATA (core metadata 2.1)
    files: dict[str, Path]  # path in the archive → file on disk

    @property
    def stem(self) -> str:
        return f"{self.name.replace('-', '_')}-{self.version}"


def _module_file(roots: list[Path], module: str, package: bool) -> tuple[str, Path]:
    rel = Path(*module.split("."))
    rel = rel / "__init__.py" if package else rel.with_suffix(".py")
    for root in roots:
        if (root / rel).is_file():
            return rel.as_posix(), root / rel
    if not package:
        return _module_file(roots, module, package=True)
    raise BuildError(f"{module}: no {rel} in {', '.join(str(r) for r in roots)}")


def collect(project: Path = PROJECT) -> Distribution:
    """What the wheel ships, as the pyproject declares it."""
    config = tomllib.loads((project / "pyproject.toml").read_text(encoding="utf-8"))
    meta: dict[str, Any] = config["project"]
    tool: dict[str, Any] = config["tool"][TOOL]
    roots = [(project / r).resolve() for r in tool["roots"] if (project / r).is_dir()]
    files: dict[str, Path] = {}
    for package in tool["packages"]:
        rel, init = _module_file(roots, package, package=True)
        for path in sorted(init.parent.glob("*.py")):
            files[f"{Path(rel).parent.as_posix()}/{path.name}"] = path
    for module in tool["modules"]:
        rel, path = _module_file(roots, module, package=False)
        files[rel] = path
    for pattern in tool["data"]:
        found = next((sorted(r.glob(pattern)) for r in roots if any(r.glob(pattern))), [])
        if not found:
            hint = (
                " (ROS 2's definitions: run `python -m node_runtime.ros_wheels` first)"
                if "ros_interfaces" in pattern
                else ""
            )
            raise BuildError(f"no file matches {pattern}{hint}")
        root = next(r for r in roots if any(r.glob(pattern)))
        files.update({p.relative_to(root).as_posix(): p for p in found})
    lines = [
        "Metadata-Version: 2.1",
        f"Name: {meta['name']}",
        f"Version: {meta['version']}",
        f"Summary: {meta['description']}",
        f"Requires-Python: {meta['requires-python']}",
        f"License: {meta['license']}",
        *(f"Requires-Dist: {d}" for d in meta["dependencies"]),
    ]
    return Distribution(meta["name"], meta["version"], "\n".join(lines) + "\n", files)


def _record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def _write(archive: zipfile.ZipFile, name: str, data: bytes) -> None:
    info = zipfile.ZipInfo(name, EPOCH)
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = 0o644 << 16
    archive.writestr(info, data)


def build_wheel(
    wheel_directory: str, config_settings: dict[str, Any] | None = None, metadata_directory: str | None = None
) -> str:
    dist = collect()
    info = f"{dist.stem}.dist-info"
    wheel_meta = (
        f"Wheel-Version: 1.0\nGenerator: {TOOL} wheel_backend\nRoot-Is-Purelib: true\nTag: {WHEEL_TAG}\n"
    )
    contents = {name: path.read_bytes() for name, path in sorted(dist.files.items())}
    contents[f"{info}/METADATA"] = dist.metadata.encode()
    contents[f"{info}/WHEEL"] = wheel_meta.encode()
    record = [_record_line(name, data) for name, data in contents.items()] + [f"{info}/RECORD,,"]
    filename = f"{dist.stem}-{WHEEL_TAG}.whl"
    with zipfile.ZipFile(Path(wheel_directory) / filename, "w") as archive:
        for name, data in contents.items():
            _write(archive, name, data)
        _write(archive, f"{info}/RECORD", ("\n".join(record) + "\n").encode())
    return filename


def build_sdist(sdist_directory: str, config_settings: dict[str, Any] | None = None) -> str:
    dist = collect()
    extra = {
        "pyproject.toml": PROJECT / "pyproject.toml",
        "_build/wheel_backend.py": Path(__file__).resolve(),
    }
    filename = f"{dist.stem}.tar.gz"
    with tarfile.open(Path(sdist_directory) / filename, "w:gz") as archive:
        entries = {**extra, **dist.files}
        for name, path in sorted(entries.items()):
            archive.add(path, arcname=f"{dist.stem}/{name}", filter=_normalized)
        pkg_info = dist.metadata.encode()
        member = tarfile.TarInfo(f"{dist.stem}/PKG-INFO")
        member.size = len(pkg_info)
        member.mode = 0o644
        archive.addfile(member, io.BytesIO(pkg_info))
    return filename


def _normalized(member: tarfile.TarInfo) -> tarfile.TarInfo:
    member.uid = member.gid = 0
    member.uname = member.gname = ""
    member.mtime = 0
    return member


def get_requires_for_build_wheel(config_settings: dict[str, Any] | None = None) -> list[str]:
    return []


def get_requires_for_build_sdist(config_settings: dict[str, Any] | None = None) -> list[str]:
    return []
