"""An authenticated bus: CURVE + ZAP admit only allow-listed keys, each in its role; open binds are refused."""

from __future__ import annotations

import logging
import threading
from pathlib import Path

import msgspec
import pytest
import zmq
import zmq.auth

from proto.bus import ErrorFrame, ReadyFrame, RequestFrame, StatsFrame
from proto.common import ErrorReply
from wana import cli
from wana.bus import curve
from wana.bus.broker import Broker
from wana.bus.client import BusError, Client
from wana.bus.worker import Worker

HEARTBEAT_S = 0.1


def _echo(payload: bytes) -> bytes:
    return b"echo:" + payload


@pytest.fixture
def keys(tmp_path) -> Path:
    root = tmp_path / "keys"
    curve.new_keys(root, services=("echo",))
    return root


@pytest.fixture
def secure_broker(keys):
    broker = Broker("tcp://127.0.0.1:*", keys=keys, heartbeat_s=HEARTBEAT_S)
    broker.start_thread()
    yield broker
    broker.close()


@pytest.fixture
def keyed_worker(secure_broker, keys):
    stop = threading.Event()
    worker = Worker("echo", _echo, secure_broker.endpoints[0], keys=keys, heartbeat_s=HEARTBEAT_S)
    thread = threading.Thread(target=worker.run, args=(stop,), daemon=True)
    thread.start()
    yield worker
    stop.set()
    thread.join(timeout=5)


def _curve_dealer(url: str, keys: Path, pair: str) -> zmq.Socket:
    """A raw DEALER speaking CURVE with ``keys/<pair>.key_secret``."""
    sock = zmq.Context.instance().socket(zmq.DEALER)
    sock.setsockopt(zmq.LINGER, 0)
    server, _ = zmq.auth.load_certificate(str(keys / "broker.key"))
    public, secret = zmq.auth.load_certificate(str(keys / f"{pair}.key_secret"))
    sock.curve_serverkey, sock.curve_publickey, sock.curve_secretkey = server, public, secret
    sock.connect(url)
    return sock


def _error_code(sock: zmq.Socket) -> str:
    assert sock.poll(5000), "no answer"
    frames = sock.recv_multipart()
    assert isinstance(msgspec.msgpack.decode(frames[0], type=ErrorFrame), ErrorFrame)
    return msgspec.msgpack.decode(frames[1], type=ErrorReply).code


def test_allow_listed_keys_run_a_job_over_curve(secure_broker, keys, keyed_worker):
    with Client(secure_broker.endpoints[0], keys=keys, heartbeat_s=HEARTBEAT_S) as client:
        assert client.request("echo", b"secret", deadline_s=10) == b"echo:secret"


def test_a_peer_without_keys_or_with_unknown_keys_gets_nothing_through(
    secure_broker, keys, keyed_worker, tmp_path
):
    url = secure_broker.endpoints[0]
    with Client(url, keys=None, heartbeat_s=HEARTBEAT_S) as plain:  # no CURVE at all
        with pytest.raises(BusError) as err:
            plain.request("echo", b"x", deadline_s=0.5)
        assert err.value.code == "E006"  # the local deadline: the broker never heard it
    stranger = tmp_path / "stranger"
    curve.new_keys(stranger)
    (stranger / "broker.key").write_bytes((keys / "broker.key").read_bytes())  # knows the broker only
    with Client(url, keys=stranger, heartbeat_s=HEARTBEAT_S) as outsider:
        with pytest.raises(BusError, match="E006"):
            outsider.request("echo", b"x", deadline_s=0.5)
    assert secure_broker.stats().completed == 0


def test_a_worker_key_may_not_send_requests_or_read_stats(secure_broker, keys):
    sock = _curve_dealer(secure_broker.endpoints[0], keys, "worker")
    try:
        sock.send_multipart([msgspec.msgpack.encode(RequestFrame("echo", "j", "k", 0, 1000)), b"x"])
        assert _error_code(sock) == "E013"
        sock.send(msgspec.msgpack.encode(StatsFrame()))
        assert _error_code(sock) == "E013"
    finally:
        sock.close(0)


def test_a_client_key_may_not_register_as_a_worker(secure_broker, keys):
    sock = _curve_dealer(secure_broker.endpoints[0], keys, "client")
    try:
        sock.send(msgspec.msgpack.encode(ReadyFrame("echo")))
        assert _error_code(sock) == "E013"
        assert "echo" not in secure_broker.stats().services
    finally:
        sock.close(0)


