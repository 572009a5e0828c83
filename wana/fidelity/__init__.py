"""Story fidelity: does the animation show what each sentence says? (DESIGN §2, "What the animation must show")

Per-sentence checks from the parse (what a sentence asks) and the computed animation (what the pipeline
made): objects and relations, actions done at their targets, bodies supported, clear of furniture and of
each other, moving continuously, entering properly. Camera and command checks come from the render service
and join in through `verdicts(..., extra=...)`. Imports proto/ and wana/ only.
"""

from wana.fidelity.story import story_checks, verdicts

__all__ = ["story_checks", "verdicts"]
