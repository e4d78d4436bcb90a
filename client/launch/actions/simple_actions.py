"""Actions that set the scene rather than start nodes: ``LogInfo``, ``SetEnvironmentVariable``,
``TimerAction``, ``OpaqueFunction``, and ``ExecuteProcess`` (a command: the lab runs ``ros2 ...`` ones)."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, Optional

from launch.action import Action
from launch.utilities import normalize_to_list_of_substitutions, perform_typed

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext
    from launch.launch_description_entity import LaunchDescriptionEntity


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
    """Its actions after ``period`` seconds: the nodes and commands among them start that much
    later (the lab evaluates the rest at once)."""

    def __init__(
        self, *, period: Any, actions: Iterable[Action], cancel_on_shutdown: bool = True, **kwargs: Any
    ) -> None:
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

    def __init__(
        self,
        *,
        function: Callable[..., Any],
        args: Iterable[Any] | None = None,
        kwargs: dict[str, Any] | None = None,
        **more: Any,
    ) -> None:
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
    """A command to run. The lab runs ``ros2 ...`` commands (as its own CLI) and nothing else; the
    launcher decides, this says what was asked."""

    def __init__(
        self,
        *,
        cmd: Iterable[Any],
        name: Any = None,
        cwd: Any = None,
        env: dict[Any, Any] | None = None,
        additional_env: dict[Any, Any] | None = None,
        shell: bool = False,
        output: Any = "log",
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.__cmd = [normalize_to_list_of_substitutions(part) for part in cmd]
        self.__name = name
        self.output = output
        self.shell = shell

    @property
    def cmd(self) -> list[Any]:
        return self.__cmd

    @property
    def name(self) -> Any:
        return self.__name

    def execute(self, context: LaunchContext) -> Optional[list[LaunchDescriptionEntity]]:  # noqa: UP045
        file, line = self.written_at or (context.current_launch_file or "", 0)
        output = None if self.output is None else perform_typed(context, self.output)
        entry: dict[str, Any] = {
            "kind": "command",
            "cmd": [perform_typed(context, part) for part in self.__cmd],
            "shell": bool(self.shell),
            "name": None if self.__name is None else perform_typed(context, self.__name),
            "output": output,
            "file": file,
            "line": line,
            "start_delay": float(context.locals.get("start_delay_s", 0.0)),
        }
        context.found.append(entry)
        return None