def test_a_worker_key_allowed_for_one_service_may_not_serve_another(secure_broker, keys):
    sock = _curve_dealer(secure_broker.endpoints[0], keys, "worker")
    try:
        sock.send(msgspec.msgpack.encode(ReadyFrame("render")))
        assert _error_code(sock) == "E013"
        assert "render" not in secure_broker.stats().services
    finally:
        sock.close(0)


@pytest.mark.parametrize("url", ["tcp://0.0.0.0:*", "tcp://*:*"])
def test_an_open_bind_without_keys_is_refused_with_what_to_do(url):
    with pytest.raises(curve.InsecureBind, match="wana keys new"):
        Broker(url)


def test_insecure_binds_an_open_endpoint_and_warns(caplog):
    with caplog.at_level(logging.WARNING, logger="wana.bus.curve"):
        broker = Broker("tcp://0.0.0.0:*", insecure=True)
    broker.close()
    assert "WITHOUT keys" in caplog.text


def test_loopback_ipc_and_inproc_need_no_keys(tmp_path):
    for url in ("tcp://127.0.0.1:*", f"ipc://{tmp_path}/b.sock", "inproc://no-keys-needed"):
        Broker(url).close()


def test_wana_keys_new_writes_pairs_and_allow_lists_and_the_broker_cli_refuses_an_open_bind(tmp_path, capsys):
    root = tmp_path / "k"
    assert cli.main(["keys", "new", str(root), "--service", "nlp"]) == 0
    for name in ("broker.key", "client.key_secret", "worker.key_secret", "allow/clients/client.key"):
        assert (root / name).is_file()
    assert (root / "allow/workers/nlp/worker.key").is_file()
    assert (root / "worker.key_secret").stat().st_mode & 0o077 == 0
    assert cli.main(["broker", "--bind", "tcp://0.0.0.0:0"]) == 2
    assert "without CURVE keys" in capsys.readouterr().err


def test_deployments_take_the_bus_keys_from_secrets_and_the_image_never_holds_them():
    import yaml

    deploy = Path(__file__).resolve().parents[3] / "deploy"
    for path in sorted((deploy / "k8s").glob("*.yaml")):
        pod = next(
            d for d in yaml.safe_load_all(path.read_text()) if d["kind"] in ("StatefulSet", "Deployment")
        )
        volumes = {v["name"]: v for v in pod["spec"]["template"]["spec"]["volumes"]}
        assert volumes["bus-keys"]["secret"]["secretName"] == "wana-bus-keys", path.name
        files = {item["key"] for item in volumes["bus-keys"]["secret"]["items"]}
        if "broker" in path.name:
            assert "broker.key_secret" in files and "worker.key_secret" not in files
        elif path.name.startswith("worker-"):  # a worker never holds the broker's secret
            assert files == {"broker.key", "worker.key", "worker.key_secret"}, path.name
        else:  # the bus's clients (gateway, metrics exporter): the client pair only
            assert files == {"broker.key", "client.key", "client.key_secret"}, path.name
    compose = yaml.safe_load((deploy / "compose.yaml").read_text())
    assert all(Path(s["file"]).parts[:2] == ("..", "keys") for s in compose["secrets"].values())
    ignored = (deploy / "Dockerfile.dockerignore").read_text().split()
    assert "keys/" in ignored and "**/*.key_secret" in ignored


def test_a_peer_re_using_another_clients_routing_id_never_gets_its_reply(secure_broker, keys, keyed_worker):
    url = secure_broker.endpoints[0]
    victim = Client(url, keys=keys, heartbeat_s=HEARTBEAT_S)
    try:
        victim_id = victim._socket.getsockopt(zmq.ROUTING_ID)
        job_id = victim.submit("echo", b"for the victim", deadline_s=10)
        thief = zmq.Context.instance().socket(zmq.DEALER)
        thief.setsockopt(zmq.LINGER, 0)
        thief.setsockopt(zmq.ROUTING_ID, victim_id)
        server, _ = zmq.auth.load_certificate(str(keys / "broker.key"))
        public, secret = zmq.auth.load_certificate(str(keys / "client.key_secret"))
        thief.curve_serverkey, thief.curve_publickey, thief.curve_secretkey = server, public, secret
        thief.connect(url)
        try:
            assert victim.result(job_id, timeout=10) == b"echo:for the victim"
            assert victim.request("echo", b"again", deadline_s=10) == b"echo:again"
            assert not thief.poll(300)  # nothing of the victim's reached the thief
        finally:
            thief.close(0)
    finally:
        victim.close()
