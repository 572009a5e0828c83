"""Tools that rebuild what the repository ships; run from a checkout, never imported by the runtime."""
