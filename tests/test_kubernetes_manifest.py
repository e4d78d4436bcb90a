"""deploy/kubernetes/class.yaml, checked without a cluster: every object against Kubernetes' own
schemas (kubernetes-validate, strict: a field Kubernetes does not know fails too), the references
between the objects (selectors, named ports, the Secret, the router's Service the workers join),
and the command each container starts with, through the app's own parsers and settings rules.
A mutated copy fails the same check. Its commands are compose.class.yml's, which
tests/classroom/test_class_deployment.py runs, but for the names of the cluster.
"""

from __future__ import annotations

import re
from pathlib import PurePosixPath
from typing import Any

import kubernetes_validate
import pytest
import yaml
from kubernetes_validate.utils import latest_version
from support.deployment import (
    KUBERNETES_CLASS,
    class_compose,
    image_workdir,
    option,
    server_settings,
    swapped,
    worker_argv,
    worker_settings,
)

from server.classroom.worker_control import TOKEN_ENV

# The oldest Kubernetes the manifest is kept valid for, and the newest the schemas know.
VERSIONS = ("1.29", latest_version())
POD_IP, POD_NAME = "10.42.1.7", "teleop-class-worker-5d8f7c9b4-x2x7q"  # what the downward API gives
MEMORY = {"Ki": 2**10, "Mi": 2**20, "Gi": 2**30}


def documents(text: str | None = None) -> list[dict[str, Any]]:
    return [d for d in yaml.safe_load_all(KUBERNETES_CLASS.read_text() if text is None else text) if d]


def the(kind: str, name: str | None = None) -> dict[str, Any]:
    (found,) = [d for d in documents() if d["kind"] == kind and name in (None, d["metadata"]["name"])]
    return found


def container(workload: dict[str, Any]) -> dict[str, Any]:
    (only,) = workload["spec"]["template"]["spec"]["containers"]
    return only


def expanded(c: dict[str, Any]) -> list[str]:
    """The container's command with ``$(NAME)`` expanded as the kubelet does: a value from the
    container's env, a field of the pod from the downward API."""
    values = {}
    for env in c.get("env", []):
        field = env.get("valueFrom", {}).get("fieldRef", {}).get("fieldPath")
        values[env["name"]] = {"status.podIP": POD_IP, "metadata.name": POD_NAME}.get(field, env.get("value"))
    return [re.sub(r"\$\((\w+)\)", lambda m: str(values[m.group(1)]), arg) for arg in c["command"]]


def port_named(c: dict[str, Any], name: str) -> int:
    (port,) = [p["containerPort"] for p in c["ports"] if p["name"] == name]
    return int(port)


def quantity(text: str) -> float:
    """A Kubernetes quantity as a number: cores (``"1"``, ``500m``) or bytes (``512Mi``)."""
    if text.endswith("m"):
        return int(text[:-1]) / 1000
    for suffix, factor in MEMORY.items():
        if text.endswith(suffix):
            return int(text[: -len(suffix)]) * factor
    return float(text)


@pytest.mark.parametrize("version", VERSIONS)
def test_every_object_is_valid_against_kubernetes_schemas(version: str) -> None:
    kinds = []
    for document in documents():
        kubernetes_validate.validate(document, version, strict=True)
        kinds.append(document["kind"])
    assert sorted(kinds) == ["Deployment", "Secret", "Service", "Service", "StatefulSet"]


@pytest.mark.parametrize(
    ("old", "new", "where"),
    [
        ("replicas: 2", "replicas: two", "spec.replicas"),  # a count that is not one
        (
            "          readinessProbe:",
            "          readynessProbe:",
            "readynessProbe",
        ),  # a field Kubernetes lacks
    ],
)
def test_a_mutated_manifest_fails_naming_what_is_wrong(old: str, new: str, where: str) -> None:
    """The control: the same check refuses a copy with one mistake."""
    text = KUBERNETES_CLASS.read_text()
    assert old in text
    failures = []
    for document in documents(text.replace(old, new, 1)):
        try:
            kubernetes_validate.validate(document, VERSIONS[-1], strict=True)
        except kubernetes_validate.ValidationError as exc:
            failures.append(f"{'.'.join(str(p) for p in exc.path)}: {exc.message}")
    assert len(failures) == 1, failures
    assert where in failures[0], failures


def test_the_services_reach_the_class_servers_ports_and_the_workers_join_its_router() -> None:
    server = the("StatefulSet")
    labels = server["spec"]["template"]["metadata"]["labels"]
    c = container(server)
    settings = server_settings(expanded(c))
    router = settings.lab.zenoh_router
    assert router is not None
    wanted = {
        "teleop-class": {settings.listen.port, settings.lab.foxglove_port},
        "teleop-class-router": {int(router.listen[0].rsplit(":", 1)[1])},
    }
    for name, ports in wanted.items():
        service = the("Service", name)
        assert service["spec"]["selector"].items() <= labels.items(), name
        assert {port_named(c, p["targetPort"]) for p in service["spec"]["ports"]} == ports, name
    assert server["spec"]["serviceName"] == "teleop-class"
    # A worker joins the router by its Service's name and port.
    (router_port,) = the("Service", "teleop-class-router")["spec"]["ports"]
    argv = expanded(container(the("Deployment")))
    assert option(argv, "--connect") == f"tcp/teleop-class-router:{router_port['port']}"


