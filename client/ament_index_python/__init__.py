"""ROS 2's ``ament_index_python`` for a lab: where a package's files are, among the lab's packages
and the workspace's (as ``$(find-pkg-share PKG)`` and ``ros2lab pkg prefix`` find them)."""

from ament_index_python.packages import (
    PackageNotFoundError,
    get_package_prefix,
    get_package_share_directory,
    get_package_share_path,
    get_packages_with_prefixes,
)

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]
