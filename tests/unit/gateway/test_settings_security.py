"""Settings from the environment, the bind/token rule, the token and Origin checks."""

from __future__ import annotations

from pathlib import Path

import pytest
from starlette.datastructures import Headers

from services.gateway.security import SESSION_COOKIE, cookie_ok, origin_ok, session_cookie, token_ok
from services.gateway.settings import Settings, is_loopback, parse_services


def test_settings_are_read_from_wana_environment_variables(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("WANA_PORT", "9000")
    monkeypatch.setenv("WANA_DB", "/tmp/x.sqlite")
    monkeypatch.setenv("WANA_TOKEN", "secret")
    monkeypatch.setenv("WANA_ALLOWED_ORIGINS", "http://localhost:5173/, http://a.example")
    s = Settings.from_env()
    assert (s.port, s.db, s.token) == (9000, Path("/tmp/x.sqlite"), "secret")
    assert s.allowed_origins == ("http://localhost:5173", "http://a.example")


def test_command_line_overrides_win_over_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("WANA_PORT", "9000")
    assert Settings.from_env(port=1234, host=None).port == 1234


def test_a_bad_integer_in_the_environment_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("WANA_PORT", "eighty")
    with pytest.raises(ValueError, match="WANA_PORT"):
        Settings.from_env()


@pytest.mark.parametrize("host", ["127.0.0.1", "127.1.2.3", "::1", "localhost"])
def test_loopback_hosts_need_no_token(host: str) -> None:
    assert is_loopback(host)
    Settings(host=host).check()


@pytest.mark.parametrize("host", ["0.0.0.0", "192.168.1.5", "::", "example.com"])
def test_binding_off_loopback_without_a_token_is_refused(host: str) -> None:
    assert not is_loopback(host)
    with pytest.raises(ValueError, match="token"):
        Settings(host=host).check()
    Settings(host=host, token="t").check()


def test_token_is_accepted_as_bearer_header_or_a_valid_session_cookie_never_from_the_url() -> None:
    assert token_ok("", Headers({}))
    assert token_ok("abc", Headers({"authorization": "Bearer abc"}))
    assert not token_ok("abc", Headers({}))
    assert not token_ok("abc", Headers({"authorization": "Bearer abd"}))
    fresh = session_cookie("abc", ttl_s=60)
    assert token_ok("abc", Headers({}), {SESSION_COOKIE: fresh})
    assert not token_ok("other", Headers({}), {SESSION_COOKIE: fresh})  # signed with another token
    assert not token_ok(
        "abc", Headers({}), {SESSION_COOKIE: session_cookie("abc", ttl_s=60, now=0)}
    )  # expired
    expiry, signature = fresh.split(".")
    assert not cookie_ok("abc", f"{int(expiry) + 3600}.{signature}")  # a forged longer life
    assert not cookie_ok("abc", "garbage")


def test_origin_must_be_the_gateways_own_loopback_origin_or_explicitly_allowed() -> None:
    host = {"host": "127.0.0.1:8765"}
    assert origin_ok(Headers(host), (), 8765)  # no Origin: not a browser
    assert origin_ok(Headers({**host, "origin": "http://127.0.0.1:8765"}), (), 8765)
    assert origin_ok(Headers({"host": "localhost:8765", "origin": "http://localhost:8765"}), (), 8765)
    assert not origin_ok(Headers({**host, "origin": "http://127.0.0.1:9999"}), (), 8765)  # another port
    assert not origin_ok(Headers({**host, "origin": "http://evil.example"}), (), 8765)
    assert not origin_ok(Headers({**host, "origin": "null"}), (), 8765)
    assert origin_ok(Headers({**host, "origin": "http://localhost:5173"}), ("http://localhost:5173",), 8765)


def test_origin_equal_to_host_is_not_enough_against_dns_rebinding() -> None:
    rebound = {"host": "evil.example:8765", "origin": "http://evil.example:8765"}  # resolves to 127.0.0.1
    assert not origin_ok(Headers(rebound), (), 8765)


def test_services_are_a_checked_comma_list(monkeypatch: pytest.MonkeyPatch) -> None:
    assert Settings.from_env().services is None
    monkeypatch.setenv("WANA_SERVICES", "nlp, retrieval")
    assert Settings.from_env().services == ("nlp", "retrieval")
    monkeypatch.setenv("WANA_SERVICES", "")
    assert Settings.from_env().services == ()
    with pytest.raises(ValueError, match="unknown service"):
        parse_services("nlp,telepathy")
