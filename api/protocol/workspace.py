"""What the workspace routes take and answer (api/routes/workspace.py): the student's files, each
with its version, new packages, the lab's templates, and zips of the workspace."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

Name = Annotated[str, StringConstraints(max_length=256)]
Text = Annotated[str, StringConstraints(max_length=1024)]


class WorkspaceEntry(BaseModel):
    """A file or folder of the workspace."""

    path: str = Field(description="POSIX, relative to the workspace")
    kind: Literal["file", "dir"]
    size: int = Field(description="bytes (0 for a folder)")
    etag: str | None = Field(description="the file's version; null for a folder")


class WorkspaceTree(BaseModel):
    """The workspace's files and folders, sorted by path, down to the depth a path may have."""

    version: str = Field(description="changes with any change in the tree ('empty' for none)")
    entries: list[WorkspaceEntry]
    too_deep: int = Field(
        description="entries just past the depth limit (WorkspaceLimits.max_depth, 16 folders): "
        "neither they nor what they hold are listed, zipped or served"
    )
    too_deep_example: str | None = Field(description="the path of one of them, or null")


class FileText(BaseModel):
    """A workspace file's text and version (also in the ``ETag`` header)."""

    path: str = Field(description="POSIX, relative to the workspace")
    text: str
    etag: str = Field(description="its version: send it back as If-Match to save over it")


class Saved(BaseModel):
    path: str
    etag: str = Field(description="the file's version now")
    size: int = Field(description="bytes")


class Deleted(BaseModel):
    path: str
    deleted: int = Field(description="how many files went")


class Renamed(BaseModel):
    path: str = Field(description="where it is now")


class PackageCreated(BaseModel):
    name: str
    path: str = Field(description="its folder, src/<name>")
    files: list[str] = Field(description="the files written")


class Template(BaseModel):
    """A starting file of the lab, with ``# TODO`` where the student's code goes; ``{package}`` in its
    path and text stands for the package it goes in."""

    name: str
    title: str
    description: str
    path: str = Field(description="a suggested path in the workspace")
    text: str


class Written(BaseModel):
    written: list[str] = Field(description="the files the zip wrote")


class SaveRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    text: str


class RenameRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    source: Text
    target: Text


class PackageRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    name: Name = Field(examples=["simple_control"])
    build_type: Literal["ament_python", "ament_cmake"] = "ament_python"
    node_name: Name | None = Field(default=None, examples=["keyboard_manager"])
    dependencies: list[Name] = Field(default_factory=list, max_length=64)
    description: Text | None = None
    license: Name | None = None
