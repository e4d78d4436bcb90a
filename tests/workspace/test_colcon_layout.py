"""A workspace as colcon finds it: packages by package.xml at any depth, named by ``<name>``; their
executables from setup.py/setup.cfg console_scripts or CMake's install(PROGRAMS); colcon's skips;
and the files that cannot be read, each one error naming file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from node_runtime.ament.entry_points import EntryPoint
from node_runtime.ament.index import ExecutableNotFoundError, PackageIndex, WorkspaceError
from node_runtime.ament.workspace import find_packages
from server.host.processes.command import node_command

from .tutorial_packages import examples_clone, manifest, python_package, write

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "workspace"


def test_nested_packages_are_named_by_their_manifest(tmp_path: Path) -> None:
    examples_clone(tmp_path)
    found = find_packages(tmp_path)
    assert set(found.packages) == {
        "examples_rclpy_minimal_publisher",
        "examples_rclpy_minimal_subscriber",
        "examples_rclpy_executors",
    }  # and not "examples", the clone's folder that holds them
    publisher = found.packages["examples_rclpy_minimal_publisher"]
    assert publisher.path == tmp_path / "src/examples/rclpy/topics/minimal_publisher"
    exe = PackageIndex(workspace=tmp_path).resolve(
        "examples_rclpy_minimal_publisher", "publisher_member_function"
    )
    assert exe.entry_point == EntryPoint(
        publisher.path,
        "examples_rclpy_minimal_publisher.publisher_member_function",
        "main",
        "publisher_member_function",
        f"{publisher.path / 'setup.py'}:11",  # the script's own line
    )
    assert exe.file == publisher.path / "examples_rclpy_minimal_publisher/publisher_member_function.py"
    assert exe.target == exe.entry_point
    with pytest.raises(ExecutableNotFoundError, match="composed"):  # an ament_python package's modules are
        PackageIndex(workspace=tmp_path).resolve("examples_rclpy_executors", "talker")  # not executables


def test_colcon_skips_ignored_hidden_and_its_own_output_folders(tmp_path: Path) -> None:
    for folder in ("pkg_a", "skipped/pkg_b", ".hidden/pkg_c", "nested/pkg_d/inner"):
        write(tmp_path / "src" / folder, {"package.xml": manifest(folder.replace("/", "_").strip("."))})
    (tmp_path / "src/skipped/COLCON_IGNORE").write_text("")
    found = find_packages(tmp_path / "src")  # a workspace without src/: packages right in it
    assert set(found.packages) == {"pkg_a", "nested_pkg_d_inner"} and not found.problems
    for leftover in ("build", "install", "log"):  # what a real colcon leaves next to the packages
        write(tmp_path / "src" / leftover / "pkg_a", {"package.xml": manifest("pkg_a")})
    assert set(find_packages(tmp_path / "src").packages) == {"pkg_a", "nested_pkg_d_inner"}
    assert not find_packages(tmp_path / "src").problems


def test_setup_cfg_and_setup_py_with_a_variable_both_declare_scripts(tmp_path: Path) -> None:
    folder = tmp_path / "src" / "tools"
    python_package(folder, "tools", [], {"go": "def run():\n    pass\n"})
    (folder / "setup.py").write_text(
        "from setuptools import setup\nname = 'tools'\nscripts = [f'go = {name}.go:run']\n"
        "setup(name=name, entry_points={'console_scripts': scripts + []})\n"
    )
    with pytest.raises(WorkspaceError, match=r"setup\.py:4: console_scripts is not a literal list"):
        PackageIndex(workspace=tmp_path).executables_of("tools")
    (folder / "setup.py").write_text("from setuptools import setup\nsetup()\n")
    (folder / "setup.cfg").write_text(
        "[metadata]\nname = tools\n\n[options.entry_points]\nconsole_scripts =\n    go = tools.go:run\n"
    )
    exe = PackageIndex(workspace=tmp_path).resolve("tools", "go")
    assert exe.entry_point is not None and exe.entry_point.declared_at == f"{folder / 'setup.cfg'}:6"
    assert (exe.entry_point.module, exe.entry_point.function) == ("tools.go", "run")


def test_cmake_install_programs_are_the_executables(tmp_path: Path) -> None:
    write(
        tmp_path / "src" / "rocketship",
        {
            "package.xml": manifest("rocketship", "ament_cmake"),
            "CMakeLists.txt": (
                "project(rocketship)\n# install(PROGRAMS src/commented_out.py DESTINATION lib)\n"
                "install(PROGRAMS\n  src/keyboard_manager.py\n  DESTINATION lib/${PROJECT_NAME} )\n"
                "install(PROGRAMS scripts/${PROJECT_NAME}_tool.py DESTINATION lib/${PROJECT_NAME}"
                " RENAME tool)\nament_package()\n"
            ),
            "src/keyboard_manager.py": "x = 1\n",
            "src/not_installed.py": "x = 1\n",
        },
    )
    exes = PackageIndex(workspace=tmp_path).executables_of("rocketship")
    assert exes["keyboard_manager.py"].file == tmp_path / "src/rocketship/src/keyboard_manager.py"
    assert exes["tool"].file == tmp_path / "src/rocketship/scripts/rocketship_tool.py"
    assert "not_installed.py" not in exes and "commented_out.py" not in exes
    assert exes["countdown"].builtin is not None  # the lab's own executables of that package stay


def test_the_handouts_files_without_a_manifest_keep_the_simple_rule() -> None:
    index = PackageIndex(workspace=EXAMPLES)
    assert (
        index.resolve("rocketship", "keyboard_manager.py").file
        == EXAMPLES / "src/rocketship/src/keyboard_manager.py"
    )
    drone = index.resolve("simple_control", "keyboard_manager")
    assert drone.file is not None and drone.entry_point is None


def test_two_packages_with_one_name_is_one_error_naming_both(tmp_path: Path) -> None:
    write(
        tmp_path / "src",
        {
            "a/dup/package.xml": manifest("dup"),
            "b/dup/package.xml": manifest("dup"),
            "fine/package.xml": manifest("fine"),
        },
    )
    index = PackageIndex(workspace=tmp_path)
    with pytest.raises(WorkspaceError) as caught:
        index.executables_of("dup")
    assert str(caught.value) == (
        f"{tmp_path / 'src/b/dup/package.xml'}: two packages are named 'dup': {tmp_path / 'src/a/dup'} and "
        f"{tmp_path / 'src/b/dup'}"
    )
    assert "fine" in index.names() and "dup" not in index.names()  # the other packages are unaffected


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "<package format='3'>\n  <name>x</name>\n  <oops>\n</package>\n",
            r"package\.xml:4: package\.xml does not parse",
        ),
        ("<package format='3'>\n</package>\n", r"package\.xml: it has no <name>"),
        ("<manifest><name>x</name></manifest>\n", r"the root element is <manifest>, not <package>"),
    ],
)
def test_a_manifest_that_cannot_be_read_names_its_file(tmp_path: Path, text: str, message: str) -> None:
    write(tmp_path / "src", {"bad/package.xml": text})
    with pytest.raises(WorkspaceError, match=message):
        PackageIndex(workspace=tmp_path).executables_of("bad")


def test_a_console_script_that_is_not_name_equals_module_colon_function(tmp_path: Path) -> None:
    python_package(tmp_path / "src" / "p", "p", ["talker = p.talker"], {})
    with pytest.raises(WorkspaceError, match=r"setup\.py:\d+: console script 'talker = p\.talker' is not"):
        PackageIndex(workspace=tmp_path).executables_of("p")


def test_a_setup_py_that_does_not_parse_names_its_line(tmp_path: Path) -> None:
    python_package(tmp_path / "src" / "p", "p", [], {})
    (tmp_path / "src/p/setup.py").write_text("from setuptools import setup\nsetup(\n")
    with pytest.raises(WorkspaceError, match=r"p/setup\.py:2: SyntaxError"):
        PackageIndex(workspace=tmp_path).executables_of("p")


def test_a_console_script_runs_through_the_runners_entry_point_mode(tmp_path: Path) -> None:
    examples_clone(tmp_path)
    exe = PackageIndex(workspace=tmp_path).resolve("examples_rclpy_executors", "composed")
    argv = node_command(exe.target, ["--ros-args", "-r", "__node:=n"]).argv
    root = tmp_path / "src/examples/rclpy/executors"
    assert argv[-8:] == [
        "--entry-point",
        str(root),
        "examples_rclpy_executors.composed:main",
        "composed",
        f"{root / 'setup.py'}:11",
        "--ros-args",
        "-r",
        "__node:=n",
    ]
    assert argv[argv.index("-m") + 1] == "node_runtime.process.runner"
