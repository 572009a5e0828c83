"""wana's typed messages. Imports only msgspec and the standard library.

See proto/PROTOCOL.md for the authoritative description of frames, commands and messages.
"""

SCHEMA_VERSION = 1
