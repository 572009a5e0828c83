"""wana — Write-An-Animation: text a person writes and edits, turned into a 3D animation."""

__version__ = "0.1.0"
