"""The one list of services, and which service answers which request.

A service's messages live in ``proto/<service>.py`` (STYLE.md), and each request names its reply through
``proto.common.Request[Reply]``; so the service of a request is the name of its proto module and its reply
type is on the class, with no table to keep in step. The handlers of a service are its ``CONTRACT``
(``services/<service>/handlers.py``), imported only by whoever runs the service in this process (the
embedded bus, the in-process backend): a client of a remote bus never imports the services' code.
tests/unit/orchestrator/test_registry.py checks that every contract answers exactly its proto module's
requests with the declared replies.
"""

from __future__ import annotations

import importlib
from typing import Any

from wana.bus.service import Contract

SERVICES: tuple[str, ...] = ("nlp", "retrieval", "motion", "optimizer", "social", "render")

_contracts: dict[str, Contract] = {}


def service_of(request_type: type[Any]) -> str:
    """The service that answers a request type (the name of the proto module it is defined in).

    Raises:
        KeyError: the request type belongs to no service (e.g. the bus's own echo request).
    """
    module = request_type.__module__
    service = module.rsplit(".", 1)[-1]
    if not module.startswith("proto.") or service not in SERVICES:
        raise KeyError(f"{request_type.__name__} ({module}) is not a request of any of {', '.join(SERVICES)}")
    return service


def contract(service: str) -> Contract:
    """The request type -> handler table of a service (imports its handlers: spaCy, torch, ...)."""
    if service not in SERVICES:
        raise KeyError(f"unknown service {service!r}; choose from {', '.join(SERVICES)}")
    found = _contracts.get(service)
    if found is None:
        if service == "optimizer":
            from wana.compose import compose

            compose()  # what the optimiser needs of another service (motion re-synthesis) is wired in here
        found = _contracts[service] = importlib.import_module(f"services.{service}.handlers").CONTRACT
    return found
