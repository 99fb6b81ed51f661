"""Margins and how sure they are: answers -> margins and verdicts, the margins under the
other attachment of the ends, and the uncertainty study (elasticities, P(margin < required))."""
