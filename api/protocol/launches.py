"""What the launch routes take and answer (api/routes/launches.py): ``ros2 launch`` and ``ros2 run``
against the running graph, a launch's nodes, and what its node processes printed. The frames of
its output socket are api/protocol/frames.py's."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

MAX_ARGS = 64  # launch arguments, parameters or remappings in one request
Short = Annotated[str, StringConstraints(max_length=256)]
Value = Annotated[str, StringConstraints(max_length=4096)]
Scalar = bool | int | float | Value
ParamValue = Scalar | Annotated[list[Scalar], Field(max_length=256)]


class LaunchRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    file: Value = Field(
        description="a launch file's name inside `package`, or a path: inside the workspace where the "
        "lab serves others (a class's worlds), any path on a single lab on loopback",
        examples=["rocket.launch"],
    )
    package: Short | None = Field(default=None, examples=["rocketship"])
    args: dict[Short, Value] = Field(
        default_factory=dict, max_length=MAX_ARGS, examples=[{"start_delay": "2.0"}]
    )


class RunRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    package: Short = Field(examples=["rocketship"])
    executable: Short = Field(examples=["keyboard_manager.py"])
    name: Short | None = None
    parameters: dict[Short, ParamValue] = Field(default_factory=dict, max_length=MAX_ARGS)
    remappings: dict[Short, Short] = Field(default_factory=dict, max_length=MAX_ARGS)


class LaunchedNodeOut(BaseModel):
    """One node of a launch or run, in the lab's process or a node process of its own."""

    name: str = Field(
        description="its fully qualified name once it runs in the lab, else its name or executable"
    )
    pkg: str
    exec: str
    error: str | None = Field(description="why it did not start, or null")
    state: str | None = Field(
        description="a node in the lab: active, crashed or destroyed; a node process: waiting, running, died "
        "or stopped"
    )
    exit_code: int | None = Field(description="a node process's exit code, once it ended")
    process: str | None = Field(description="its node process's label, as ros2 launch prints it")


class LaunchGroupOut(BaseModel):
    """A launch or run: the nodes it started, stopped together."""

    id: str
    file: str = Field(description="the launch file, or the package and executable run")
    messages: list[str] = Field(description="a Python launch file's LogInfo lines and prints, and refusals")
    nodes: list[LaunchedNodeOut]


class ProcessOutputOut(BaseModel):
    label: str
    lines: list[str] = Field(description="its last lines (at most 200, each cut at 4096 characters)")
    printed: int = Field(description="lines it printed in all")


class LaunchOutputOut(BaseModel):
    group: LaunchGroupOut
    processes: list[ProcessOutputOut] = Field(description="each node or command process of the group")
