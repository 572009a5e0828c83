"""Authoring of committed data: the action clips (author_actions + action_specs_*) and the VAD table (build_vad).

These run from a checkout (python -m tools.authoring.author_actions) and write under assets/; the
runtime reads only the files they write, so they may use several services (they are no service).
"""