def test_the_class_server_starts_as_a_class_with_its_state_and_workspaces_on_volumes() -> None:
    server = the("StatefulSet")
    c = container(server)
    settings = server_settings(expanded(c))
    klass = settings.classroom
    assert klass is not None and klass.local_worlds == 0 and klass.workers_at_start == 0
    assert settings.listen.host == "0.0.0.0" and settings.sandboxes_students
    mounts = {m["mountPath"]: m["name"] for m in c["volumeMounts"]}
    claims = {t["metadata"]["name"] for t in server["spec"]["volumeClaimTemplates"]}
    workdir = image_workdir()
    for folder in (settings.lab.state_dir, klass.workspaces_dir):
        assert mounts.get(str(workdir / folder)) in claims, (folder, mounts)
    assert server["spec"]["replicas"] == 1


def secret_file_of(workload: dict[str, Any]) -> tuple[str, dict[str, Any]]:
    """Where the pod's container reads the class secret file (its --class-secret-file), and the
    volume mounted there."""
    c = container(workload)
    path = PurePosixPath(option(expanded(c), "--class-secret-file"))
    mounts = [m for m in c.get("volumeMounts", []) if path.is_relative_to(m["mountPath"])]
    assert len(mounts) == 1, (path, c.get("volumeMounts"))
    (mount,) = mounts
    assert mount.get("readOnly") is True, mount
    (volume,) = [v for v in workload["spec"]["template"]["spec"]["volumes"] if v["name"] == mount["name"]]
    return str(path.relative_to(mount["mountPath"])), volume


def test_both_workloads_read_the_class_secret_file_from_the_manifests_secret() -> None:
    secret = the("Secret")
    assert "data" not in secret and "stringData" not in secret  # made once by the operator, never here
    for workload in (the("StatefulSet"), the("Deployment")):
        inside, volume = secret_file_of(workload)
        assert volume["secret"]["secretName"] == secret["metadata"]["name"], volume
        assert {"key": "class-secret", "path": inside} in volume["secret"]["items"], volume
        c = container(workload)
        assert TOKEN_ENV not in {e["name"] for e in c.get("env", [])}  # nothing from the class server's log
    # Both parse it as theirs: the class server's settings and the worker's command.
    server = server_settings(expanded(container(the("StatefulSet"))))
    assert server.classroom.class_secret_file == PurePosixPath("/run/secrets/class-secret")
    assert (
        option(expanded(container(the("Deployment"))), "--class-secret-file") == "/run/secrets/class-secret"
    )


def test_a_worker_names_itself_by_its_pod() -> None:
    c = container(the("Deployment"))
    settings = worker_settings(expanded(c))
    assert settings.worker.url == f"http://{POD_IP}:{port_named(c, 'http')}" == f"http://{POD_IP}:8100"
    assert settings.worker.id == POD_NAME and settings.listen.host == "0.0.0.0"


def test_the_commands_are_the_compose_files_but_for_the_clusters_names() -> None:
    services = class_compose()
    assert expanded(container(the("StatefulSet"))) == services["classroom"]["command"]
    names = {"--connect": "tcp/teleop-class-router:7447", "--advertise": POD_IP}
    compose_worker = swapped(worker_argv(services["worker"]["command"]), names)
    kube_worker = expanded(container(the("Deployment")))
    at = kube_worker.index("--id")  # a pod's name (compose's containers keep their HOSTNAME-PID)
    assert kube_worker[:at] + kube_worker[at + 2 :] == compose_worker


def test_each_container_has_probes_on_its_own_port_and_requests_within_its_limits() -> None:
    server, worker = container(the("StatefulSet")), container(the("Deployment"))
    for c, settings in (
        (server, server_settings(expanded(server))),
        (worker, worker_settings(expanded(worker))),
    ):
        port = settings.listen.port
        probes = [c[k] for k in ("startupProbe", "readinessProbe", "livenessProbe")]
        for probe in probes:
            get = probe["httpGet"]
            assert get["path"] == "/api/health" and port_named(c, get["port"]) == port, probe
            (host,) = [h["value"] for h in get["httpHeaders"] if h["name"] == "Host"]
            assert host in settings.listen.accepted_hosts  # a name it answers, whatever the pod's address
        resources = c["resources"]
        for what in ("cpu", "memory"):
            assert quantity(resources["requests"][what]) <= quantity(resources["limits"][what]), c["name"]
        security = c["securityContext"]
        assert security["allowPrivilegeEscalation"] is False and security["capabilities"]["drop"] == ["ALL"]
