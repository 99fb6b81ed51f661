"""Report figures as deterministic inline SVG, one module per report kind (:mod:`.check`,
:mod:`.sweep`, :mod:`.diagram`); :mod:`.common` owns the matplotlib set-up."""
