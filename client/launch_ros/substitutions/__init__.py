"""launch_ros's substitutions: ``FindPackageShare('pkg')`` and ``FindPackagePrefix('pkg')``."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ament_index_python.packages import PackageNotFoundError, get_package_prefix, get_package_share_directory
from launch import Substitution
from launch.substitutions import SubstitutionFailure
from launch.utilities import perform_typed

if TYPE_CHECKING:
    from launch import LaunchContext


class FindPackageShare(Substitution):
    def __init__(self, package: Any) -> None:
        self.__package = package

    @property
    def package(self) -> Any:
        return self.__package

    def describe(self) -> str:
        return f"FindPackageShare(pkg={self.__package!r})"

    def perform(self, context: LaunchContext) -> str:
        try:
            return get_package_share_directory(perform_typed(context, self.__package))
        except PackageNotFoundError as exc:
            raise SubstitutionFailure(str(exc.args[0]) if exc.args else str(exc)) from None

    def find(self, package_name: str) -> str:
        return get_package_share_directory(package_name)


class FindPackagePrefix(FindPackageShare):
    def perform(self, context: LaunchContext) -> str:
        try:
            return get_package_prefix(perform_typed(context, self.package))
        except PackageNotFoundError as exc:
            raise SubstitutionFailure(str(exc.args[0]) if exc.args else str(exc)) from None


__all__ = ["FindPackagePrefix", "FindPackageShare"]
