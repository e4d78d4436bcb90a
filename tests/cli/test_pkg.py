"""``ros2lab pkg``: create writes what ``ros2 pkg create`` writes (tests/workspace/ros2_pkg_create holds
ros2pkg's templates expanded for the same options, file by file), and list/executables/prefix
print as ``ros2 pkg`` prints. None of these needs a lab server (the workspace is given)."""

from __future__ import annotations

from pathlib import Path

import pytest

from server.cli import main

EXPECTED = Path(__file__).resolve().parents[1] / "workspace" / "ros2_pkg_create"
NO_LAB = "http://127.0.0.1:9"  # nothing listens: these verbs must not need one
EMPTY_FOLDERS = {
    "rocket_parts": {"include", "include/rocket_parts"}
}  # ros2 makes them; git keeps no empty folder
MAINTAINER = ["--maintainer-name", "student", "--maintainer-email", "student@example.com"]


def tree(root: Path) -> tuple[dict[str, str], set[str]]:
    files = {str(p.relative_to(root)): p.read_text() for p in root.rglob("*") if p.is_file()}
    folders = {str(p.relative_to(root)) for p in root.rglob("*") if p.is_dir()}
    return files, folders


def expected_tree(package: str) -> tuple[dict[str, str], set[str]]:
    files, folders = tree(EXPECTED / package)
    return {
        name.removesuffix(".expected"): text for name, text in files.items()
    }, folders | EMPTY_FOLDERS.get(package, set())


@pytest.mark.parametrize(
    ("package", "options"),
    [
        # The handout's own command, as written (and a maintainer, so the file does not depend on who runs it).
        ("simple_control", ["--build-type", "ament_python", "--node-name", "keyboard_manager"]),
        (
            "rocket_parts",
            [
                "--dependencies",
                "rclcpp",
                "std_msgs",
                "--license",
                "MIT",
                "--description",
                "Parts of a rocket",
                "--node-name",
                "engine",
            ],
        ),
    ],
)
def test_pkg_create_writes_what_ros2_pkg_create_writes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], package: str, options: list[str]
) -> None:
    code = main(
        [
            "--url",
            NO_LAB,
            "pkg",
            "create",
            *options,
            *MAINTAINER,
            package,
            "--destination-directory",
            str(tmp_path),
        ]
    )
    out = capsys.readouterr().out
    assert code == 0
    files, folders = tree(tmp_path / package)
    want_files, want_folders = expected_tree(package)
    assert sorted(files) == sorted(want_files)
    for name, text in want_files.items():
        assert files[name] == text, name
    assert folders == want_folders
    assert out.startswith(f"going to create a new package\npackage name: {package}\n")
    assert "maintainer: ['student <student@example.com>']\n" in out
    assert f"creating {tmp_path / package / 'package.xml'}\n" in out


def test_pkg_create_refuses_an_existing_folder_and_a_bad_name(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "taken").mkdir()
    assert main(["pkg", "create", "taken", "--destination-directory", str(tmp_path)]) == 1
    assert f"The directory already exists: {tmp_path / 'taken'}" in capsys.readouterr().err
    assert main(["pkg", "create", "Bad-Name", "--destination-directory", str(tmp_path)]) == 1
    assert "Invalid package name 'Bad-Name'" in capsys.readouterr().err
    assert (
        main(
            [
                "pkg",
                "create",
                "test",
                "--build-type",
                "ament_python",
                "--destination-directory",
                str(tmp_path),
            ]
        )
        == 1
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken"]  # nothing written
    # and a good name in the same place works
    assert main(["pkg", "create", "good_name", "--destination-directory", str(tmp_path), *MAINTAINER]) == 0
    assert (tmp_path / "good_name" / "CMakeLists.txt").is_file()


def test_pkg_list_executables_and_prefix_print_as_ros2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    ws = tmp_path / "ws"
    nested = ws / "src" / "nested"
    create = ["pkg", "create", "--build-type", "ament_python", "--node-name", "talker", "demo", *MAINTAINER]
    assert main([*create, "--destination-directory", str(nested)]) == 0
    capsys.readouterr()
    workspace = ["--workspace", str(ws), "--url", NO_LAB]
    assert main(["pkg", "list", *workspace]) == 0
    names = capsys.readouterr().out.splitlines()
    assert "demo" in names and "rocketship" in names and names == sorted(names)
    assert main(["pkg", "executables", "demo", *workspace]) == 0
    assert capsys.readouterr().out == "demo talker\n"
    assert main(["pkg", "executables", "demo", "--full-path", *workspace]) == 0
    assert capsys.readouterr().out == f"{ws / 'src/nested/demo/demo/talker.py'}\n"
    assert main(["pkg", "executables", *workspace]) == 0
    every = capsys.readouterr().out.splitlines()
    assert "demo talker" in every and "rocketship countdown" in every
    assert main(["pkg", "prefix", "demo", *workspace]) == 0
    assert capsys.readouterr().out == f"{ws / 'src/nested/demo'}\n"
    assert main(["pkg", "prefix", "nope", *workspace]) == 1
    assert capsys.readouterr().err == "Package not found\n"
    assert main(["pkg", "executables", "nope", *workspace]) == 1
    assert capsys.readouterr().err == "Package 'nope' not found\n"


def test_the_workspace_comes_from_the_environment(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    ws = tmp_path / "elsewhere"
    assert main(["pkg", "create", "from_env", "--destination-directory", str(ws / "src"), *MAINTAINER]) == 0
    capsys.readouterr()
    monkeypatch.chdir(tmp_path)
    assert main(["--url", NO_LAB, "pkg", "list"]) == 0
    assert "from_env" not in capsys.readouterr().out  # ./workspace, which has none
    monkeypatch.setenv("ROS2LAB_WORKSPACE", str(ws))
    assert main(["--url", NO_LAB, "pkg", "list"]) == 0
    assert "from_env" in capsys.readouterr().out.splitlines()
