"""What ``python -m server`` prints as it starts: where to open the page and which keys fly, a
lab's token link and its graph, a class's code and the instructor's link, and how students'
nodes run."""

from __future__ import annotations

from node_runtime.transport.config import is_loopback
from server import cli
from server.host.settings import ANY_ADDRESS, Settings


def shown_host(host: str) -> str:
    return "127.0.0.1" if host in ANY_ADDRESS else host


def banner(host: str, port: int, launch: str) -> str:
    """The first lines a student reads: where to open the page, and which keys fly."""
    return (
        f"Teleop lab: open http://{shown_host(host)}:{port}/ in a browser (launch: {launch}; Ctrl-C stops it)\n"
        "Keys, after a click in the 3D view: arrows fly the drone, PgUp/PgDn climb and sink, "
        "a aborts the rocket, ? shows help"
    )


def classroom_banner(settings: Settings, code: str, instructor_token: str) -> str:
    """The class code for the projector, the instructor's link (its token, printed once) and, with
    Zenoh, how to add a world worker."""
    host, port = settings.listen.host, settings.listen.port
    shown = shown_host(host)
    lan = " (and this machine's LAN address)" if host in ANY_ADDRESS else ""
    lines = [
        f"Class server: students open http://{shown}:{port}/{lan} and join with class code {code}",
        f"Instructor (keep this link to yourself): http://127.0.0.1:{port}/instructor?token={instructor_token}",
    ]
    router = settings.lab.zenoh_router
    foxglove, rosbridge = settings.lab.foxglove_port, settings.lab.rosbridge_port
    if router is not None and foxglove is not None:
        lines.append(
            f"Foxglove, every world as /<world>/...: ws://{shown}:{foxglove}/?token=<the instructor's token>"
        )
    if router is not None and rosbridge is not None:
        lines.append(
            f"rosbridge, every world as /<world>/...: ws://{shown}:{rosbridge}/?token=<the instructor's token>"
        )
    assert settings.classroom is not None
    from server.base.cores import usable_cores
    from server.classroom.local_workers import spare_cores

    per_core, cores = settings.classroom.worlds_per_core, usable_cores()
    if per_core:
        lines.append(
            f"This machine takes {per_core * cores} worlds ({per_core} a core, {cores} cores: "
            "--worlds-per-core); past that a join waits in the queue until the instructor lets it in"
        )
    started, spare = settings.classroom.workers_at_start, spare_cores()
    if started:
        ids = "local-1" if started == 1 else f"local-1..local-{started}"
        lines.append(
            f"World workers on this machine: {started} ({ids}), started and stopped with this server"
        )
    elif settings.classroom.auto_workers and router is not None and spare:
        lines.append(
            f"World workers on this machine: one each {settings.classroom.spread_at} worlds, at most {spare} "
            "(its spare cores), started as the class grows and stopped with this server (--workers)"
        )
    if router is not None:
        endpoint = router.listen[0].replace("0.0.0.0", "<this machine's address>")
        lines.append(
            f"More cores or machines: ROS2LAB_TOKEN=<the instructor's token> ros2lab {cli.WORKER_VERB} "
            f"--connect {endpoint}"
        )
    level = settings.classroom.world_log_level
    if level != "debug":
        lines.append(
            f"This console shows the worlds' node lines at {level} and above, each under its world's "
            "name; every line is on its world's /rosout (--world-log-level to change)"
        )
    return "\n".join(lines)


def print_lab_lines(settings: Settings) -> None:
    """Where to open the page, the lab's token link, and where its graph is."""
    listen, zenoh = settings.listen, settings.lab.zenoh
    print(banner(listen.host, listen.port, settings.lab.launch), flush=True)
    if listen.token is not None and settings.classroom is None:
        print(
            f"This lab needs its token: open http://{shown_host(listen.host)}:{listen.port}/?token={listen.token} "
            "(bridges: ?token= or Authorization: Bearer)",
            flush=True,
        )
    if zenoh is not None:
        wide = [e for e in zenoh.listen if not is_loopback(e)] if zenoh.mode == "router" else []
        where = ", ".join(zenoh.listen) if zenoh.mode == "router" else "router " + ", ".join(zenoh.connect)
        domains = "a ROS domain per world (1, 2, ...)" if settings.classroom else f"domain {zenoh.domain_id}"
        print(f"ROS graph on Zenoh ({where}, {domains})", flush=True)
        if wide:
            print(
                f"note: Zenoh listens on {', '.join(wide)}: other machines with the login can join this graph "
                "(GET /api/zenoh/join with the token gives it; see docs/zenoh.md)",
                flush=True,
            )


def student_code_line(settings: Settings) -> str | None:
    """How students' nodes run here, in one line, when the server serves others."""
    if not settings.confines_paths:
        return None
    if not settings.sandboxes_students:
        return (
            "warning: --student-code unsandboxed: students' nodes run as this server's user, with "
            "everything it can read and reach (tokens, other workspaces, the network)"
        )
    from server.host.processes.sandbox import StudentCodeRefusedError, probe

    why = probe()
    if why is not None:
        return f"error: {StudentCodeRefusedError(why)}"
    from server.host.processes.sandbox import cpu_layer, memory_layer

    limits = settings.sandbox
    return (
        f"Students' nodes run sandboxed (bubblewrap, seccomp, no capability, the workspace read-only, "
        f"no network but their world's graph; {limits.memory_mib} MiB counted {memory_layer()}, "
        f"{limits.processes} processes, {cpu_layer(limits.nice)})"
    )
