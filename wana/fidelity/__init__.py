"""Story fidelity: does the animation show what each sentence says? (DESIGN §2, "What the animation must show")

Per-sentence checks from the parse (what a sentence asks) and the computed animation (what the pipeline
made): objects and relations, actions done at their targets, bodies supported, clear of furniture and of
each other, moving continuously, entering properly. Camera and command checks come from the render service
and join in through `verdicts(..., extra=...)`. Imports proto/ and wana/ only.

The checks judge what a viewer sees (eval/agreement.py measures how often they agree with a person looking
at the frames): depth into furniture on the objects' own parts and only as deep and as long as shows, held
objects and handovers by their prop tracks, "behind the door" on the object's front, the actor the text names.
"""

from wana.fidelity.story import story_checks, verdicts

__all__ = ["story_checks", "verdicts"]
