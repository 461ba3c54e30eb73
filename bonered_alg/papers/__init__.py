"""The papers' printed equations and the verdicts of the derivations against them, one
module per paper (``verify(derivation, generated, studies) -> [Verdict]``)."""
