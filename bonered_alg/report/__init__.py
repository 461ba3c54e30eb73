"""LaTeX derivation reports."""
