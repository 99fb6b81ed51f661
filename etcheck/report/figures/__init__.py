"""Report figures, each drawn once as an inline PNG at print resolution (the same bytes in the HTML and the
PDF), one module per report kind (:mod:`.check`, :mod:`.sweep`, :mod:`.diagram`, :mod:`.orbit`,
:mod:`.uncertainty`); :mod:`.common` owns the matplotlib set-up and the drawing."""
