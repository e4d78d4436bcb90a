"""The files ``ros2 pkg create`` writes, as text: package.xml (format 3), and for ament_python
setup.py, setup.cfg, the resource marker, ``__init__.py``, the three linter tests and the node
with a ``main()``; for ament_cmake CMakeLists.txt and the C++ node. Each is what ros2pkg's
templates expand to for the same options, so a package made here builds with a real colcon too.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

APACHE_HEADER = """\
# Copyright {year} Open Source Robotics Foundation, Inc.
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.
"""

LINTER_TESTS = {
    "test_copyright.py": (
        2015,
        """
from ament_copyright.main import main
import pytest


# Remove the `skip` decorator once the source file(s) have a copyright header
@pytest.mark.skip(reason='No copyright header has been placed in the generated source file.')
@pytest.mark.copyright
@pytest.mark.linter
def test_copyright():
    rc = main(argv=['.', 'test'])
    assert rc == 0, 'Found errors'
""",
    ),
    "test_flake8.py": (
        2017,
        """
from ament_flake8.main import main_with_errors
import pytest


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8():
    rc, errors = main_with_errors(argv=[])
    assert rc == 0, \\
        'Found %d code style errors / warnings:\\n' % len(errors) + \\
        '\\n'.join(errors)
""",
    ),
    "test_pep257.py": (
        2015,
        """
from ament_pep257.main import main
import pytest


@pytest.mark.linter
@pytest.mark.pep257
def test_pep257():
    rc = main(argv=['.', 'test'])
    assert rc == 0, 'Found code style errors / warnings'
""",
    ),
}

TEST_DEPENDS = {
    "ament_python": ["ament_copyright", "ament_flake8", "ament_pep257", "python3-pytest"],
    "ament_cmake": ["ament_lint_auto", "ament_lint_common"],
}


@dataclass(frozen=True)
class PackageSpec:
    """``ros2 pkg create``'s options, after its defaults."""

    name: str
    build_type: str = "ament_cmake"
    description: str = "TODO: Package description"
    license: str = "TODO: License declaration"
    maintainer_name: str = "user"
    maintainer_email: str = "user@todo.todo"
    dependencies: list[str] = field(default_factory=list)
    node_name: str | None = None


def _group(tag: str, names: list[str]) -> str:
    return "".join(f"  <{tag}>{escape(n)}</{tag}>\n" for n in names) + "\n" if names else ""


def package_xml(spec: PackageSpec) -> str:
    buildtool = ["ament_cmake"] if spec.build_type == "ament_cmake" else []
    return (
        '<?xml version="1.0"?>\n'
        '<?xml-model href="http://download.ros.org/schema/package_format3.xsd" '
        'schematypens="http://www.w3.org/2001/XMLSchema"?>\n'
        '<package format="3">\n'
        f"  <name>{escape(spec.name)}</name>\n"
        "  <version>0.0.0</version>\n"
        f"  <description>{escape(spec.description)}</description>\n"
        f"  <maintainer email={quoteattr(spec.maintainer_email)}>{escape(spec.maintainer_name)}</maintainer>\n"
        f"  <license>{escape(spec.license)}</license>\n\n"
        + _group("buildtool_depend", buildtool)
        + _group("depend", spec.dependencies)
        + _group("test_depend", TEST_DEPENDS[spec.build_type])
        + f"  <export>\n    <build_type>{spec.build_type}</build_type>\n  </export>\n</package>\n"
    )


def setup_py(spec: PackageSpec) -> str:
    script = f"            '{spec.node_name} = {spec.name}.{spec.node_name}:main'\n" if spec.node_name else ""
    return f"""\
from setuptools import find_packages, setup

package_name = '{spec.name}'

setup(
    name=package_name,
    version='0.0.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages',
            ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='{spec.maintainer_name}',
    maintainer_email='{spec.maintainer_email}',
    description='{spec.description}',
    license='{spec.license}',
    tests_require=['pytest'],
    entry_points={{
        'console_scripts': [
{script}        ],
    }},
)
"""


def setup_cfg(spec: PackageSpec) -> str:
    return f"[develop]\nscript_dir=$base/lib/{spec.name}\n[install]\ninstall_scripts=$base/lib/{spec.name}\n"


def python_node(spec: PackageSpec) -> str:
    return f"def main():\n    print('Hi from {spec.name}.')\n\n\nif __name__ == '__main__':\n    main()\n"


def cmake_lists(spec: PackageSpec) -> str:
    finds = "".join(f"find_package({d} REQUIRED)\n" for d in spec.dependencies) or (
        "# uncomment the following section in order to fill in\n"
        "# further dependencies manually.\n"
        "# find_package(<dependency> REQUIRED)\n"
    )
    node = ""
    if spec.node_name:
        n = spec.node_name
        deps = "".join(f'  "{d}"\n' for d in spec.dependencies)
        node = (
            f"\nadd_executable({n} src/{n}.cpp)\n"
            f"target_include_directories({n} PUBLIC\n"
            "  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n"
            "  $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)\n"
            f"target_compile_features({n} PUBLIC c_std_99 cxx_std_17)  # Require C99 and C++17\n"
            + (f"ament_target_dependencies(\n  {n}\n{deps})\n" if deps else "")
            + f"\ninstall(TARGETS {n}\n  DESTINATION lib/${{PROJECT_NAME}})\n"
        )
    return (
        f"cmake_minimum_required(VERSION 3.8)\nproject({spec.name})\n\n"
        'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")\n'
        "  add_compile_options(-Wall -Wextra -Wpedantic)\nendif()\n\n"
        "# find dependencies\nfind_package(ament_cmake REQUIRED)\n" + finds + node + "\n"
        "if(BUILD_TESTING)\n"
        "  find_package(ament_lint_auto REQUIRED)\n"
        "  # the following line skips the linter which checks for copyrights\n"
        "  # comment the line when a copyright and license is added to all source files\n"
        "  set(ament_cmake_copyright_FOUND TRUE)\n"
        "  # the following line skips cpplint (only works in a git repo)\n"
        "  # comment the line when this package is in a git repo and when\n"
        "  # a copyright and license is added to all source files\n"
        "  set(ament_cmake_cpplint_FOUND TRUE)\n"
        "  ament_lint_auto_find_test_dependencies()\n"
        "endif()\n\nament_package()\n"
    )


def cpp_node(spec: PackageSpec) -> str:
    return (
        "#include <cstdio>\n\nint main(int argc, char ** argv)\n{\n  (void) argc;\n  (void) argv;\n\n"
        f'  printf("hello world {spec.name} package\\n");\n  return 0;\n}}\n'
    )


def package_files(spec: PackageSpec) -> dict[str, str]:
    """Path inside the package folder → text, in the order ``ros2 pkg create`` writes them."""
    files = {"package.xml": package_xml(spec)}
    if spec.build_type == "ament_python":
        files |= {
            "setup.py": setup_py(spec),
            "setup.cfg": setup_cfg(spec),
            f"resource/{spec.name}": "",
            f"{spec.name}/__init__.py": "",
        }
        files |= {
            f"test/{name}": APACHE_HEADER.format(year=year) + body
            for name, (year, body) in LINTER_TESTS.items()
        }
        if spec.node_name:
            files[f"{spec.name}/{spec.node_name}.py"] = python_node(spec)
    else:
        files["CMakeLists.txt"] = cmake_lists(spec)
        if spec.node_name:
            files[f"src/{spec.node_name}.cpp"] = cpp_node(spec)
    return files
