"""Checkpoint 1: the rocket's launch aborted with "a" through the student's keyboard manager.

Met when, during a countdown (no positive /cmd_vel since it began), an "a" keydown from the lab's
keyboard node is followed within ABORT_WITHIN_S by ``/abort_takeoff: true`` published by a node of
the student's own process, and no positive /cmd_vel comes for CONFIRM_S after it (the rocket
stayed on the pad).
"""

from __future__ import annotations

from .declared import Checkpoint, Evidence, Question, Step
from .events import LAB, Abort, CmdVel, Countdown, Event, KeyDown, Source
from .timeline import Timeline

KEY_A = 97  # SDL's code for "a", as keyboard_msgs/Key carries it
ABORT_WITHIN_S = 1.0
CONFIRM_S = 1.0
COUNTDOWN_GONE_S = 2.5  # no count this long: the countdown is over (the lab counts once a second)


def from_keyboard(source: Source) -> bool:
    """A key from the lab's keyboard node (the page's keys), not one published by hand."""
    return source.process == LAB and not source.node.rsplit("/", 1)[-1].startswith("_")


class KeyboardAbortCheck:
    def __init__(self) -> None:
        self.timeline = Timeline(200)
        self._count: int | None = None
        self._count_s = -1e18
        self._lifted = False
        self._key_s: float | None = None
        self._pending: tuple[float, Source] | None = None
        self._note = "start the rocket's launch: the countdown begins"
        self._counting_note = True  # the line only counts down: nothing else was said in this countdown
        self._judged = False  # an abort was judged in this countdown
        self._aborters: set[str] = set()  # nodes whose abort the timeline has since the last key
        self.started = False

    def _counting(self, t_s: float) -> bool:
        return self._count is not None and self._count > 0 and t_s - self._count_s <= COUNTDOWN_GONE_S

    def feed(self, event: Event) -> Evidence | None:
        if isinstance(event, Countdown):
            if (
                self._count is None
                or event.value > self._count
                or event.t_s - self._count_s > COUNTDOWN_GONE_S
            ):
                self._lifted = False  # a new countdown (a reset rocket)
                self.timeline.clear()
                self._counting_note = True
                self._judged = False
                self._aborters.clear()
            self._count, self._count_s = event.value, event.t_s
            self.timeline.add(event.t_s, "countdown", event.value)
            if self._counting_note:  # what was said in this countdown stays said until the next
                self._note = f"countdown at {event.value} s: press a"
        elif isinstance(event, CmdVel) and event.value_mps > 0:
            if not self._lifted:
                self.timeline.add(event.t_s, "cmd_vel", event.value_mps)
            self._lifted = True
            if self._pending is not None:
                self._say("the rocket lifted off after your abort: reset the rocket and try again")
            else:
                self._say("the rocket lifted off: reset the rocket and abort it during the countdown")
            self._pending = None
        elif isinstance(event, KeyDown) and event.code == KEY_A and from_keyboard(event.source):
            self.started = True  # the student's own doing (a countdown alone is the lab's)
            self.timeline.add(event.t_s, "key", "a", event.source)
            self._aborters.clear()
            if self._counting(event.t_s) and not self._lifted:
                self._key_s = event.t_s
                self._say("a pressed: waiting for /abort_takeoff from your keyboard manager")
        elif isinstance(event, Abort) and event.value:
            self.started = True
            if event.source.node not in self._aborters:  # a manager may repeat its abort: once is told
                self._aborters.add(event.source.node)
                self.timeline.add(event.t_s, "abort", True, event.source)
            self._on_abort(event)
        return self.tick(event.t_s)

    def _on_abort(self, event: Abort) -> None:
        if self._pending is not None:  # the lab's own manager may abort too, after the student's
            return
        if self._judged and not self._counting(event.t_s):
            return  # an abort repeated after its countdown: what was said of it stands
        self._judged = True
        key_s = self._key_s
        if self._lifted:
            self._say("the rocket had lifted off: reset the rocket and abort it during the countdown")
        elif not self._counting(event.t_s):
            self._say("no countdown running: start (or reset) the rocket and abort during the countdown")
        elif key_s is None or not 0 <= event.t_s - key_s <= ABORT_WITHIN_S:
            self._say(
                f"/abort_takeoff from {event.source.node or 'someone'} without an a pressed just before"
            )
        elif not event.source.student:
            self._say(
                f"/abort_takeoff came from {event.source.node} in {event.source.process}, not from a "
                "keyboard manager of your workspace: run yours (ros2lab run) instead of the lab's"
            )
        else:
            self._pending = (event.t_s, event.source)
            self._say("aborted: checking that the rocket stays on the pad")

    def tick(self, now_s: float) -> Evidence | None:
        pending = self._pending
        if pending is None or now_s - pending[0] < CONFIRM_S or self._lifted:
            return None
        self._pending = None
        key_s = self._key_s if self._key_s is not None else pending[0]
        self._key_s = None
        self._say("done: the rocket stayed on the pad")
        return {
            "student_node": pending[1].node,
            "student_process": pending[1].process,
            "key_to_abort_s": round(pending[0] - key_s, 3),
            "timeline": self.timeline.entries(),
        }

    def progress(self, now_s: float) -> str:
        return self._note

    def _say(self, note: str) -> None:
        self._note, self._counting_note = note, False


CHECKPOINT = Checkpoint(
    name="keyboard_abort",
    title="Abort the rocket with your keyboard manager",
    steps=(
        Step("Write a keyboard manager in your workspace: it subscribes to /keydown and publishes "
             "std_msgs/Bool true on /abort_takeoff when the key is 'a'.", ("ros2lab pkg create --build-type ament_python rocket_keys",)),
        Step("Start the rocket's launch and run your keyboard manager as its own process.",
             ("ros2lab launch rocketship rocket.launch", "ros2lab run rocket_keys keyboard_manager")),
        Step("Open the graph and find your node between the keyboard and the rocket's controller.", ("ros2lab node list",)),
        Step("During the countdown, press a in the page: your node aborts the launch and the rocket stays on the pad.", ()),
    ),
    check=KeyboardAbortCheck,
    questions=(
        Question("q1", "Which nodes and topics does the graph show while the rocket counts down, and which node is yours?", shows_graph=True),
        Question("q2", "What does your keyboard manager subscribe to and publish, with which message types?"),
        Question("q3", "Why does the rocket stay on the pad when /abort_takeoff arrives during the countdown, and what would an abort do after lift-off?"),
    ),
    wants_graph=True,
)  # fmt: skip
