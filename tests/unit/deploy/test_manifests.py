"""The deployment files start every service the same way the CLI does."""

from pathlib import Path

import yaml

from services.orchestrator.registry import SERVICES
from wana.cli import build_parser

DEPLOY = Path(__file__).resolve().parents[3] / "deploy"


def test_compose_runs_the_broker_and_one_container_per_service():
    compose = yaml.safe_load((DEPLOY / "compose.yaml").read_text())["services"]
    assert compose["broker"]["command"][:2] == ["broker", "--bind"]
    for service in SERVICES:
        assert compose[service]["command"] == ["worker", service, "--connect", "tcp://broker:5555"]


def test_every_worker_type_is_a_scaled_deployment_whose_args_the_cli_accepts():
    parser = build_parser()
    for service in SERVICES:
        docs = list(yaml.safe_load_all((DEPLOY / "k8s" / f"worker-{service}.yaml").read_text()))
        kinds = {d["kind"]: d for d in docs}
        assert set(kinds) == {"Deployment", "HorizontalPodAutoscaler"}
        args = kinds["Deployment"]["spec"]["template"]["spec"]["containers"][0]["args"]
        parsed = parser.parse_args(args)
        assert parsed.service == service and parsed.connect == "tcp://wana-broker:5555"
        hpa = kinds["HorizontalPodAutoscaler"]["spec"]
        assert hpa["scaleTargetRef"]["name"] == kinds["Deployment"]["metadata"]["name"]
        assert hpa["metrics"][0]["external"]["metric"]["selector"]["matchLabels"]["service"] == service


def test_the_broker_is_a_statefulset_behind_a_service_on_the_bus_port():
    docs = {d["kind"]: d for d in yaml.safe_load_all((DEPLOY / "k8s" / "broker.yaml").read_text())}
    assert docs["StatefulSet"]["spec"]["template"]["spec"]["containers"][0]["args"] == [
        "broker",
        "--bind",
        "tcp://0.0.0.0:5555",
        "--keys",
        "/etc/wana/bus-keys",
    ]
    assert docs["Service"]["spec"]["ports"][0]["port"] == 5555


def test_the_compose_gateway_uses_the_broker_through_options_wana_serve_accepts():
    from services.gateway.app import build_parser as serve_parser

    compose = yaml.safe_load((DEPLOY / "compose.yaml").read_text())["services"]
    command = compose["gateway"]["command"]
    assert command[0] == "serve"
    args = serve_parser().parse_args(command[1:])
    assert args.broker == "tcp://broker:5555" and args.host == "0.0.0.0"


def test_the_deployment_has_a_worker_for_exactly_the_registered_services():
    compose = yaml.safe_load((DEPLOY / "compose.yaml").read_text())["services"]
    workers = {name for name, spec in compose.items() if spec.get("command", [""])[0] == "worker"}
    assert workers == set(SERVICES)
    manifests = {p.stem.removeprefix("worker-") for p in (DEPLOY / "k8s").glob("worker-*.yaml")}
    assert manifests == set(SERVICES)
