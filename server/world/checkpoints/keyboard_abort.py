"""Checkpoint 1: the rocket's launch aborted with "a" through the student's keyboard manager.

Met when, during a countdown (no positive /cmd_vel since it began), an "a" keydown from the lab's
keyboard node is followed within ABORT_WITHIN_S by ``/abort_takeoff: true`` published by a node of
the student's own process, and no positive /cmd_vel comes for CONFIRM_S after it (the rocket
stayed on the pad).
"""

from __future__ import annotations

from server.world.checkpoints.declared import Checkpoint, Evidence, Question, Step
from server.world.checkpoints.events import LAB, Abort, CmdVel, Countdown, Event, KeyDown, Source
from server.world.checkpoints.page_names import (
    CODE,
    GRAPH,
    NEW_FILE,
    NEW_PACKAGE,
    RESET_ROCKET,
    ROCKET_TEMPLATE,
    RUN,
)
from server.world.checkpoints.timeline import Timeline

KEY_A = 97  # SDL's code for "a", as keyboard_msgs/Key carries it
ABORT_WITHIN_S = 1.0
CONFIRM_S = 1.0
COUNTDOWN_GONE_S = 2.5  # no count this long: the countdown is over (the lab counts once a second)


def from_keyboard(source: Source) -> bool:
    """A key from the lab's keyboard node (the page's keys), not one published by hand."""
    return source.process == LAB and not source.node.rsplit("/", 1)[-1].startswith("_")


class KeyboardAbortCheck:
    """The line (``progress``) says where the student is and what is missing; it changes when that
    changes, never with each repeat of an abort (a manager publishes it at 10 Hz) nor with each
    count: an abort is judged once per node, from a key (or a countdown) to the next."""

    def __init__(self) -> None:
        self.timeline = Timeline(200)
        self._counts: dict[Source, tuple[int, float]] = {}  # each counter's last count and its time
        self._lifted = False
        self._key_s: float | None = None
        self._pending: tuple[float, Source] | None = None
        self._note = "press Reset rocket, then press a during its countdown"
        self._counting_note = True  # the line only says the countdown is on: nothing else was said in it
        self._judged = False  # an abort was judged in this countdown
        self._aborters: set[Source] = (
            set()
        )  # publishers whose abort was judged since the last key or countdown
        self.started = False

    def _counting(self, t_s: float) -> bool:
        return any(value > 0 and t_s - at_s <= COUNTDOWN_GONE_S for value, at_s in self._counts.values())

    def _on_countdown(self, event: Countdown) -> None:
        last = self._counts.get(event.source)
        if last is None or event.value > last[0] or event.t_s - last[1] > COUNTDOWN_GONE_S:
            self._lifted = False  # a new countdown (a reset rocket); a second rocket counting is not one
            self.timeline.clear()
            self._counting_note = True
            self._judged = False
            self._aborters.clear()
        self._counts = {
            who: count for who, count in self._counts.items() if event.t_s - count[1] <= COUNTDOWN_GONE_S
        }
        self._counts[event.source] = (event.value, event.t_s)
        self.timeline.add(event.t_s, "countdown", event.value)
        if self._counting_note:  # what was said in this countdown stays said until the next
            self._note = "the countdown is on: press a" if event.value > 0 else self._note

    def feed(self, event: Event) -> Evidence | None:
        if isinstance(event, Countdown):
            self._on_countdown(event)
        elif isinstance(event, CmdVel) and event.value_mps > 0:
            if not self._lifted:
                self.timeline.add(event.t_s, "cmd_vel", event.value_mps)
                if self._pending is not None:
                    self._say("the rocket lifted off after your abort: press Reset rocket and try again")
                else:
                    self._say("the rocket lifted off: press Reset rocket, then press a during its countdown")
            self._lifted = True
            self._pending = None
        elif isinstance(event, KeyDown) and event.code == KEY_A and from_keyboard(event.source):
            self.started = True  # the student's own doing (a countdown alone is the lab's)
            self.timeline.add(event.t_s, "key", "a", event.source)
            self._aborters.clear()
            if self._counting(event.t_s) and not self._lifted:
                self._key_s = event.t_s
                if self._pending is None:
                    self._say("a pressed: waiting for /abort_takeoff from your keyboard manager")
        elif isinstance(event, Abort) and event.value:
            self.started = True
            if event.source not in self._aborters:  # a manager repeats its abort: once is judged
                self._aborters.add(event.source)
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
            self._say("the rocket had lifted off: press Reset rocket, then press a during its countdown")
        elif not self._counting(event.t_s):
            self._say("no countdown running: press Reset rocket, then press a during its countdown")
        elif key_s is None or not 0 <= event.t_s - key_s <= ABORT_WITHIN_S:
            self._say(
                f"/abort_takeoff from {event.source.node or 'someone'} without an a pressed just "
                "before: press a during the countdown"
            )
        elif not event.source.student:
            self._say(
                f"/abort_takeoff came from {event.source.node} in {event.source.process}, not from a "
                f"keyboard manager of your workspace: open yours in the {CODE} view and press {RUN}"
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
        Step(
            "Write a keyboard manager in your workspace: it subscribes to /keydown and publishes "
            "std_msgs/Bool true on /abort_takeoff when the key is 'a'.",
            ("ros2lab pkg create --build-type ament_python rocket_keys",),
            page=(
                f"In the {CODE} view: {NEW_PACKAGE} (rocket_keys), then {NEW_FILE} in it, Start from "
                f"\u201c{ROCKET_TEMPLATE}\u201d, and fill in its TODOs."
            ),
        ),
        Step(
            "Start the rocket's launch.",
            ("ros2lab launch rocketship rocket.launch",),
            running=("/CountDownNode", "/MainControllerNode"),
            already="The rocket is already running (the lab's launch started it): nothing to start.",
        ),
        Step(
            "Run your keyboard manager as its own process.",
            ("ros2lab run rocket_keys keyboard_manager",),
            page=f"Open your keyboard_manager.py in the {CODE} view and press {RUN}.",
        ),
        Step(
            "Open the graph and find your node between the keyboard and the rocket's controller.",
            ("ros2lab node list",),
            page=f"Open {GRAPH} at the top of the page.",
        ),
        Step(
            "During the countdown, press a: your node aborts the launch and the rocket stays on the pad.",
            (),
            page=f"Press {RESET_ROCKET} to start a new countdown, click the 3D view, then press a.",
        ),
    ),
    check=KeyboardAbortCheck,
    questions=(
        Question(
            "q1",
            "Which nodes and topics does the graph show while the rocket counts down, "
            "and which node is yours?",
            shows_graph=True,
        ),
        Question("q2", "What does your keyboard manager subscribe to and publish, with which message types?"),
        Question(
            "q3",
            "Why does the rocket stay on the pad when /abort_takeoff arrives during the countdown, "
            "and what would an abort do after lift-off?",
        ),
    ),
    wants_graph=True,
)
