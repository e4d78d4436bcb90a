"""ROS 2 action definitions (``.action`` text) and the types rosidl generates from one.

An action ``pkg/action/Name`` is three messages written in one file (goal, result, feedback,
between ``---`` lines), and on the wire it is what rosidl derives from them: the services
``Name_SendGoal`` (goal id and goal → accepted and stamp) and ``Name_GetResult`` (goal id →
status and result), and the message ``Name_FeedbackMessage`` (goal id and feedback). Cancelling
and the status topic use ``action_msgs``' own types, the same for every action.
"""

from __future__ import annotations

from dataclasses import dataclass

from node_runtime.msgs.idl import (
    SERVICE_SEPARATOR,
    DefinitionError,
    MessageSpec,
    ServiceSpec,
    _strip_comment,
    parse_message,
)

UUID = "unique_identifier_msgs/msg/UUID"
TIME = "builtin_interfaces/msg/Time"
CANCEL_GOAL = "action_msgs/srv/CancelGoal"
GOAL_STATUS_ARRAY = "action_msgs/msg/GoalStatusArray"


@dataclass(frozen=True)
class ActionSpec:
    """An action type ``pkg/action/Name``: its three parts and the types derived from them."""

    name: str
    goal: MessageSpec
    result: MessageSpec
    feedback: MessageSpec
    send_goal: ServiceSpec
    get_result: ServiceSpec
    feedback_message: MessageSpec
    text: str

    @property
    def messages(self) -> tuple[MessageSpec, ...]:
        """Every message type of the action, services' parts aside."""
        return (self.goal, self.result, self.feedback, self.feedback_message)

    @property
    def services(self) -> tuple[ServiceSpec, ...]:
        return (self.send_goal, self.get_result)


def _service(name: str, request: str, response: str) -> ServiceSpec:
    text = f"{request}\n{SERVICE_SEPARATOR}\n{response}\n"
    return ServiceSpec(
        name, parse_message(f"{name}_Request", request), parse_message(f"{name}_Response", response), text
    )


def parse_action(name: str, text: str, *, source: str | None = None) -> ActionSpec:
    """Parse a ``.action`` (goal, ``---``, result, ``---``, feedback); ``name`` is ``pkg/action/Name``.

    Callers with a definition of their own (a student's package) call this with its text."""
    parts = name.split("/")
    if len(parts) != 3 or parts[1] != "action" or not all(parts):
        raise DefinitionError(f"{source or name}: an action's name is pkg/action/Name, got {name!r}")
    lines = text.splitlines()
    marks = [i for i, line in enumerate(lines) if _strip_comment(line).strip() == SERVICE_SEPARATOR]
    if len(marks) != 2:
        raise DefinitionError(f"{source or name}: an action has two '---' lines, found {len(marks)}")
    sections = ["\n".join(lines[: marks[0]]), "\n".join(lines[marks[0] + 1 : marks[1]])]
    sections.append("\n".join(lines[marks[1] + 1 :]))
    firsts = (1, marks[0] + 2, marks[1] + 2)  # each section's first line in the file
    goal, result, feedback = (
        parse_message(f"{name}_{part}", section, source=source, first_line=first)
        for part, section, first in zip(("Goal", "Result", "Feedback"), sections, firsts, strict=True)
    )
    send_goal = _service(
        f"{name}_SendGoal", f"{UUID} goal_id\n{goal.name} goal", f"bool accepted\n{TIME} stamp"
    )
    get_result = _service(f"{name}_GetResult", f"{UUID} goal_id", f"int8 status\n{result.name} result")
    feedback_message = parse_message(f"{name}_FeedbackMessage", f"{UUID} goal_id\n{feedback.name} feedback")
    return ActionSpec(name, goal, result, feedback, send_goal, get_result, feedback_message, text)


def action_description_text(spec: ActionSpec) -> str:
    """The action's own type as its type description lists it (REP-2016): the three parts, the
    two services and the feedback message, as fields."""
    members = (
        (spec.goal.name, "goal"),
        (spec.result.name, "result"),
        (spec.feedback.name, "feedback"),
        (spec.send_goal.name, "send_goal_service"),
        (spec.get_result.name, "get_result_service"),
        (spec.feedback_message.name, "feedback_message"),
    )
    return "".join(f"{type_name} {field}\n" for type_name, field in members)
