"""An independent ROS 2-over-Zenoh peer for the interop tests: zenoh-ros2-sdk, in its own process.

It imports nothing of this project. The test feeds it the message definitions as text (so the
SDK never fetches them), and commands as JSON lines on stdin; it answers with JSON lines on
stdout. The test also gives the type hashes, ROS 2's own values (offline the SDK would fetch
definitions with git to hash nested types, and it hashes some types wrongly).

Commands: {"cmd": "define", "types": {name: text}} · {"cmd": "subscribe", "topic", "type"}
· {"cmd": "publish", "topic", "type", "msg", "node"} · {"cmd": "topics"} · {"cmd": "topic_info",
"topic"} · {"cmd": "serve", "service", "type", "request", "response", "node"} · {"cmd": "call",
"service", "type", "request", "response"} · {"cmd": "quit"}.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
from typing import Any

_out_lock = threading.Lock()


def emit(**event: Any) -> None:
    with _out_lock:
        sys.stdout.write(json.dumps(event, default=str) + "\n")
        sys.stdout.flush()


def to_plain(value: Any) -> Any:
    """A rosbags message (or array) as JSON-able data."""
    if hasattr(value, "__dataclass_fields__"):
        return {k: to_plain(getattr(value, k)) for k in value.__dataclass_fields__ if k != "__msgtype__"}
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, list):
        return [to_plain(v) for v in value]
    return value


def build(store: Any, type_name: str, data: dict[str, Any]) -> Any:
    """A rosbags message of ``type_name`` from ``data``, every missing field at its zero value."""
    from rosbags.interfaces import Nodetype

    fields = store.fielddefs[type_name][1]
    values: dict[str, Any] = {}
    for name, (kind, detail) in fields:
        if name in data and kind != Nodetype.NAME:
            values[name] = data[name]
        elif kind == Nodetype.NAME:
            values[name] = build(store, detail, data.get(name, {}))
        elif kind == Nodetype.BASE:
            values[name] = "" if detail[0] == "string" else (False if detail[0] == "bool" else 0)
        else:
            raise ValueError(f"{type_name}.{name}: arrays are not needed here")
    return store.types[type_name](**values)


class Peer:
    def __init__(self, router_ip: str, router_port: int) -> None:
        import zenoh_ros2_sdk as sdk

        self.sdk = sdk
        self.ip, self.port = router_ip, router_port
        self.session = sdk.ZenohSession.get_instance(router_ip, router_port)
        self.keep: list[Any] = []
        self.publishers: dict[str, Any] = {}

    def define(self, types: dict[str, str]) -> None:
        # Dependencies first: the SDK looks nested types up among those already registered.
        pending = dict(types)
        while pending:
            ready = [n for n, t in pending.items() if not (_references(n, t) & set(pending))]
            if not ready:
                raise ValueError(f"definitions refer to each other or to missing types: {sorted(pending)}")
            for name in ready:
                self.session.register_message_type(pending.pop(name), name)

    def subscribe(self, topic: str, type_name: str, type_hash: str) -> None:
        def on_message(msg: Any) -> None:
            emit(event="msg", topic=topic, msg=to_plain(msg))

        self.keep.append(
            self.sdk.ROS2Subscriber(
                topic,
                type_name,
                on_message,
                msg_definition=_text(self.session, type_name),
                router_ip=self.ip,
                router_port=self.port,
                type_hash=type_hash,
            )
        )

    def publish(self, topic: str, type_name: str, type_hash: str, data: dict[str, Any], node: str) -> None:
        pub = self.publishers.get(topic)
        if pub is None:
            pub = self.publishers[topic] = self.sdk.ROS2Publisher(
                topic,
                type_name,
                msg_definition=_text(self.session, type_name),
                node_name=node,
                router_ip=self.ip,
                router_port=self.port,
                type_hash=type_hash,
            )
        message = build(self.session.store, type_name, data)
        pub.publish(**{k: getattr(message, k) for k in message.__dataclass_fields__ if k != "__msgtype__"})

    def serve(
        self, service: str, type_name: str, type_hash: str, request: str, response: str, node: str
    ) -> None:
        def answer(req: Any) -> Any:
            cls = server.response_msg_class
            return cls(sum=int(req.a) + int(req.b))

        server = self.sdk.ROS2ServiceServer(
            service,
            type_name,
            answer,
            request_definition=request,
            response_definition=response,
            node_name=node,
            router_ip=self.ip,
            router_port=self.port,
            type_hash=type_hash,
        )
        self.keep.append(server)

    def call(self, service: str, type_name: str, type_hash: str, request: str, response: str) -> Any:
        client = self.sdk.ROS2ServiceClient(
            service,
            type_name,
            request_definition=request,
            response_definition=response,
            router_ip=self.ip,
            router_port=self.port,
            timeout=10.0,
            type_hash=type_hash,
        )
        self.keep.append(client)
        return to_plain(client.call())


PRIMITIVES = {
    "bool",
    "byte",
    "char",
    "float32",
    "float64",
    "int8",
    "uint8",
    "int16",
    "uint16",
    "int32",
    "uint32",
    "int64",
    "uint64",
    "string",
    "wstring",
}


def _references(name: str, text: str) -> set[str]:
    """The message types a definition's fields name, in full (``pkg/msg/Type``)."""
    package = name.split("/")[0]
    out = set()
    for line in text.splitlines():
        words = line.split("#", 1)[0].split()
        if len(words) < 2 or "=" in words[1]:
            continue
        base = words[0].split("[", 1)[0].split("<=", 1)[0]
        if base in PRIMITIVES:
            continue
        parts = base.split("/")
        out.add(f"{package}/msg/{base}" if len(parts) == 1 else f"{parts[0]}/msg/{parts[-1]}")
    return out


