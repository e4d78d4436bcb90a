"""Actions that set the scene rather than start nodes: ``LogInfo``, ``SetEnvironmentVariable``,
``TimerAction``, ``OpaqueFunction``, and ``ExecuteProcess``, which the lab does not run."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, Optional

from ..action import Action
from ..utilities import normalize_to_list_of_substitutions, perform_typed

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity


def _where(action: Action) -> str:
    return f"{action.written_at[0]}:{action.written_at[1]}: " if action.written_at else ""


class LogInfo(Action):
    """``[INFO] [launch.user]: MSG`` when it runs."""

    def __init__(self, *, msg: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__msg = normalize_to_list_of_substitutions(msg)

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.messages.append(f"[INFO] [launch.user]: {perform_typed(context, self.__msg)}")
        return None


class SetEnvironmentVariable(Action):
    """Sets a variable for what the launch evaluates after it (``EnvironmentVariable``)."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name, self.__value = name, value

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.environment[perform_typed(context, self.__name)] = perform_typed(context, self.__value)
        return None


class TimerAction(Action):
    """Its actions after ``period`` seconds: the nodes among them start that much later (the lab
    evaluates the rest at once)."""

    def __init__(self, *, period: Any, actions: Iterable[Action], cancel_on_shutdown: bool = True,
                 **kwargs: Any) -> None:  # fmt: skip
        super().__init__(**kwargs)
        self.__period = period
        self.__actions = list(actions)

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return list(self.__actions)

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        text = perform_typed(context, self.__period)
        try:
            period = float(text)
        except ValueError:
            raise RuntimeError(f"TimerAction's period '{text}' is not a number of seconds") from None
        if not 0.0 <= period < float("inf"):
            raise RuntimeError(f"TimerAction's period {period} is not a number of seconds >= 0")
        return [_Delay(period), *self.__actions, _Delay(-period)]


class _Delay(Action):
    """What a TimerAction's nodes wait before they start, while its actions are evaluated."""

    def __init__(self, seconds: float) -> None:
        super().__init__()
        self.seconds = seconds

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        context.locals["start_delay_s"] = max(0.0, context.locals.get("start_delay_s", 0.0) + self.seconds)
        return None


class OpaqueFunction(Action):
    """Calls ``function(context, *args, **kwargs)``; the actions it returns run next."""

    def __init__(self, *, function: Callable[..., Any], args: Iterable[Any] | None = None,
                 kwargs: dict[str, Any] | None = None, **more: Any) -> None:  # fmt: skip
        super().__init__(**more)
        if not callable(function):
            raise TypeError(f"OpaqueFunction's function is not callable: {function!r}")
        self.__function = function
        self.__args = list(args or [])
        self.__kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        result = self.__function(context, *self.__args, **self.__kwargs)
        return None if result is None else list(result)


class ExecuteProcess(Action):
    """A command to run. The lab runs nodes only: it says which command it did not run."""

    def __init__(self, *, cmd: Iterable[Any], name: Any = None, cwd: Any = None,
                 env: dict[Any, Any] | None = None, additional_env: dict[Any, Any] | None = None,
                 shell: bool = False, output: Any = "log", **kwargs: Any) -> None:  # fmt: skip
        super().__init__(**kwargs)
        self.__cmd = [normalize_to_list_of_substitutions(part) for part in cmd]
        self.__name = name
        self.output = output
        self.shell = shell

    @property
    def cmd(self) -> list[Any]:
        return self.__cmd

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        command = " ".join(perform_typed(context, part) for part in self.__cmd)
        context.messages.append(
            f"[WARNING] [launch]: {_where(self)}ExecuteProcess not run (the lab starts nodes only): {command}"
        )
        return None
