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


def _docs(name: str) -> dict[str, dict]:
    return {d["kind"]: d for d in yaml.safe_load_all((DEPLOY / "k8s" / name).read_text()) if d}


def test_the_gateway_is_one_replica_recreated_with_its_sessions_on_a_claimed_volume():
    from services.gateway.app import build_parser as serve_parser

    docs = _docs("gateway.yaml")
    spec = docs["Deployment"]["spec"]
    assert spec["replicas"] == 1 and spec["strategy"]["type"] == "Recreate"  # one SQLite writer
    pod = spec["template"]["spec"]
    (container,) = pod["containers"]
    args = serve_parser().parse_args(container["args"][1:])
    assert container["args"][0] == "serve" and args.broker == "tcp://wana-broker:5555"
    claims = {
        v["name"]: v["persistentVolumeClaim"]["claimName"]
        for v in pod["volumes"]
        if "persistentVolumeClaim" in v
    }
    assert claims == {"sessions": docs["PersistentVolumeClaim"]["metadata"]["name"]}
    mount = next(m["mountPath"] for m in container["volumeMounts"] if m["name"] == "sessions")
    assert Path(args.db).parent == Path(mount)
    env = {e["name"]: e for e in container["env"]}
    assert env["WANA_TOKEN"]["valueFrom"]["secretKeyRef"]["name"] == "wana-gateway-token"
    assert docs["Service"]["spec"]["ports"][0]["port"] == args.port


def test_the_gateway_probe_asks_a_path_the_gateway_serves_on_its_port():
    from services.gateway.app import create_app
    from services.gateway.settings import Settings

    (container,) = _docs("gateway.yaml")["Deployment"]["spec"]["template"]["spec"]["containers"]
    probe = container["readinessProbe"]["httpGet"]
    ports = {p["name"]: p["containerPort"] for p in container["ports"]}
    assert ports[probe["port"]] == int(container["args"][container["args"].index("--port") + 1])
    paths = {getattr(r, "path", "") for r in create_app(Settings()).routes}
    assert probe["path"] in paths and "/metrics" in paths


def test_the_exporter_reads_the_broker_with_the_client_keys_and_serves_the_metric_the_hpas_read():
    from wana.metrics import build_parser as metrics_parser

    docs = _docs("metrics.yaml")
    (container,) = docs["Deployment"]["spec"]["template"]["spec"]["containers"]
    assert container["args"][0] == "metrics"
    args = metrics_parser().parse_args(container["args"][1:])
    assert args.broker == "tcp://wana-broker:5555" and args.host == "0.0.0.0"
    assert docs["Service"]["spec"]["ports"][0]["targetPort"] == container["ports"][0]["name"]
    keys = {
        i["key"]
        for v in docs["Deployment"]["spec"]["template"]["spec"]["volumes"]
        for i in v["secret"]["items"]
    }
    assert keys == {"broker.key", "client.key", "client.key_secret"}
    rules = yaml.safe_load(docs["ConfigMap"]["data"]["config.yaml"])["externalRules"]
    served = {rule["name"]["as"] for rule in rules}
    for service in SERVICES:
        hpa = _docs(f"worker-{service}.yaml")["HorizontalPodAutoscaler"]["spec"]
        assert hpa["metrics"][0]["external"]["metric"]["name"] in served


def test_compose_runs_the_exporter_and_keeps_the_gateway_sessions_on_a_volume():
    from services.gateway.app import build_parser as serve_parser
    from wana.metrics import build_parser as metrics_parser

    compose = yaml.safe_load((DEPLOY / "compose.yaml").read_text())
    gateway = compose["services"]["gateway"]
    db = serve_parser().parse_args(gateway["command"][1:]).db
    volume, mount = gateway["volumes"][0].split(":")
    assert volume in compose["volumes"] and Path(db).parent == Path(mount)
    assert "/healthz" in " ".join(gateway["healthcheck"]["test"])
    metrics = compose["services"]["metrics"]["command"]
    assert metrics[0] == "metrics" and metrics_parser().parse_args(metrics[1:]).broker == "tcp://broker:5555"