def _text(session: Any, type_name: str) -> str | None:
    return session.defined_texts.get(type_name) if hasattr(session, "defined_texts") else None


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--router", required=True, help="HOST:PORT of the lab's Zenoh router")
    parser.add_argument(
        "--override",
        default="",
        help="more ZENOH_CONFIG_OVERRIDE entries (a class's login, from /api/zenoh/join)",
    )
    args = parser.parse_args()
    host, _, port = args.router.rpartition(":")
    # Loopback only, no multicast, and no git fetching from the network: nothing leaves this machine.
    os.environ["GIT_ALLOW_PROTOCOL"] = "file"
    os.environ["ZENOH_CONFIG_OVERRIDE"] = ";".join(
        filter(None, ['listen/endpoints=["tcp/127.0.0.1:0"];scouting/multicast/enabled=false', args.override])
    )
    peer = Peer(host, int(port))
    texts: dict[str, str] = {}
    peer.session.defined_texts = texts
    emit(event="ready")
    for line in sys.stdin:
        command = json.loads(line)
        cmd = command["cmd"]
        try:
            if cmd == "define":
                texts.update(command["types"])
                peer.define(command["types"])
            elif cmd == "subscribe":
                peer.subscribe(command["topic"], command["type"], command["hash"])
            elif cmd == "publish":
                peer.publish(
                    command["topic"],
                    command["type"],
                    command["hash"],
                    command["msg"],
                    command.get("node", "sdk_peer"),
                )
            elif cmd == "topics":
                emit(
                    event="topics",
                    topics=peer.sdk.get_topic_names_and_types(router_ip=host, router_port=int(port)),
                )
                continue
            elif cmd == "topic_info":
                info = peer.sdk.get_topic_info(
                    command["topic"], router_ip=host, router_port=int(port), verbose=True
                )
                nodes = [] if info is None else [p.node_name for p in info.publishers + info.subscribers]
                emit(event="topic_info", nodes=nodes, types=[] if info is None else info.topic_types)
                continue
            elif cmd == "serve":
                peer.serve(
                    command["service"],
                    command["type"],
                    command["hash"],
                    command["request"],
                    command["response"],
                    command.get("node", "sdk_server"),
                )
            elif cmd == "call":
                reply = peer.call(
                    command["service"],
                    command["type"],
                    command["hash"],
                    command["request"],
                    command["response"],
                )
                emit(event="reply", msg=reply)
                continue
            elif cmd == "quit":
                break
            emit(event="done", cmd=cmd)
        except Exception as exc:  # report to the test instead of dying silently
            emit(event="error", cmd=cmd, error=f"{type(exc).__name__}: {exc}")
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    # The SDK's subscribers keep threads that are not daemons: without this the process outlives
    # "quit" until its parent kills it.
    os._exit(code)
