"""What a workspace refuses, each error naming the problem; api/errors.py gives each its status."""

from __future__ import annotations


class WorkspaceFileError(Exception):
    """Anything a workspace refuses; changes nothing."""


class BadPathError(WorkspaceFileError, ValueError):
    """A path that leaves the workspace or that ROS and colcon would not accept (422)."""


class NoWorkspaceError(WorkspaceFileError, LookupError):
    """This lab has no workspace folder (404)."""


class FileMissingError(WorkspaceFileError, LookupError):
    """No file or folder at this path (404)."""


class NotTextError(WorkspaceFileError):
    """A file that is not UTF-8 text, or text holding a NUL (415)."""


class TakenError(WorkspaceFileError):
    """The target exists already: a rename's target, a package's name (409)."""


class ChangedError(WorkspaceFileError):
    """The file is not the version the caller read (``If-Match``), or exists for a create-only
    save (``If-None-Match: *``) (412); ``etag`` is its current version (None: gone)."""

    def __init__(self, message: str, etag: str | None) -> None:
        super().__init__(message)
        self.etag = etag


class TooLargeError(WorkspaceFileError):
    """Over a size or count limit of a file, the workspace or an upload (413)."""


class BadArchiveError(WorkspaceFileError, ValueError):
    """An upload that is not a zip this workspace takes: a bomb, a symlink, a path out (422)."""


class BadPackageError(WorkspaceFileError, ValueError):
    """A package name, node name or dependency ``ros2 pkg create`` would refuse (422)."""
