"""Contract tests: each service's real worker on a real socket, every reply checked against its contract."""
