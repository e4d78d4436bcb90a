"""Action types as rclpy has them: ``Fibonacci.Goal``, ``.Result``, ``.Feedback``, and ``Impl``
with the services and messages an action is carried by on the wire."""

from __future__ import annotations

from typing import Any, ClassVar

from node_runtime.msgs._base import Message, Service, define_message, load_generated
from node_runtime.msgs.action_spec import CANCEL_GOAL, GOAL_STATUS_ARRAY, ActionSpec, parse_action
from node_runtime.msgs.definitions import lab_definitions

_ACTIONS: dict[str, type[Action]] = {}
_SERVICES: dict[str, type[Service]] = {}


class Action:
    """Base of every action type: ``class Fibonacci(Action, type_name="pkg/action/Fibonacci")``
    with ``Goal``, ``Result``, ``Feedback`` and an ``Impl`` naming the wire types (rclpy's
    ``SendGoalService``, ``GetResultService``, ``FeedbackMessage``, ``CancelGoalService``,
    ``GoalStatusMessage``)."""

    TYPE: ClassVar[str] = ""
    SPEC: ClassVar[ActionSpec]
    Goal: ClassVar[type[Message]]
    Result: ClassVar[type[Message]]
    Feedback: ClassVar[type[Message]]
    Impl: ClassVar[Any]

    def __init_subclass__(
        cls, type_name: str | None = None, spec: ActionSpec | None = None, **kw: Any
    ) -> None:
        super().__init_subclass__(**kw)
        if type_name is None:
            return
        spec = spec or lab_definitions().actions[type_name]
        impl = cls.Impl
        declared = (
            (cls.Goal.TYPE, spec.goal.name),
            (cls.Result.TYPE, spec.result.name),
            (cls.Feedback.TYPE, spec.feedback.name),
            (impl.SendGoalService.TYPE, spec.send_goal.name),
            (impl.GetResultService.TYPE, spec.get_result.name),
            (impl.FeedbackMessage.TYPE, spec.feedback_message.name),
            (impl.CancelGoalService.TYPE, CANCEL_GOAL),
            (impl.GoalStatusMessage.TYPE, GOAL_STATUS_ARRAY),
        )
        for got, wanted in declared:
            if got != wanted:
                raise TypeError(f"{cls.__name__}: declares {got} where {type_name} has {wanted}")
        cls.TYPE = type_name
        cls.SPEC = spec
        _ACTIONS[type_name] = cls


def action_class(type_name: str) -> type[Action]:
    """The class declared for ``pkg/action/Name`` (KeyError if none)."""
    if type_name not in _ACTIONS:
        load_generated(type_name.split("/")[0])
    return _ACTIONS[type_name]


def action_classes() -> dict[str, type[Action]]:
    load_generated()
    return dict(_ACTIONS)


def _service(spec: Any) -> type[Service]:
    request = define_message(spec.request)
    response = define_message(spec.response)
    namespace = {"Request": request, "Response": response, "__module__": __name__}
    cls: type[Service] = type(
        spec.name.rsplit("/", 1)[1], (Service,), namespace, type_name=spec.name, spec=spec
    )
    _SERVICES[spec.name] = cls
    return cls


def define_action(spec: ActionSpec) -> type[Action]:
    """The classes of an action parsed at run time (a student's own ``.action``): its messages,
    its two services and the action class. The types it nests must have classes already."""
    from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatusArray

    goal, result, feedback, feedback_message = (define_message(m) for m in spec.messages)
    impl = type(
        "Impl",
        (),
        {
            "SendGoalService": _service(spec.send_goal),
            "GetResultService": _service(spec.get_result),
            "FeedbackMessage": feedback_message,
            "CancelGoalService": CancelGoal,
            "GoalStatusMessage": GoalStatusArray,
        },
    )
    namespace = {"Goal": goal, "Result": result, "Feedback": feedback, "Impl": impl, "__module__": __name__}
    cls: type[Action] = type(
        spec.name.rsplit("/", 1)[1], (Action,), namespace, type_name=spec.name, spec=spec
    )
    return cls


def action_type_from_text(package: str, name: str, text: str) -> type[Action]:
    """The action class of ``<package>/action/<name>`` defined by ``text`` (a ``.action`` file's),
    with its messages and services; a DefinitionError names what does not parse."""
    full = f"{package}/action/{name}"
    return define_action(parse_action(full, text, source=f"{package}/action/{name}.action"))


def defined_service(type_name: str) -> type[Service] | None:
    """A service class :func:`define_action` made (None if it made none of that name)."""
    return _SERVICES.get(type_name)


__all__ = [
    "Action",
    "action_class",
    "action_classes",
    "action_type_from_text",
    "define_action",
    "defined_service",
]
